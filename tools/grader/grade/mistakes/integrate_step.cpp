// The course's step with its lines switchable (integrate_step.h).
#include "grader/grade/mistakes/integrate_step.h"

#include <cmath>
#include <functional>

namespace clothref::grader::integrators {
namespace {

template <typename T>
bool take(T& into, const T& from, const T& course) {
  if (from == course || from == into) return true;
  if (into != course) return false;
  into = from;
  return true;
}
}  // namespace

bool merge(Lines& into, const Lines& from) {
  const Lines c;
  return take(into.backup_follows_live, from.backup_follows_live, c.backup_follows_live) &&
         take(into.reevaluates, from.reevaluates, c.reevaluates) &&
         take(into.evaluates_again, from.evaluates_again, c.evaluates_again) &&
         take(into.per_body, from.per_body, c.per_body) &&
         take(into.first_body_only, from.first_body_only, c.first_body_only) &&
         take(into.updates_position, from.updates_position, c.updates_position) &&
         take(into.updates_velocity, from.updates_velocity, c.updates_velocity) &&
         take(into.position_half_acceleration, from.position_half_acceleration,
              c.position_half_acceleration) &&
         take(into.velocity_first, from.velocity_first, c.velocity_first) &&
         take(into.predictor_full_step, from.predictor_full_step, c.predictor_full_step) &&
         take(into.predictor_adds_nothing, from.predictor_adds_nothing, c.predictor_adds_nothing) &&
         take(into.predictor_symplectic, from.predictor_symplectic, c.predictor_symplectic) &&
         take(into.evaluates_before_predictor, from.evaluates_before_predictor,
              c.evaluates_before_predictor) &&
         take(into.corrector_new_velocity, from.corrector_new_velocity, c.corrector_new_velocity) &&
         take(into.corrector_trapezoidal, from.corrector_trapezoidal, c.corrector_trapezoidal) &&
         take(into.corrector_start_velocity, from.corrector_start_velocity,
              c.corrector_start_velocity) &&
         take(into.stage, from.stage, c.stage) &&
         take(into.stage_increment_after_overwrite, from.stage_increment_after_overwrite,
              c.stage_increment_after_overwrite) &&
         take(into.stage_from_current, from.stage_from_current, c.stage_from_current) &&
         take(into.stage_position_from_new_velocity, from.stage_position_from_new_velocity,
              c.stage_position_from_new_velocity) &&
         take(into.stage_position_from_kv, from.stage_position_from_kv, c.stage_position_from_kv) &&
         take(into.result_adds_nothing, from.result_adds_nothing, c.result_adds_nothing) &&
         take(into.result_on_last_stage, from.result_on_last_stage, c.result_on_last_stage) &&
         take(into.result_position_from_kv, from.result_position_from_kv,
              c.result_position_from_kv) &&
         take(into.result_velocity_k4_from_kx, from.result_velocity_k4_from_kx,
              c.result_velocity_k4_from_kx) &&
         take(into.result_first_stage_only, from.result_first_stage_only,
              c.result_first_stage_only) &&
         take(into.result_k4x_after_velocity, from.result_k4x_after_velocity,
              c.result_k4x_after_velocity);
}

namespace {

// The start state of `bodies`: a copy, or with `alias` the live state (what a pointer or
// Eigen::Ref "copy" reads later).
struct Backup {
  Backup(const std::vector<Particles<float>*>& of, bool alias_live)
      : bodies(of), alias(alias_live) {
    for (auto* p : bodies) x0.push_back(p->position), v0.push_back(p->velocity);
  }
  Mat4X<float> x(std::size_t b) const { return alias ? bodies[b]->position : x0[b]; }
  Mat4X<float> v(std::size_t b) const { return alias ? bodies[b]->velocity : v0[b]; }
  const std::vector<Particles<float>*>& bodies;
  bool alias;
  std::vector<Mat4X<float>> x0, v0;
};

// The step sizes of one call: h of every term, the result's h and the result's factor.
struct Sizes {
  float dt, result_dt, result_scale;
};

// `rate` · h · scale, or the course's rate · h when the scale is 1.
Mat4X<float> increment(const Mat4X<float>& rate, float h, float scale) {
  return scale == 1 ? Mat4X<float>(rate * h) : Mat4X<float>((rate * h) * scale);
}

// The course's explicit Euler (core/integrator.cpp's integrateExplicit, line for line).
void explicitEuler(const std::vector<Particles<float>*>& bodies, const Lines& w, const Sizes& z) {
  const float dt = z.dt;
  for (auto* p : bodies) {
    if (w.velocity_first) {
      if (w.updates_velocity) p->velocity += increment(p->acceleration, dt, z.result_scale);
      if (w.updates_position) p->position += increment(p->velocity, dt, z.result_scale);
      continue;
    }
    if (w.position_half_acceleration)
      p->position += p->velocity * dt + p->acceleration * (0.5f * dt * dt);
    else if (w.updates_position)
      p->position += increment(p->velocity, dt, z.result_scale);
    if (w.updates_velocity) p->velocity += increment(p->acceleration, dt, z.result_scale);
  }
}

// The course's predictor-corrector (implicit h = 1, midpoint h = 1/2: core/integrator.cpp's
// predictEvaluateCorrect, operation for operation) for `bodies` only; the others keep their state.
void predictCorrect(System& s, const std::vector<Particles<float>*>& bodies, float h,
                    const Lines& w, const Sizes& z, const std::function<void()>& at_stage) {
  const float dt = z.dt, rdt = z.result_dt, scale = z.result_scale;
  const Backup backup(bodies, w.backup_follows_live);
  std::vector<Mat4X<float>> a0;
  for (auto* p : bodies) a0.push_back(p->acceleration);
  if (w.evaluates_before_predictor) simulate(s);
  if (w.predictor_full_step) h = 1;
  if (w.predictor_adds_nothing) h = 0;
  for (auto* p : bodies) {
    if (w.predictor_symplectic) {
      p->velocity += (p->acceleration * dt) * h;
      p->position += (p->velocity * dt) * h;
    } else {
      p->position += (p->velocity * dt) * h;
      p->velocity += (p->acceleration * dt) * h;
    }
  }
  at_stage();
  if (!w.evaluates_before_predictor) simulate(s);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    auto* p = bodies[b];
    Mat4X<float> x, v;
    if (w.corrector_trapezoidal) {
      const float half = float(0.5 * double(scale));
      v = backup.v(b);
      v += (a0[b] * rdt) * half;
      v += (p->acceleration * rdt) * half;
      x = backup.x(b);
      x += (backup.v0[b] * rdt) * half;
      x += (p->velocity * rdt) * half;
    } else if (w.corrector_new_velocity) {
      v = backup.v(b) + increment(p->acceleration, rdt, scale);
      x = backup.x(b) + increment(v, rdt, scale);
    } else {
      const Mat4X<float>& along = w.corrector_start_velocity ? backup.v0[b] : p->velocity;
      x = backup.x(b) + increment(along, rdt, scale);
      v = backup.v(b) + increment(p->acceleration, rdt, scale);
    }
    p->velocity = w.updates_velocity ? v : backup.v(b);
    p->position = w.updates_position ? x : backup.x(b);
  }
}

// The rational weight of a fitted RK4 result (a small rational: 1/720 steps).
float weight(double w, float scale) {
  return float(double(std::lround(w * 720)) / 720 * double(scale));
}

// The course's RK4 (core/integrator.cpp's integrateRk4, operation for operation) for `bodies`
// only.
void rungeKutta(System& s, const std::vector<Particles<float>*>& bodies, const Lines& w,
                const Sizes& z, const Overlay& o, const std::function<void()>& at_stage) {
  const float dt = z.dt;
  const Backup backup(bodies, w.backup_follows_live);
  // vk, ak: the velocity and acceleration each kx, kv was read from
  std::vector<Mat4X<float>> kx[4], kv[4], vk[4], ak[4];
  const float node[] = {0.5f, 0.5f, 1.0f};  // stage k + 1's time, in h
  for (int k = 0; k < 4; ++k) {
    if (k > 0) simulate(s);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      auto* p = bodies[b];
      if (w.stage_increment_after_overwrite && k > 0)
        p->velocity = backup.v(b) + (p->acceleration * dt) * node[k - 1];
      vk[k].push_back(p->velocity), ak[k].push_back(p->acceleration);
      kx[k].push_back(p->velocity * dt), kv[k].push_back(p->acceleration * dt);
    }
    if (k == 3) break;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const bool current = w.stage_from_current && k > 0;
      const Mat4X<float> x = current ? bodies[b]->position : backup.x(b);
      const Mat4X<float> v = current ? bodies[b]->velocity : backup.v(b);
      bodies[b]->velocity = v + kv[k][b] * w.stage[std::size_t(k)];
      if (w.stage_position_from_new_velocity)
        bodies[b]->position = x + (bodies[b]->velocity * dt) * w.stage[std::size_t(k)];
      else
        bodies[b]->position =
            x + (w.stage_position_from_kv == k ? kv[k][b] : kx[k][b]) * w.stage[std::size_t(k)];
    }
    at_stage();
  }
  // The result's increments at the result's h.
  if (z.result_dt != dt)
    for (int k = 0; k < 4; ++k)
      for (std::size_t b = 0; b < bodies.size(); ++b) {
        kx[k][b] = vk[k][b] * z.result_dt;
        kv[k][b] = ak[k][b] * z.result_dt;
      }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Mat4X<float> x = w.result_on_last_stage ? bodies[b]->position : backup.x(b);
    const Mat4X<float> v = w.result_on_last_stage ? bodies[b]->velocity : backup.v(b);
    if (w.result_first_stage_only) {
      bodies[b]->position = x + kx[0][b];
      bodies[b]->velocity = v + kv[0][b];
      continue;
    }
    const float factor = (w.result_adds_nothing ? 0.0f : 1.0f) * z.result_scale;
    const auto& kxs = w.result_position_from_kv ? kv : kx;
    const Mat4X<float>& kv4 = w.result_velocity_k4_from_kx ? kx[3][b] : kv[3][b];
    Mat4X<float> nv = v + (kv[0][b] + 2.0f * kv[1][b] + 2.0f * kv[2][b] + kv4) / 6.0f * factor;
    // x's k4 read from the live velocity after v was updated: v_new dt
    const Mat4X<float> kx4 =
        w.result_k4x_after_velocity ? Mat4X<float>(nv * z.result_dt) : Mat4X<float>(kxs[3][b]);
    Mat4X<float> nx = x + (kxs[0][b] + 2.0f * kxs[1][b] + 2.0f * kxs[2][b] + kx4) / 6.0f * factor;
    // Fitted weights, term by term (x0 + w1 k1 + ...; a zero weight adds nothing).
    if (!o.weights_x.empty()) {
      nx = x;
      for (std::size_t k = 0; k < 4 && k < o.weights_x.size(); ++k)
        if (o.weights_x[k] != 0) nx += kx[k][b] * weight(o.weights_x[k], z.result_scale);
    }
    if (!o.weights_v.empty()) {
      nv = v;
      for (std::size_t k = 0; k < 4 && k < o.weights_v.size(); ++k)
        if (o.weights_v[k] != 0) nv += kv[k][b] * weight(o.weights_v[k], z.result_scale);
    }
    bodies[b]->position = w.updates_position ? nx : backup.x(b);
    bodies[b]->velocity = w.updates_velocity ? nv : backup.v(b);
  }
}

}  // namespace

