// Stand-in for the course's configs.h (2024 edition): constants and the GUI-tunable globals.
// The grader builds the springs probe a second time with CLOTHREF_GRADER_PARTICLES_PER_EDGE set,
// so a cloth that hard-codes 25 is caught; every other build uses the course's 25.
#pragma once
#include <Eigen/Core>

#ifndef CLOTHREF_GRADER_PARTICLES_PER_EDGE
#define CLOTHREF_GRADER_PARTICLES_PER_EDGE 25
#endif

inline constexpr int particlesPerEdge = CLOTHREF_GRADER_PARTICLES_PER_EDGE;
inline constexpr int clothWidth = 2;
inline constexpr int clothHeight = 2;
inline constexpr float particleMass = 1.0f;
inline constexpr float sphereDensity = 1e3f;
inline constexpr float baseSpeed = 1e-3f;
inline constexpr int sphereSlice = 36;
inline constexpr int sphereStack = 18;

extern int windowWidth;
extern int windowHeight;
extern int speedMultiplier;
extern float mouseMoveSpeed;
extern float keyboardMoveSpeed;
extern float deltaTime;
extern int simulationPerFrame;
extern float springCoef;
extern float damperCoef;
extern float viscousCoef;
extern Eigen::Vector4f sphereColor;
extern bool isSphereColorChange;
extern bool isDrawingParticles;
extern bool isDrawingStructuralSprings;
extern bool isDrawingShearSprings;
extern bool isDrawingBendSprings;
extern bool isDrawingCloth;
extern bool isPaused;
extern bool isStateSwitched;
extern int currentIntegrator;
