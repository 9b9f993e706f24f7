// The probe protocol's names, the one list of them: the group names and the ProbeMessage keys
// (probe_protocol.h) that the grader (grade/probes/) and the driver (driver/) exchange. Both
// sides are built together, so the names are internal; a key written anywhere else is a bug. Std
// only: the course side includes it too.
//
// Each list is an X-macro, X(identifier, text): it declares probe::group::<identifier> and
// probe::key::<identifier>, and kAll, every {identifier, text} in list order, which the tests
// loop over. A new name is one line here. A group's line also names its functions, one on each
// side, X(identifier, text, Name): the driver's probe<Name>(in, out), in a header of
// driver/groups/, and the grader's probeRows<Name>(), its rows of the probe table
// (grade/probes/probes.h) in the probe's own file; both sides' dispatch is this list, so a probe
// is its file, its course side and its line here (a group without either function does not build).
//
// Arrays of a body's particles are 4 x n column-major (x, y, z, w per particle), as the course's
// Particles matrices. A key marked "per case" is sent once per case k as "<key>.<k>"
// (perCase()), k = 0 .. cases - 1.
#pragma once
#include <string>

// clang-format off
// The request's "group" text: which stubs the child runs.
#define CLOTHREF_PROBE_GROUPS(X)                                                                   \
  X(kSprings, "springs", Springs)                      /* Cloth() and its springs */               \
  X(kForces, "forces", Forces)                         /* Cloth::computeSpringForce */             \
  X(kCollideCloth, "collide-cloth", CollideCloth)      /* Spheres::collide(Cloth*) */              \
  X(kCollideSpheres, "collide-spheres", CollideSpheres) /* Spheres::collide() (2022) */            \
  X(kIntegrate, "integrate", Integrate)                /* one Integrator::integrate */             \
  X(kWholeRun, "whole-run", WholeRun)                  /* the course scene, all stubs */

