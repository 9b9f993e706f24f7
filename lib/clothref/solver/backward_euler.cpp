#include "clothref/solver/backward_euler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace clothref {

namespace {

// Index into matrix.valuePtr() of entry (row, col); the entry must be in the pattern.
template <typename T>
int slotOf(const Eigen::SparseMatrix<T, Eigen::RowMajor>& matrix, int row, int col) {
  const int* begin = matrix.innerIndexPtr() + matrix.outerIndexPtr()[row];
  const int* end = matrix.innerIndexPtr() + matrix.outerIndexPtr()[row + 1];
  const int* found = std::lower_bound(begin, end, col);
  return static_cast<int>(found - matrix.innerIndexPtr());
}

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

// Adds `sign * block` into the 3x3 block whose 9 slots start at `slots` (row-major order).
template <typename T>
void addBlock(T* values, const int* slots, const Mat3<T>& block, T sign) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) values[slots[3 * r + c]] += sign * block(r, c);
}

}  // namespace

template <typename T>
double cgTolerance(const CgSettings& settings) {
  if (settings.tolerance > 0) return settings.tolerance;
  return std::is_same_v<T, float> ? 1e-5 : 1e-10;
}

template <typename T>
void prepareBackwardEuler(const Cloth<T>& cloth, BackwardEulerSolver<T>& solver) {
  const int n = cloth.particles.size();
  const int dofs = 3 * n;
  std::vector<Eigen::Triplet<T>> triplets;
  triplets.reserve(9 * n + 18 * cloth.springs.size());
  auto block = [&triplets](int a, int b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) triplets.emplace_back(3 * a + r, 3 * b + c, T(0));
  };
  for (int i = 0; i < n; ++i) block(i, i);
  for (const Spring<T>& spring : cloth.springs) {
    block(int(spring.start), int(spring.end));
    block(int(spring.end), int(spring.start));
  }
  solver.matrix.resize(dofs, dofs);
  solver.matrix.setFromTriplets(triplets.begin(), triplets.end());
  solver.matrix.makeCompressed();

  auto blockSlots = [&solver](int a, int b, int* out) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out[3 * r + c] = slotOf(solver.matrix, 3 * a + r, 3 * b + c);
  };
  solver.spring_slots.assign(36 * cloth.springs.size(), 0);
  for (std::size_t k = 0; k < cloth.springs.size(); ++k) {
    const int s = int(cloth.springs[k].start);
    const int e = int(cloth.springs[k].end);
    int* out = solver.spring_slots.data() + 36 * k;
    blockSlots(s, s, out);
    blockSlots(e, e, out + 9);
    blockSlots(s, e, out + 18);
    blockSlots(e, s, out + 27);
  }
  solver.diagonal_slots.assign(3 * n, 0);
  for (int d = 0; d < dofs; ++d) solver.diagonal_slots[d] = slotOf(solver.matrix, d, d);

  // filtering: a fixed particle's rows and columns become the identity
  solver.filtered_slots.clear();
  solver.fixed_diagonal_slots.clear();
  const auto fixed = [&cloth](int dof) { return cloth.particles.mass[dof / 3] == T(0); };
  for (int row = 0; row < dofs; ++row) {
    for (int k = solver.matrix.outerIndexPtr()[row]; k < solver.matrix.outerIndexPtr()[row + 1];
         ++k) {
      const int col = solver.matrix.innerIndexPtr()[k];
      if (row == col && fixed(row))
        solver.fixed_diagonal_slots.push_back(k);
      else if (fixed(row) || fixed(col))
        solver.filtered_slots.push_back(k);
    }
  }
  for (VecX<T>* v : {&solver.rhs, &solver.dv, &solver.residual, &solver.direction, &solver.z,
                     &solver.product, &solver.inverse_diagonal})
    v->setZero(dofs);
  solver.particles = n;
  solver.springs = cloth.springs.size();
}

template <typename T>
int solveConjugateGradient(const Eigen::SparseMatrix<T, Eigen::RowMajor>& matrix, const VecX<T>& b,
                           VecX<T>& x, BackwardEulerSolver<T>& solver) {
  VecX<T>& r = solver.residual;
  VecX<T>& p = solver.direction;
  VecX<T>& z = solver.z;
  VecX<T>& product = solver.product;
  VecX<T>& inverse_diagonal = solver.inverse_diagonal;
  const Eigen::Index dofs = b.size();
  for (Eigen::Index k = 0; k < dofs; ++k) {
    const T d = matrix.valuePtr()[solver.diagonal_slots[k]];
    inverse_diagonal[k] = d != T(0) ? T(1) / d : T(1);
  }
  x.setZero();
  r = b;
  const T rhs_norm2 = b.squaredNorm();
  CgStats& stats = solver.stats;
  ++stats.solves;
  if (rhs_norm2 == T(0)) {
    stats.last_relative_residual = 0;
    return 0;
  }
  const T tolerance = T(cgTolerance<T>(solver.settings));
  const T threshold = std::max(tolerance * tolerance * rhs_norm2, std::numeric_limits<T>::min());
  T residual_norm2 = r.squaredNorm();
  int iterations = 0;
  if (residual_norm2 >= threshold) {
    p = inverse_diagonal.cwiseProduct(r);
    T rz = r.dot(p);
    while (iterations < solver.settings.max_iterations) {
      product.noalias() = matrix * p;
      const T alpha = rz / p.dot(product);
      x += alpha * p;
      r -= alpha * product;
      ++iterations;
      residual_norm2 = r.squaredNorm();
      if (residual_norm2 < threshold) break;
      z = inverse_diagonal.cwiseProduct(r);
      const T rz_old = rz;
      rz = r.dot(z);
      p = z + (rz / rz_old) * p;
    }
  }
  stats.iterations += iterations;
  stats.max_iterations_seen = std::max(stats.max_iterations_seen, iterations);
  if (residual_norm2 >= threshold) ++stats.capped;
  stats.last_relative_residual = std::sqrt(double(residual_norm2) / double(rhs_norm2));
  return iterations;
}

