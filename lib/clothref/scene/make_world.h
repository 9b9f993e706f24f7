// makeWorld: a scene's initial state as a World in precision T.
#pragma once

#include <optional>

#include "clothref/core/integrator.h"
#include "clothref/core/world.h"
#include "clothref/scene/scene.h"

namespace clothref {

// Builds the initial state of `scene`: the grid (initializeVertex, fixed particles,
// initializeSpring) or the listed particles and springs, then the spheres (addSphere), and the
// frame loop when the scene has one. `dt` overrides the scene's dt when given. Throws SceneError
// for an invalid scene.
template <typename T>
World<T> makeWorld(const Scene& scene, Method method, std::optional<double> dt = std::nullopt);

}  // namespace clothref
