// The integrate group's course side: one of the student's integrators on small systems whose
// derivatives come from the course-form force code here (never the student's forces).
// Included into probe_driver.cpp's one translation unit (driver_support.h says why), whose dispatch
// calls its function by the group's name.
#pragma once
#include "grader/driver/driver_support.h"

namespace {

// ---- Course-form reference derivatives for the integrator probes (our code, not the student's).
struct MiniWorld {
  Particles cloth, spheres;
  std::vector<Spring> springs;
  std::vector<float> radius;
  float spring_coef = 0, damper_coef = 0, viscous = 0;
  Eigen::Vector4f gravity = Eigen::Vector4f::Zero();
  bool sphere_gravity = false, cloth_contact = false, sphere_contact = false;
  float e_cloth = 0, e_sphere = 0, correction = 0;  // the request's (the edition's record)
};

void externalForce(Particles& p, const Eigen::Vector4f& gravity, float viscous) {
  // the course's expression, written once for clothref and this driver alike
  for (int i = 0; i < p.getCapacity(); ++i)
    clothref::formula::externalAcceleration(p.velocity(i).data(), p.mass(i), p.inverseMass(i),
                                            gravity.data(), viscous, p.acceleration(i).data());
}

void springForce(MiniWorld& w) {
  Particles& p = w.cloth;
  for (const Spring& spring : w.springs) {
    const int s = static_cast<int>(spring.startParticleIndex());
    const int e = static_cast<int>(spring.endParticleIndex());
    // the course's expression, written once for clothref and this driver alike
    Eigen::Vector4f force;
    clothref::formula::springForce(p.position(s).data(), p.position(e).data(), p.velocity(s).data(),
                                   p.velocity(e).data(), spring.length(), w.spring_coef,
                                   w.damper_coef, force.data());
    p.acceleration(s) -= force * p.inverseMass(s);
    p.acceleration(e) += force * p.inverseMass(e);
  }
}

void contact(Particles& a, int i, Particles& b, int j, float reach, float e, float correction) {
  clothref::formula::resolveContact(a.position(i).data(), a.velocity(i).data(), a.inverseMass(i),
                                    b.position(j).data(), b.velocity(j).data(), b.inverseMass(j),
                                    reach, e, correction);
}

void simulate(MiniWorld& w) {
  externalForce(w.cloth, w.gravity, w.viscous);
  if (w.sphere_gravity)
    externalForce(w.spheres, w.gravity, w.viscous);
  else
    w.spheres.acceleration().setZero();
  springForce(w);
  if (w.cloth_contact)
    for (int i = 0; i < w.spheres.getCapacity(); ++i)
      for (int j = 0; j < w.cloth.getCapacity(); ++j)
        contact(w.spheres, i, w.cloth, j, w.radius[static_cast<size_t>(i)], w.e_cloth,
                w.correction);
  if (w.sphere_contact)
    for (int i = 0; i < w.spheres.getCapacity(); ++i)
      for (int j = i + 1; j < w.spheres.getCapacity(); ++j)
        contact(w.spheres, i, w.spheres, j,
                w.radius[static_cast<size_t>(i)] + w.radius[static_cast<size_t>(j)], w.e_sphere,
                w.correction);
}

void probeIntegrate(const ProbeMessage& in, ProbeMessage& out) {
  const Integrator& integrator = integratorFor(in.scalarInt(key::kMethod));
  const int cases = static_cast<int>(in.scalarInt(key::kCases));
  for (int k = 0; k < cases; ++k) {
    const auto& clothMass = in.f(perCase(key::kClothMass, k));
    const auto& sphereMass = in.f(perCase(key::kSphereMass, k));
    MiniWorld w{Particles(static_cast<int>(clothMass.size())),
                Particles(static_cast<int>(sphereMass.size())),
                {},
                {}};
    load(w.cloth.position(), in.f(perCase(key::kClothPos, k)));
    load(w.cloth.velocity(), in.f(perCase(key::kClothVel, k)));
    loadMass(w.cloth, clothMass);
    load(w.spheres.position(), in.f(perCase(key::kSpherePos, k)));
    load(w.spheres.velocity(), in.f(perCase(key::kSphereVel, k)));
    loadMass(w.spheres, sphereMass);
    w.springs = springsFrom(in, k);
    w.radius = in.f(perCase(key::kSphereRadius, k));
    // ks, kd, viscous, gx, gy, gz, e_cloth, e_sphere, correction
    const auto& params = in.f(perCase(key::kParams, k));
    w.spring_coef = params.at(0);
    w.damper_coef = params.at(1);
    w.viscous = params.at(2);
    w.gravity = Eigen::Vector4f(params.at(3), params.at(4), params.at(5), 0);
    w.e_cloth = params.at(6);
    w.e_sphere = params.at(7);
    w.correction = params.at(8);
    const auto& flags =
        in.i(perCase(key::kFlags, k));  // sphere gravity, cloth contact, sphere contact
    w.sphere_gravity = flags.at(0) != 0;
    w.cloth_contact = flags.at(1) != 0;
    w.sphere_contact = flags.at(2) != 0;
    const float dt = in.scalar(perCase(key::kDt, k));
    const std::int64_t steps = in.scalarInt(perCase(key::kSteps, k), 1);
    const std::int64_t stride = in.scalarInt(perCase(key::kStride, k), 0);
    std::int64_t calls = 0;
    std::vector<Particles*> bodies{&w.cloth, &w.spheres};
    // The stage record (a contact-free case): every state handed to simulateOneStep() and the
    // accelerations it produced, in call order; cloth and spheres positions, velocities, a.
    const bool record = in.scalarInt(perCase(key::kRecordStages, k), 0) != 0;
    std::vector<float> stages[6];
    const auto append = [](std::vector<float>& to, const std::vector<float>& values) {
      to.insert(to.end(), values.begin(), values.end());
    };
    std::function<void(void)> simulateOneStep = [&] {
      ++calls;
      const bool keep = record && calls <= probe::key::kMaxStageRecords;
      if (keep) {
        append(stages[0], save(w.cloth.position()));
        append(stages[1], save(w.cloth.velocity()));
        append(stages[3], save(w.spheres.position()));
        append(stages[4], save(w.spheres.velocity()));
      }
      simulate(w);
      if (keep) {
        append(stages[2], save(w.cloth.acceleration()));
        append(stages[5], save(w.spheres.acceleration()));
      }
    };
    std::vector<float> trajectory;
    float dtAfter = dt;
    for (std::int64_t step = 0; step < steps; ++step) {
      deltaTime = dt;  // a student's integrate may change it; each step starts from the probe's
      simulate(w);
      if (record && step == 0) {
        out.floats[perCase(key::kStartClothPos, k)] = save(w.cloth.position());
        out.floats[perCase(key::kStartClothVel, k)] = save(w.cloth.velocity());
        out.floats[perCase(key::kStartClothAcc, k)] = save(w.cloth.acceleration());
        out.floats[perCase(key::kStartSpherePos, k)] = save(w.spheres.position());
        out.floats[perCase(key::kStartSphereVel, k)] = save(w.spheres.velocity());
        out.floats[perCase(key::kStartSphereAcc, k)] = save(w.spheres.acceleration());
      }
      // the first step only: a stub that reads an uninitialised local does so there, and its
      // answers then differ (a fill per step cost a third more of the probe's CPU)
      if (step == 0) fillStack();
      integrator.integrate(bodies, simulateOneStep);
      if (step == 0) dtAfter = deltaTime;
      if (stride > 0 && (step + 1) % stride == 0) {
        const auto x = save(w.cloth.position());
        trajectory.insert(trajectory.end(), x.begin(), x.end());
      }
    }
    out.floats[perCase(key::kClothPos, k)] = save(w.cloth.position());
    out.floats[perCase(key::kClothVel, k)] = save(w.cloth.velocity());
    out.floats[perCase(key::kSpherePos, k)] = save(w.spheres.position());
    out.floats[perCase(key::kSphereVel, k)] = save(w.spheres.velocity());
    out.floats[perCase(key::kDtAfter, k)] = {dtAfter};
    out.ints[perCase(key::kCalls, k)] = {calls};
    out.floats[perCase(key::kTrajectory, k)] = trajectory;
    if (record) {
      const char* names[6] = {key::kEvalClothPos,  key::kEvalClothVel,  key::kEvalClothAcc,
                              key::kEvalSpherePos, key::kEvalSphereVel, key::kEvalSphereAcc};
      for (int r = 0; r < 6; ++r) out.floats[perCase(names[r], k)] = stages[r];
    }
  }
}

}  // namespace
