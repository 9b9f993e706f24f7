// Scalar and vector types shared by every part of the library.
//
// State is stored the way the course stores it: one 4-vector column per particle, positions with
// w = 1 and velocities / accelerations with w = 0. Keeping the course's layout (and Eigen's own
// 4-wide reductions for norm and dot) is what lets the float build reproduce the course bit for
// bit.
#pragma once

#include <Eigen/Core>

namespace clothref {

// 4-vector (x, y, z, w); w = 1 for points, 0 for directions.
template <typename T>
using Vec4 = Eigen::Matrix<T, 4, 1>;

// 4 x N matrix, one column per particle, column-major (contiguous per particle).
template <typename T>
using Mat4X = Eigen::Matrix<T, 4, Eigen::Dynamic>;

// Column vector of N scalars (masses, radii).
template <typename T>
using VecX = Eigen::Matrix<T, Eigen::Dynamic, 1>;

}  // namespace clothref
