// The probe driver: the child process's main, linked with the student's three object files and
// our framework definitions. It reads one ProbeMessage (the probe group and its inputs) from
// stdin, calls the student's stubs of that group, and writes one ProbeMessage with the outputs to
// fd 3. It never computes a score or a reference result: those live in the grader process.
//
// The groups it serves are the rows of kGroups below, one per name of bridge/probe_keys.h (the
// build fails on a name without a row); a request for another group, or for a method that is not
// one of the course's integrators, is refused: nothing on fd 3, the reason on stderr, exit 70.
#include <unistd.h>

#include <Eigen/Core>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

// std only, the headers of clothref the course side may include (docs/layout.md): the course's
// formulas and the method table
#include "clothref/core/method.h"
#include "clothref/formula/course_formulas.h"
#include "grader/bridge/probe_keys.h"
#include "grader/bridge/probe_protocol.h"

// the course's headers (the stand-in of this edition)
#include "cloth.h"
#include "configs.h"
#include "integrator.h"
#include "particles.h"
#include "sphere.h"

namespace {

using probe::ProbeMessage;
namespace key = probe::key;
namespace group = probe::group;
using key::perCase;

// A request the driver cannot serve (an unknown group or method): main refuses it.
struct BadRequest {
  std::string why;
};

// ---- The stack a student's stub starts on (issue 38: undefined behaviour that neither crashes
// nor varies). A local the stub reads before it writes it (`Eigen::Vector4f force; force += ...`)
// holds what the stack held there, the same bytes in both runs of a probe. So before each call of
// a stub the driver fills the stack below its own frame, where the stub's frame will be, with one
// byte: 0x00, or the byte of probe::kStackFillVariable (0xff in the second run: NaN in every
// float, -1 in every int). A stub that reads such a local answers differently in the two runs
// (undefined-behaviour); one that does not reads none of these bytes and answers the same.
constexpr std::size_t kStackFillBytes = 32 << 10;  // more than a stub's frame of fixed-size Eigen

unsigned char stackFillByte() {
  static const unsigned char byte = [] {
    const char* fill = std::getenv(probe::kStackFillVariable);
    return fill ? static_cast<unsigned char>(std::strtoul(fill, nullptr, 16)) : 0;
  }();
  return byte;
}

// Not inlined, so that its frame lies where the next call's will; the empty asm that reads the
// array keeps the stores (the array is dead after them).
[[gnu::noinline]] void fillStack() {
  unsigned char below[kStackFillBytes];
  std::memset(below, stackFillByte(), sizeof below);
  asm volatile("" : : "r"(below) : "memory");
}

// Copies a 4 x n column-major float array in or out of a Particles matrix.
void load(Eigen::Ref<Eigen::Matrix4Xf> target, const std::vector<float>& values) {
  const long n = std::min<long>(target.cols(), static_cast<long>(values.size() / 4));
  for (long c = 0; c < n; ++c)
    for (int r = 0; r < 4; ++r) target(r, c) = values[static_cast<size_t>(4 * c + r)];
}
std::vector<float> save(const Eigen::Ref<Eigen::Matrix4Xf>& source) {
  return std::vector<float>(source.data(), source.data() + source.size());
}
void loadMass(Particles& particles, const std::vector<float>& masses) {
  for (size_t i = 0; i < masses.size() && i < particles.mass().size(); ++i)
    particles.mass(static_cast<int>(i)) = masses[i];
}

// The spring set sent under the spring keys: once (k < 0) or as case k.
std::vector<Spring> springsFrom(const ProbeMessage& in, int k) {
  const auto name = [k](const char* spring_key) {
    return k < 0 ? std::string(spring_key) : perCase(spring_key, k);
  };
  const auto& start = in.i(name(key::kSpringStart));
  const auto& end = in.i(name(key::kSpringEnd));
  const auto& type = in.i(name(key::kSpringType));
  const auto& rest = in.f(name(key::kSpringRest));
  std::vector<Spring> springs;
  for (size_t s = 0; s < start.size() && s < end.size() && s < rest.size(); ++s)
    springs.emplace_back(
        static_cast<unsigned>(start[s]), static_cast<unsigned>(end[s]), rest[s],
        s < type.size() ? static_cast<Spring::Type>(type[s]) : Spring::Type::STRUCTURAL);
  return springs;
}

void probeSprings(const ProbeMessage&, ProbeMessage& out) {
  fillStack();  // Cloth() calls initializeSpring
  Cloth cloth;
  std::vector<std::int64_t> start, end, type;
  std::vector<float> rest;
  for (const Spring& spring : cloth.springs()) {
    start.push_back(spring.startParticleIndex());
    end.push_back(spring.endParticleIndex());
    type.push_back(static_cast<std::int64_t>(spring.type()));
    rest.push_back(spring.length());
  }
  out.ints[key::kParticlesPerEdge] = {particlesPerEdge};
  out.ints[key::kSpringStart] = start;
  out.ints[key::kSpringEnd] = end;
  out.ints[key::kSpringType] = type;
  out.floats[key::kSpringRest] = rest;
  out.floats[key::kClothPos] = save(cloth.particles().position());
}

void probeForces(const ProbeMessage& in, ProbeMessage& out) {
  Cloth cloth;
  // Our spring set, never the student's: a wrong initializeSpring must not fail the forces.
  cloth.springs() = springsFrom(in, -1);
  springCoef = in.scalar(key::kSpringCoef);
  damperCoef = in.scalar(key::kDamperCoef);
  const int cases = static_cast<int>(in.scalarInt(key::kCases));
  Particles& p = cloth.particles();
  for (int k = 0; k < cases; ++k) {
    load(p.position(), in.f(perCase(key::kClothPos, k)));
    load(p.velocity(), in.f(perCase(key::kClothVel, k)));
    load(p.acceleration(), in.f(perCase(key::kClothAcc, k)));
    loadMass(p, in.f(perCase(key::kClothMass, k)));
    fillStack();
    cloth.computeSpringForce();
    out.floats[perCase(key::kClothAcc, k)] = save(p.acceleration());
  }
}

// Both collision groups: three spheres added once (the singleton persists), then every case
// restores the whole state before the call, as the course's main restores its backups.
void collide(const ProbeMessage& in, ProbeMessage& out, bool sphereSphere) {
  Cloth cloth;
  Spheres& spheres = Spheres::initSpheres();
  const auto& radii = in.f(key::kSphereRadius);
  for (size_t s = 0; s < radii.size(); ++s)
    spheres.addSphere(Eigen::Vector4f(100.0f * float(s + 1), 100, 0, 1), radii[s]);
  const int cases = static_cast<int>(in.scalarInt(key::kCases));
  Particles& c = cloth.particles();
  Particles& s = spheres.particles();
  // addSphere grows the capacity by doubling and leaves the new columns unset (the course's
  // resize): the spare one is parked far away at rest, so that no answer holds bytes nobody set
  // (the two runs of a probe must agree to the bit) and a loop over the capacity meets nothing.
  for (int k = static_cast<int>(radii.size()); k < s.getCapacity(); ++k) {
    s.position(k) = Eigen::Vector4f(1000.0f * float(k + 1), 1000, 0, 1);
    s.velocity(k).setZero();
    s.acceleration(k).setZero();
  }
  for (int k = 0; k < cases; ++k) {
    load(c.position(), in.f(perCase(key::kClothPos, k)));
    load(c.velocity(), in.f(perCase(key::kClothVel, k)));
    // what simulateOneStep() computed before collide (the stub must leave it alone)
    c.acceleration().setZero();
    load(c.acceleration(), in.f(perCase(key::kClothAcc, k)));
    loadMass(c, in.f(perCase(key::kClothMass, k)));
    load(s.position(), in.f(perCase(key::kSpherePos, k)));
    load(s.velocity(), in.f(perCase(key::kSphereVel, k)));
    s.acceleration().setZero();
    load(s.acceleration(), in.f(perCase(key::kSphereAcc, k)));
    loadMass(s, in.f(perCase(key::kSphereMass, k)));
    fillStack();
#ifdef CLOTHREF_GRADER_EDITION_2024
    (void)sphereSphere;
    spheres.collide(&cloth);
#else
    if (sphereSphere)
      spheres.collide();
    else
      spheres.collide(&cloth);
#endif
    out.floats[perCase(key::kClothPos, k)] = save(c.position());
    out.floats[perCase(key::kClothVel, k)] = save(c.velocity());
    out.floats[perCase(key::kSpherePos, k)] = save(s.position());
    out.floats[perCase(key::kSphereVel, k)] = save(s.velocity());
    out.floats[perCase(key::kClothAcc, k)] = save(c.acceleration());
    out.floats[perCase(key::kSphereAcc, k)] = save(s.acceleration());
  }
}
void probeCollideCloth(const ProbeMessage& in, ProbeMessage& out) { collide(in, out, false); }
void probeCollideSpheres(const ProbeMessage& in, ProbeMessage& out) { collide(in, out, true); }

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

// The rows of clothref's method table (core/method.h), copied at compile time: the driver holds
// no clothref symbol that a student's file could declare and reach.
constexpr auto kMethodRows = [] {
  std::array<std::pair<clothref::Method, std::string_view>, clothref::kMethods.size()> rows{};
  for (std::size_t row = 0; row < rows.size(); ++row)
    rows[row] = {clothref::kMethods[row].method, clothref::kMethods[row].name};
  return rows;
}();

// The course's integrator of the request's key::kMethod, a row of the method table; a row the
// course has no class for, or a number outside the table, is refused.
const Integrator& integratorFor(std::int64_t row) {
  static const ExplicitEuler explicitEuler;
  static const ImplicitEuler implicitEuler;
  static const MidpointEuler midpointEuler;
  static const RungeKuttaFourth rungeKutta;
  if (row < 0 || row >= std::ssize(kMethodRows))
    throw BadRequest{"no method " + std::to_string(row) + " in the method table"};
  const auto& [method, name] = kMethodRows[static_cast<std::size_t>(row)];
  switch (method) {
    case clothref::Method::Explicit:
      return explicitEuler;
    case clothref::Method::Implicit:
      return implicitEuler;
    case clothref::Method::Midpoint:
      return midpointEuler;
    case clothref::Method::Rk4:
      return rungeKutta;
    case clothref::Method::Symplectic:
    case clothref::Method::BackwardEuler:
      break;  // textbook methods: the course has no class for them
  }
  throw BadRequest{"method " + std::string(name) + " is not one of the course's integrators"};
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

// The course's main loop on its default scene, with every stub the student's.
void probeWholeRun(const ProbeMessage& in, ProbeMessage& out) {
  const Integrator& integrator = integratorFor(in.scalarInt(key::kMethod));
  Cloth cloth;
  Spheres& spheres = Spheres::initSpheres();
#ifdef CLOTHREF_GRADER_EDITION_2024
  spheres.addSphere(Eigen::Vector4f(0, 0, 0, 1), 1.0f);
#else
  spheres.addSphere(Eigen::Vector4f(-0.75f, 1, -0.75f, 1), 0.5f);
  spheres.addSphere(Eigen::Vector4f(0.75f, 1, -0.75f, 1), 0.5f);
  spheres.addSphere(Eigen::Vector4f(-0.75f, 1, 0.75f, 1), 0.5f);
  spheres.addSphere(Eigen::Vector4f(0.75f, 1, 0.75f, 1), 0.5f);
#endif
  deltaTime = in.scalar(key::kDt, 1e-4f);
  const std::int64_t steps = in.scalarInt(key::kSteps, 100);
  const std::int64_t stride = std::max<std::int64_t>(1, in.scalarInt(key::kStride, 10));
  std::vector<Particles*> particles{&cloth.particles(), &spheres.particles()};
  std::function<void(void)> simulateOneStep = [&] {
    cloth.computeExternalForce();
#ifdef CLOTHREF_GRADER_EDITION_2024
    cloth.computeSpringForce();
    spheres.collide(&cloth);
#else
    spheres.computeExternalForce();
    cloth.computeSpringForce();
    spheres.collide(&cloth);
    spheres.collide();
#endif
  };
  std::vector<float> clothX, clothV, sphereX, sphereV;
  auto record = [&] {
    for (auto [from, to] :
         {std::pair{&cloth.particles(), &clothX}, std::pair{&spheres.particles(), &sphereX}}) {
      auto x = save(from->position());
      to->insert(to->end(), x.begin(), x.end());
    }
    for (auto [from, to] :
         {std::pair{&cloth.particles(), &clothV}, std::pair{&spheres.particles(), &sphereV}}) {
      auto v = save(from->velocity());
      to->insert(to->end(), v.begin(), v.end());
    }
  };
  record();
  for (std::int64_t step = 1; step <= steps; ++step) {
#ifdef CLOTHREF_GRADER_EDITION_2024
    // the 2024 main loop's per-frame work (docs/course.md §3), every 40 steps (a 60 Hz frame):
    // re-pin the corners, then spheres.setVelocity(0, 0), as clothref's course2024 does
    if ((step - 1) % 40 == 0) {
      constexpr int n = particlesPerEdge;
      for (int corner : {0, n - 1, n * (n - 1), n * n - 1}) {
        cloth.particles().mass(corner) = 0.0f;
        cloth.particles().velocity(corner).setZero();
        cloth.particles().acceleration(corner).setZero();
      }
      spheres.setVelocity(0, Eigen::Vector4f::Zero());
    }
#endif
    simulateOneStep();
    integrator.integrate(particles, simulateOneStep);
    if (step % stride == 0 || step == steps) record();
  }
  out.floats[key::kClothPos] = clothX;
  out.floats[key::kClothVel] = clothV;
  out.floats[key::kSpherePos] = sphereX;
  out.floats[key::kSphereVel] = sphereV;
  out.ints[key::kSphereCapacity] = {spheres.particles().getCapacity()};
}

// The groups served, by the protocol's group name: the one dispatch of the driver.
struct Group {
  const char* name;
  void (*run)(const ProbeMessage& in, ProbeMessage& out);
};
constexpr Group kGroups[] = {
    // Cloth() and its springs (N = particlesPerEdge of this build)
    {group::kSprings, probeSprings},
    // Cloth::computeSpringForce on given states and OUR spring set
    {group::kForces, probeForces},
    // Spheres::collide(Cloth*) on crafted states
    {group::kCollideCloth, probeCollideCloth},
    // Spheres::collide() on crafted states (2022 only)
    {group::kCollideSpheres, probeCollideSpheres},
    // one integrator on small systems whose derivatives come from the course-form force code
    // above (never the student's forces)
    {group::kIntegrate, probeIntegrate},
    // the student's full simulation of the course scene (information only)
    {group::kWholeRun, probeWholeRun},
};

// Every group of the protocol's list has exactly one row.
constexpr bool servesEveryGroupOnce() {
  for (const probe::Name& name : group::kAll) {
    int rows = 0;
    for (const Group& row : kGroups) rows += std::string_view(row.name) == name.text ? 1 : 0;
    if (rows != 1) return false;
  }
  return std::size(kGroups) == std::size(group::kAll);
}
static_assert(servesEveryGroupOnce(), "kGroups must have one row per name of probe::group");

// Runs the row named `name`; false when no row is. Unrolled over the rows, so that each call is
// a direct call the compiler may inline, as a hand-written chain's would be (a crash report
// quotes the same driver frames as before the table).
template <std::size_t... row>
bool serve(const std::string& name, const ProbeMessage& in, ProbeMessage& out,
           std::index_sequence<row...>) {
  return ((name == kGroups[row].name && (kGroups[row].run(in, out), true)) || ...);
}

bool writeAll(int fd, const std::string& data) {
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

int main() {
  std::string request((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
  const auto in = probe::decodeMessage(request);
  if (!in) {
    std::fprintf(stderr, "probe driver: malformed request\n");
    return 70;
  }
  ProbeMessage out;
  out.nonce = in->nonce;
  const std::string name = in->text(key::kGroup);
  try {
    if (!serve(name, *in, out, std::make_index_sequence<std::size(kGroups)>()))
      throw BadRequest{"unknown group '" + name + "'"};
  } catch (const BadRequest& bad) {
    std::fprintf(stderr, "probe driver: %s\n", bad.why.c_str());
    return 70;
  }
  out.texts[key::kGroup] = name;
  return writeAll(probe::kResultFd, probe::encodeMessage(out)) ? 0 : 71;
}