template <typename T>
void integrateBackwardEuler(World<T>& world, BackwardEulerSolver<T>& solver) {
  simulateOneStep(world);
  const Physics<T>& physics = world.physics;
  const T h = physics.dt;

  if (world.cloth) {
    Cloth<T>& cloth = *world.cloth;
    Particles<T>& p = cloth.particles;
    if (solver.particles != p.size() || solver.springs != cloth.springs.size())
      prepareBackwardEuler(cloth, solver);
    T* values = solver.matrix.valuePtr();
    std::fill(values, values + solver.matrix.nonZeros(), T(0));
    VecX<T>& b = solver.rhs;
    const T c = physics.viscous_coef;
    for (int i = 0; i < p.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        values[solver.diagonal_slots[3 * i + k]] = p.mass[i] + h * c;
        b[3 * i + k] = h * (p.mass[i] * p.acceleration(k, i));
      }
    }
    const T k_s = cloth.spring_coef;
    const T k_d = cloth.damper_coef;
    const Mat3<T> identity = Mat3<T>::Identity();
    for (std::size_t k = 0; k < cloth.springs.size(); ++k) {
      const int s = int(cloth.springs[k].start);
      const int e = int(cloth.springs[k].end);
      const Vec3<T> d = p.position.col(s).template head<3>() - p.position.col(e).template head<3>();
      const T length = d.norm();
      if (!(length > T(0))) continue;  // no direction: the course's force is zero as well
      const Vec3<T> n = d / length;
      const Mat3<T> nn = n * n.transpose();
      const T transverse = std::max(T(0), T(1) - cloth.springs[k].rest_length / length);
      // -K_ss: the stiffness Jacobian of the force on `start` with respect to x_start, negated
      const Mat3<T> stiffness = k_s * (nn + transverse * (identity - nn));
      const Mat3<T> block = (h * k_d) * nn + (h * h) * stiffness;
      const int* slots = solver.spring_slots.data() + 36 * k;
      addBlock(values, slots, block, T(1));
      addBlock(values, slots + 9, block, T(1));
      addBlock(values, slots + 18, block, T(-1));
      addBlock(values, slots + 27, block, T(-1));
      // h^2 K v0: the force change the velocity makes over the step
      const Vec3<T> relative =
          p.velocity.col(s).template head<3>() - p.velocity.col(e).template head<3>();
      const Vec3<T> change = (h * h) * (stiffness * relative);
      b.template segment<3>(3 * s) -= change;
      b.template segment<3>(3 * e) += change;
    }
    for (int slot : solver.filtered_slots) values[slot] = T(0);
    for (int slot : solver.fixed_diagonal_slots) values[slot] = T(1);
    for (int i = 0; i < p.size(); ++i)
      if (p.mass[i] == T(0)) b.template segment<3>(3 * i).setZero();

    solveConjugateGradient(solver.matrix, b, solver.dv, solver);
    for (int i = 0; i < p.size(); ++i) {
      for (int k = 0; k < 3; ++k) p.velocity(k, i) += solver.dv[3 * i + k];
    }
    p.position += p.velocity * h;
  }
  if (world.spheres) {
    Particles<T>& p = world.spheres->particles;
    const T c = physics.sphere_external_force ? physics.viscous_coef : T(0);
    for (int i = 0; i < p.size(); ++i) {
      // the sphere's own 1x1 backward-Euler system: drag is its only velocity-dependent force
      p.velocity.col(i) += p.acceleration.col(i) * (h / (T(1) + h * c * p.inverse_mass[i]));
    }
    p.position += p.velocity * h;
  }
}

template <typename T>
void BackwardEulerSolver<T>::integrate(World<T>& world) {
  integrateBackwardEuler(world, *this);
}

template <typename T>
void installBackwardEuler(World<T>& world) {
  auto solver = std::make_shared<BackwardEulerSolver<T>>();
  if (world.cloth) prepareBackwardEuler(*world.cloth, *solver);
  world.method = Method::BackwardEuler;
  world.stepper = std::move(solver);
}

template <typename T>
BackwardEulerSolver<T>* backwardEulerSolver(World<T>& world) {
  return dynamic_cast<BackwardEulerSolver<T>*>(world.stepper.get());
}

template <typename T>
const BackwardEulerSolver<T>* backwardEulerSolver(const World<T>& world) {
  return dynamic_cast<const BackwardEulerSolver<T>*>(world.stepper.get());
}

#define CLOTHREF_INSTANTIATE(T)                                                       \
  template double cgTolerance<T>(const CgSettings&);                                  \
  template void prepareBackwardEuler(const Cloth<T>&, BackwardEulerSolver<T>&);       \
  template struct BackwardEulerSolver<T>;                                             \
  template void integrateBackwardEuler(World<T>&, BackwardEulerSolver<T>&);           \
  template void installBackwardEuler(World<T>&);                                      \
  template BackwardEulerSolver<T>* backwardEulerSolver(World<T>&);                    \
  template const BackwardEulerSolver<T>* backwardEulerSolver(const World<T>&);        \
  template int solveConjugateGradient(const Eigen::SparseMatrix<T, Eigen::RowMajor>&, \
                                      const VecX<T>&, VecX<T>&, BackwardEulerSolver<T>&);
CLOTHREF_INSTANTIATE(float)
CLOTHREF_INSTANTIATE(double)
#undef CLOTHREF_INSTANTIATE

}  // namespace clothref
