// A World as the trace sees it: body views (cloth, then spheres), its state hash and its step line.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "clothref/core/world.h"
#include "clothref/trace/body_view.h"
#include "clothref/trace/hash.h"
#include "clothref/trace/step_line.h"

namespace clothref {

// The bodies of `world` in trace order; `storage` holds the views the span points to.
template <typename T>
std::span<const BodyView<T>> bodyViews(const World<T>& world, std::array<BodyView<T>, 2>& storage) {
  std::size_t count = 0;
  const auto view = [](std::string_view name, const Particles<T>& p) {
    return BodyView<T>{name, p.position.data(), p.velocity.data(), p.size()};
  };
  if (world.cloth) storage[count++] = view("cloth", world.cloth->particles);
  if (world.spheres) storage[count++] = view("spheres", world.spheres->particles);
  return {storage.data(), count};
}

template <typename T>
std::uint64_t stateHash(const World<T>& world) {
  std::array<BodyView<T>, 2> storage;
  return stateHash(bodyViews(world, storage));
}

// Appends the step line of the world's current state (step and t = step * dt from the world).
template <typename T>
void appendStepLine(std::string& out, const World<T>& world) {
  std::array<BodyView<T>, 2> storage;
  appendStepLine(out, world.step, double(world.step) * double(world.physics.dt),
                 bodyViews(world, storage));
}

}  // namespace clothref
