#pragma once
#include <Eigen/Core>
// Changed by the student: a comment and a larger default step. Student headers are never used.
inline constexpr int particlesPerEdge = 25;
inline constexpr int clothWidth = 2;
inline constexpr int clothHeight = 2;
inline constexpr float particleMass = 1.0f;
inline constexpr float sphereDensity = 1e3f;
inline constexpr float baseSpeed = 1e-3f;
inline constexpr int sphereSlice = 36;
inline constexpr int sphereStack = 18;
extern float deltaTime;
extern float springCoef;
extern float damperCoef;
extern float viscousCoef;
