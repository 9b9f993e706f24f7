// Backward Euler: the linearised implicit step of Baraff & Witkin (1998), beside the course's
// one-pass predictor-corrector "implicit" Euler (core/integrator.h).
//
// One step, for the cloth's N particles (v, x: 3N, metres per second and metres):
//   1. simulateOneStep, as every method: forces give a0, contacts change v and x (course step);
//   2. solve (M - h D - h^2 K) dv = h (M a0 + h K v0) for dv (3N), where
//        M  diagonal masses (kg)
//        K  = df/dx, the spring stiffness Jacobian at x0 (N/m): per spring
//             -k_s (n n^T + max(0, 1 - L0 / L) (I - n n^T)), the transverse (geometric) term
//             dropped under compression so the matrix stays positive definite
//        D  = df/dv, the damping Jacobian (N s/m): per spring -k_d n n^T, plus -c I for the drag
//   3. v = v0 + dv, x = x0 + h v (cloth); a sphere has only drag and gravity, so its 1x1 system
//      is solved in closed form: v = v0 + h a0 / (1 + h c / m).
// Fixed particles (mass 0) are filtered: their rows and columns are the identity with a zero
// right-hand side, so dv = 0 for them exactly, whatever the number of CG iterations.
//
// The system is solved by a Jacobi-preconditioned conjugate gradient on an Eigen sparse matrix.
// It is the algorithm of Eigen's ConjugateGradient with DiagonalPreconditioner, written out on
// work vectors sized once, because Eigen's allocates its work vectors in every solve (a test
// checks the two agree). Stopping rule: |r| <= tolerance * |b| (Euclidean norms), or
// max_iterations. The matrix pattern is built once; a step allocates nothing.
#pragma once

#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "clothref/core/world.h"

namespace clothref {

// CG stopping rule. Defaults: tolerance 1e-10 in double and 1e-5 in float (about 100 float
// epsilons: the residual of a float solve cannot go much lower), at most 1000 iterations.
struct CgSettings {
  double tolerance = 0;  // 0: the precision's default above
  int max_iterations = 1000;
};

// What the solves have done so far.
struct CgStats {
  std::int64_t solves = 0;
  std::int64_t iterations = 0;  // summed over solves
  int max_iterations_seen = 0;  // the most one solve needed
  std::int64_t capped = 0;      // solves that stopped at max_iterations
  double last_relative_residual = 0;

  double meanIterations() const { return solves ? double(iterations) / double(solves) : 0.0; }
};

// Everything a backward-Euler step needs, sized on the first step for the world it is used with.
// It is the world's MethodStepper for Method::BackwardEuler (installBackwardEuler).
template <typename T>
struct BackwardEulerSolver final : MethodStepper<T> {
  CgSettings settings;
  CgStats stats;

  // sparsity pattern (row-major, 3N x 3N) and where each spring writes in it
  Eigen::SparseMatrix<T, Eigen::RowMajor> matrix;
  std::vector<int> spring_slots;    // per spring, 4 blocks x 9 entries: (s,s) (e,e) (s,e) (e,s)
  std::vector<int> diagonal_slots;  // per particle, 3 entries (x, y, z)
  std::vector<int> filtered_slots;  // entries in a fixed particle's row or column (set to 0)
  std::vector<int> fixed_diagonal_slots;  // the diagonal of fixed particles (set to 1)
  int particles = -1;                     // the cloth size the pattern was built for
  std::size_t springs = 0;

  // CG work vectors, 3N
  VecX<T> rhs, dv, residual, direction, z, product, inverse_diagonal;

  void integrate(World<T>& world) override;
};

// Builds the pattern for `cloth` (done by the first step; call again if the topology changes).
template <typename T>
void prepareBackwardEuler(const Cloth<T>& cloth, BackwardEulerSolver<T>& solver);

// Makes `world` step by backward Euler: sets its method and installs a solver as its stepper
// (pattern built now when the world has a cloth). makeWorld does this for Method::BackwardEuler.
template <typename T>
void installBackwardEuler(World<T>& world);

// The backward-Euler solver installed in `world`, or nullptr (for its CG statistics).
template <typename T>
BackwardEulerSolver<T>* backwardEulerSolver(World<T>& world);
template <typename T>
const BackwardEulerSolver<T>* backwardEulerSolver(const World<T>& world);

// The body of one backward-Euler step (steps 1-3 above): simulateOneStep and the update of every
// body. World::step calls it through the stepper, with the frame's work before and the step count
// after.
template <typename T>
void integrateBackwardEuler(World<T>& world, BackwardEulerSolver<T>& solver);

// Solves A x = b with the Jacobi-preconditioned CG above, starting from x = 0. `solver` supplies
// the work vectors (sized to b). Returns the iterations; updates solver.stats.
template <typename T>
int solveConjugateGradient(const Eigen::SparseMatrix<T, Eigen::RowMajor>& matrix, const VecX<T>& b,
                           VecX<T>& x, BackwardEulerSolver<T>& solver);

// The tolerance actually used for precision T.
template <typename T>
double cgTolerance(const CgSettings& settings);

}  // namespace clothref