void holdStill(const std::vector<Pins>& pinned, const std::vector<int>& spheres, System& s,
               const Mat4X<float>& cloth_x0) {
  for (const Pins& pins : pinned)
    if (pins.cloth_size == s.cloth.particles.size())
      for (int j : pins.particles)
        if (j >= 0 && j < s.cloth.particles.size()) {
          s.cloth.particles.velocity.col(j).setZero();
          if (pins.positions && j < cloth_x0.cols())
            s.cloth.particles.position.col(j) = cloth_x0.col(j);
        }
  for (int j : spheres)
    if (j >= 0 && j < s.spheres.particles.size()) s.spheres.particles.velocity.col(j).setZero();
}

Step linesStep(Method method, const Lines& lines, const Overlay& o) {
  return [method, lines, o](System& s) {
    simulate(s);
    const Mat4X<float> cloth_x0 = s.cloth.particles.position;
    const float dt = o.step == 1 ? s.dt : float(double(s.dt) * o.step);
    const Sizes z{dt, o.result_dt ? float(double(*o.result_dt) * o.step) : dt,
                  float(o.result_step)};
    const std::function<void()> at_stage = [&] {
      if (o.pins_at_stages) holdStill(o.pinned, o.pinned_spheres, s, cloth_x0);
    };
    std::vector<Particles<float>*> bodies{&s.cloth.particles};
    if (!lines.first_body_only) bodies.push_back(&s.spheres.particles);
    if (method == Method::Explicit || !lines.reevaluates) {
      if (lines.evaluates_again) simulate(s);
      explicitEuler(bodies, lines, z);
    } else {
      // A per-body loop: each body alone, later bodies after the earlier ones have moved; the
      // first body uses the derivatives evaluated before integrate(), each later one those of
      // the previous body's last simulateOneStep().
      std::vector<std::vector<Particles<float>*>> groups;
      if (lines.per_body)
        for (auto* p : bodies) groups.push_back({p});
      else
        groups.push_back(bodies);
      for (const auto& group : groups) {
        if (method == Method::Implicit || method == Method::Midpoint)
          predictCorrect(s, group, method == Method::Midpoint ? 0.5f : 1.0f, lines, z, at_stage);
        else
          rungeKutta(s, group, lines, z, o, at_stage);
      }
    }
    // What the fitted overlay lays over the step.
    Particles<float>* both[] = {&s.cloth.particles, &s.spheres.particles};
    for (std::size_t b = 0; b < 2; ++b)
      if (o.velocity_factor[b] != 1) both[b]->velocity *= float(o.velocity_factor[b]);
    holdStill(o.pinned, o.pinned_spheres, s, cloth_x0);
    if (o.dt_after_factor) s.dt = float(double(s.dt) * *o.dt_after_factor);
    if (o.dt_after) s.dt = *o.dt_after;
  };
}

}  // namespace clothref::grader::integrators
