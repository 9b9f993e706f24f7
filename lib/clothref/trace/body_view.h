// BodyView: what the trace sees of one body, without owning it or knowing where it lives (a
// clothref World, or a probe built around a student's Particles).
//   name       "cloth" or "spheres"
//   position   4 x particles values, column-major, one (x, y, z, w) column per particle, metres
//   velocity   same layout, metres / second
// The course's Eigen::Matrix4Xf has exactly this layout (matrix.data()).
#pragma once

#include <string_view>

namespace clothref {

template <typename T>
struct BodyView {
  std::string_view name;
  const T* position = nullptr;
  const T* velocity = nullptr;
  int particles = 0;
};

}  // namespace clothref