// The ProbeMessage keys.
#define CLOTHREF_PROBE_KEYS(X)                                                                     \
  /* ---- Every group */                                                                           \
  X(kGroup, "group") /* text: a group name above (request and answer) */                           \
  /* int[1]: the number of cases (forces, collide, integrate) */                                   \
  X(kCases, "cases")                                                                               \
  /* int[1]: the integrator, the row of clothref's method table (core/method.h, kMethods) of a */  \
  /* course method: 0 explicit, 1 implicit, 2 midpoint, 3 RK4 (integrate, whole-run) */            \
  X(kMethod, "method")                                                                             \
  /* ---- Body states (per case in forces, collide and integrate; every record in whole-run) */    \
  X(kClothPos, "cloth.pos")         /* float[4 n]: cloth positions (m) */                          \
  X(kClothVel, "cloth.vel")         /* float[4 n]: cloth velocities (m/s) */                       \
  X(kClothAcc, "cloth.acc")         /* float[4 n]: cloth accelerations (m/s^2) */                  \
  X(kClothMass, "cloth.mass")       /* float[n]: cloth masses (kg, 0 = fixed) */                   \
  X(kSpherePos, "sphere.pos")       /* float[4 s]: sphere centres (m) */                           \
  X(kSphereVel, "sphere.vel")       /* float[4 s]: sphere velocities (m/s) */                      \
  X(kSphereAcc, "sphere.acc")       /* float[4 s]: sphere accelerations (m/s^2; collide) */        \
  X(kSphereMass, "sphere.mass")     /* float[s]: sphere masses (kg) */                             \
  X(kSphereRadius, "sphere.radius") /* float[s]: sphere radii (m) */                               \
  /* ---- A spring set: springs' answer; forces' request (once); integrate's request (per case) */ \
  X(kSpringStart, "spring.start") /* int[springs]: first particle index */                         \
  X(kSpringEnd, "spring.end")     /* int[springs]: second particle index */                        \
  X(kSpringType, "spring.type")   /* int[springs]: Spring::Type value */                           \
  X(kSpringRest, "spring.rest")   /* float[springs]: rest length (m) */                            \
  /* ---- springs (answer) */                                                                      \
  X(kParticlesPerEdge, "particles_per_edge") /* int[1]: N of this build */                         \
  /* ---- forces (request): the course's global coefficients */                                    \
  X(kSpringCoef, "spring_coef") /* float[1]: springCoef (N/m) */                                   \
  X(kDamperCoef, "damper_coef") /* float[1]: damperCoef (N s/m) */                                 \
  /* ---- integrate (request, per case; dt, steps and stride also whole-run's, once) */            \
  /* float[8]: spring coef (N/m), damper coef (N s/m), viscous (N s/m), gravity x y z (m/s^2), */  \
  /* restitution cloth-sphere and sphere-sphere (1) */                                             \
  X(kParams, "params")                                                                             \
  /* int[3]: sphere gravity, cloth-sphere contact, sphere-sphere contact (0 or 1) */               \
  X(kFlags, "flags")                                                                               \
  X(kDt, "dt")         /* float[1]: the step (s) */                                                \
  X(kSteps, "steps")   /* int[1]: steps to take */                                                 \
  X(kStride, "stride") /* int[1]: record every stride steps (0 = never) */                         \
  /* ---- integrate (answer, per case) */                                                          \
  X(kDtAfter, "dt_after") /* float[1]: deltaTime after the first step (s) */                       \
  /* int[1]: simulateOneStep() calls made inside integrate(), over all steps */                    \
  X(kCalls, "calls")                                                                               \
  /* float[4 n x records]: cloth positions (m) every stride steps, concatenated */                 \
  X(kTrajectory, "trajectory")                                                                     \
  /* ---- integrate, the stage record */                                                           \
  /* (docs/grading-reference.md, "Integrators explained by their stages") */                                 \
  /* int[1] (request, per case): 1 = record this case's stages */                                  \
  /* (a contact-free case of one step) */                                                          \
  X(kRecordStages, "record_stages")                                                                \
  /* (answer, per recorded case) The start: the state integrate() receives, after the */           \
  /* simulate() before it. float[4 n] / float[4 s] each; the accelerations are our */              \
  /* simulate()'s. */                                                                              \
  X(kStartClothPos, "start.cloth.pos")     /* m */                                                 \
  X(kStartClothVel, "start.cloth.vel")     /* m/s */                                               \
  X(kStartClothAcc, "start.cloth.acc")     /* m/s^2 */                                             \
  X(kStartSpherePos, "start.sphere.pos")   /* m */                                                 \
  X(kStartSphereVel, "start.sphere.vel")   /* m/s */                                               \
  X(kStartSphereAcc, "start.sphere.acc")   /* m/s^2 */                                             \
  /* Each simulateOneStep() call integrate() makes (the first kMaxStageRecords; key */             \
  /* kCalls counts them all): the state handed to it and the accelerations it produced, */         \
  /* float[4 n x r] / float[4 s x r] for r recorded calls, concatenated in call order. The */      \
  /* result after integrate() is in the body-state keys (kClothPos, kClothVel, kSpherePos, */      \
  /* kSphereVel) as for every case. */                                                             \
  X(kEvalClothPos, "eval.cloth.pos")     /* m */                                                   \
  X(kEvalClothVel, "eval.cloth.vel")     /* m/s */                                                 \
  X(kEvalClothAcc, "eval.cloth.acc")     /* m/s^2 */                                               \
  X(kEvalSpherePos, "eval.sphere.pos")   /* m */                                                   \
  X(kEvalSphereVel, "eval.sphere.vel")   /* m/s */                                                 \
  X(kEvalSphereAcc, "eval.sphere.acc")   /* m/s^2 */                                               \
  /* ---- whole-run (answer): the body-state keys hold every record's state, concatenated, and */  \
  X(kSphereCapacity, "sphere_capacity") /* int[1]: spheres per record */

// clang-format on

namespace probe {

// A name of the protocol: its identifier in the lists above, and its text on the wire.
struct Name {
  const char* identifier;
  const char* text;
};

#define CLOTHREF_PROBE_DECLARE(identifier, text) inline constexpr const char* identifier = text;
#define CLOTHREF_PROBE_ENTRY(identifier, text) Name{#identifier, text},
#define CLOTHREF_PROBE_DECLARE_GROUP(identifier, text, name) \
  CLOTHREF_PROBE_DECLARE(identifier, text)
#define CLOTHREF_PROBE_GROUP_ENTRY(identifier, text, name) CLOTHREF_PROBE_ENTRY(identifier, text)

namespace group {
CLOTHREF_PROBE_GROUPS(CLOTHREF_PROBE_DECLARE_GROUP)
// Every group, in the list's order.
inline constexpr Name kAll[] = {CLOTHREF_PROBE_GROUPS(CLOTHREF_PROBE_GROUP_ENTRY)};
}  // namespace group

namespace key {
CLOTHREF_PROBE_KEYS(CLOTHREF_PROBE_DECLARE)
// Every key, in the list's order.
inline constexpr Name kAll[] = {CLOTHREF_PROBE_KEYS(CLOTHREF_PROBE_ENTRY)};

// simulateOneStep() calls recorded per case (kEval... keys)
inline constexpr int kMaxStageRecords = 16;

// The key of case k: "<key>.<k>".
inline std::string perCase(const char* key, int k) {
  return std::string(key) + "." + std::to_string(k);
}
}  // namespace key

#undef CLOTHREF_PROBE_DECLARE
#undef CLOTHREF_PROBE_ENTRY
#undef CLOTHREF_PROBE_DECLARE_GROUP
#undef CLOTHREF_PROBE_GROUP_ENTRY

}  // namespace probe
