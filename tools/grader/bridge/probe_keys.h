// The probe protocol's names, the one table of them: the group names and the ProbeMessage keys
// (probe_protocol.h) that the grader (grade/probes/) and the driver
// (driver/probe_driver.cpp) exchange. Both sides are built together, so the names are internal;
// a key written anywhere else is a bug. Std only: the course side includes it too.
//
// Arrays of a body's particles are 4 x n column-major (x, y, z, w per particle), as the course's
// Particles matrices. A key marked "per case" is sent once per case k as "<key>.<k>"
// (perCase()), k = 0 .. cases - 1.
#pragma once
#include <string>

namespace probe {

// The request's "group" text: which stubs the child runs.
namespace group {
inline constexpr const char* kSprings = "springs";                 // Cloth() and its springs
inline constexpr const char* kForces = "forces";                   // Cloth::computeSpringForce
inline constexpr const char* kCollideCloth = "collide-cloth";      // Spheres::collide(Cloth*)
inline constexpr const char* kCollideSpheres = "collide-spheres";  // Spheres::collide() (2022)
inline constexpr const char* kIntegrate = "integrate";             // one Integrator::integrate
inline constexpr const char* kWholeRun = "whole-run";              // the course scene, all stubs
}  // namespace group

namespace key {
// ---- Every group
inline constexpr const char* kGroup = "group";  // text: a group name above (request and answer)
// int[1]: the number of cases (forces, collide, integrate)
inline constexpr const char* kCases = "cases";
// int[1]: the integrator, 0 explicit, 1 implicit, 2 midpoint, 3 RK4 (integrate, whole-run)
inline constexpr const char* kMethod = "method";

// ---- Body states (per case in forces, collide and integrate; every record in whole-run)
inline constexpr const char* kClothPos = "cloth.pos";    // float[4 n]: cloth positions (m)
inline constexpr const char* kClothVel = "cloth.vel";    // float[4 n]: cloth velocities (m/s)
inline constexpr const char* kClothAcc = "cloth.acc";    // float[4 n]: cloth accelerations (m/s^2)
inline constexpr const char* kClothMass = "cloth.mass";  // float[n]: cloth masses (kg, 0 = fixed)
inline constexpr const char* kSpherePos = "sphere.pos";  // float[4 s]: sphere centres (m)
inline constexpr const char* kSphereVel = "sphere.vel";  // float[4 s]: sphere velocities (m/s)
inline constexpr const char* kSphereMass = "sphere.mass";      // float[s]: sphere masses (kg)
inline constexpr const char* kSphereRadius = "sphere.radius";  // float[s]: sphere radii (m)

// ---- A spring set: springs' answer; forces' request (once); integrate's request (per case)
inline constexpr const char* kSpringStart = "spring.start";  // int[springs]: first particle index
inline constexpr const char* kSpringEnd = "spring.end";      // int[springs]: second particle index
inline constexpr const char* kSpringType = "spring.type";    // int[springs]: Spring::Type value
inline constexpr const char* kSpringRest = "spring.rest";    // float[springs]: rest length (m)

// ---- springs (answer)
inline constexpr const char* kParticlesPerEdge = "particles_per_edge";  // int[1]: N of this build

// ---- forces (request): the course's global coefficients
inline constexpr const char* kSpringCoef = "spring_coef";  // float[1]: springCoef (N/m)
inline constexpr const char* kDamperCoef = "damper_coef";  // float[1]: damperCoef (N s/m)

// ---- integrate (request, per case; dt, steps and stride also whole-run's, once)
// float[8]: spring coef (N/m), damper coef (N s/m), viscous (N s/m), gravity x y z (m/s^2),
// restitution cloth-sphere and sphere-sphere (1)
inline constexpr const char* kParams = "params";
// int[3]: sphere gravity, cloth-sphere contact, sphere-sphere contact (0 or 1)
inline constexpr const char* kFlags = "flags";
inline constexpr const char* kDt = "dt";          // float[1]: the step (s)
inline constexpr const char* kSteps = "steps";    // int[1]: steps to take
inline constexpr const char* kStride = "stride";  // int[1]: record every stride steps (0 = never)
// ---- integrate (answer, per case)
inline constexpr const char* kDtAfter = "dt_after";  // float[1]: deltaTime after the first step (s)
// int[1]: simulateOneStep() calls made inside integrate(), over all steps
inline constexpr const char* kCalls = "calls";
// float[4 n x records]: cloth positions (m) every stride steps, concatenated
inline constexpr const char* kTrajectory = "trajectory";

// ---- integrate, the stage record (docs/grading.md, "Integrators explained by their stages")
// int[1] (request, per case): 1 = record this case's stages (a contact-free case of one step)
inline constexpr const char* kRecordStages = "record_stages";
inline constexpr int kMaxStageRecords = 16;  // simulateOneStep() calls recorded per case
// (answer, per recorded case) The start: the state integrate() receives, after the simulate()
// before it. float[4 n] / float[4 s] each; the accelerations are our simulate()'s (m/s^2).
inline constexpr const char* kStartClothPos = "start.cloth.pos";    // m
inline constexpr const char* kStartClothVel = "start.cloth.vel";    // m/s
inline constexpr const char* kStartClothAcc = "start.cloth.acc";    // m/s^2
inline constexpr const char* kStartSpherePos = "start.sphere.pos";  // m
inline constexpr const char* kStartSphereVel = "start.sphere.vel";  // m/s
inline constexpr const char* kStartSphereAcc = "start.sphere.acc";  // m/s^2
// Each simulateOneStep() call integrate() makes (the first kMaxStageRecords; key kCalls counts
// them all): the state handed to it and the accelerations it produced, float[4 n x r] /
// float[4 s x r] for r recorded calls, concatenated in call order. The result after integrate()
// is in the body-state keys (kClothPos, kClothVel, kSpherePos, kSphereVel) as for every case.
inline constexpr const char* kEvalClothPos = "eval.cloth.pos";    // m
inline constexpr const char* kEvalClothVel = "eval.cloth.vel";    // m/s
inline constexpr const char* kEvalClothAcc = "eval.cloth.acc";    // m/s^2
inline constexpr const char* kEvalSpherePos = "eval.sphere.pos";  // m
inline constexpr const char* kEvalSphereVel = "eval.sphere.vel";  // m/s
inline constexpr const char* kEvalSphereAcc = "eval.sphere.acc";  // m/s^2

// ---- whole-run (answer): the body-state keys hold every record's state, concatenated, and
inline constexpr const char* kSphereCapacity = "sphere_capacity";  // int[1]: spheres per record

// The key of case k: "<key>.<k>".
inline std::string perCase(const char* key, int k) {
  return std::string(key) + "." + std::to_string(k);
}
}  // namespace key

}  // namespace probe
