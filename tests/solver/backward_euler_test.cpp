// Backward Euler (solver/backward_euler.h): the step is the linearised implicit step (checked
// against a hand solve on a linear spring), its CG agrees with Eigen's ConjugateGradient, fixed
// particles do not move, it is first order, it stays stable on course2022 at 10x the explicit
// methods' limit, and a step allocates nothing once sized.
#include "clothref/solver/backward_euler.h"

#include <gtest/gtest.h>

#include <Eigen/IterativeLinearSolvers>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "clothref/analysis/stability.h"
#include "clothref/scene/make_world.h"
#include "clothref/solver/backward_euler.h"
#include "clothref/verify/analytic.h"
#include "clothref/verify/verify.h"

// Counts every allocation of this test binary, to check that a step makes none.
namespace {
std::atomic<long> g_allocations{0};
}
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace clothref {
namespace {

const Scene& scene(const char* name) {
  const Scene* found = findBuiltinScene(name);
  if (!found) throw std::runtime_error(std::string("no scene ") + name);
  return *found;
}

TEST(BackwardEuler, OneStepOnALinearSpringIsTheImplicitSolve) {
  // 1-D along the spring's axis the spring is linear, so the linearised step is exact backward
  // Euler: v1 (1 + h delta + h^2 kappa) = v0 - h kappa (x0 - x_eq), x1 = x0 + h v1
  const Scene& spring = scene("spring");
  const SpringProblem problem = springProblem(spring);
  const double kappa = problem.oscillator.stiffness / problem.oscillator.mass;
  const double delta = problem.oscillator.damping / problem.oscillator.mass;
  for (double h : {1e-3, 0.05, 0.5}) {
    World<double> sim = makeWorld<double>(spring, Method::BackwardEuler, h);
    const double x_eq = problem.rest_length;
    double x = 1.2, v = 0;
    for (int s = 0; s < 5; ++s) {
      step(sim);
      v = (v - h * kappa * (x - x_eq)) / (1 + h * delta + h * h * kappa);
      x = x + h * v;
      EXPECT_NEAR(sim.cloth->particles.position(0, 1), x, 1e-12 * (1 + std::abs(x))) << h;
      EXPECT_NEAR(sim.cloth->particles.velocity(0, 1), v, 1e-12 * (1 + std::abs(v))) << h;
    }
  }
}

template <typename T>
void expectAgreesWithEigen(double tolerance) {
  World<T> sim = makeWorld<T>(scene("course2022"), Method::BackwardEuler, 2e-3);
  for (int s = 0; s < 3; ++s) step(sim);  // a sagging, moving cloth
  const BackwardEulerSolver<T>& solver = *backwardEulerSolver(sim);
  Eigen::ConjugateGradient<Eigen::SparseMatrix<T, Eigen::RowMajor>, Eigen::Lower | Eigen::Upper,
                           Eigen::DiagonalPreconditioner<T>>
      eigen;
  eigen.setTolerance(T(cgTolerance<T>(solver.settings)));
  eigen.setMaxIterations(solver.settings.max_iterations);
  eigen.compute(solver.matrix);
  const VecX<T> expected = eigen.solve(solver.rhs);
  ASSERT_EQ(eigen.info(), Eigen::Success);
  EXPECT_LE(double((expected - solver.dv).norm()), tolerance * double(expected.norm()));
  // both reached the stated residual on the same system
  EXPECT_LE(double((solver.matrix * solver.dv - solver.rhs).norm()),
            10 * cgTolerance<T>(solver.settings) * double(solver.rhs.norm()));
  EXPECT_GT(solver.stats.meanIterations(), 1.0);
  EXPECT_EQ(solver.stats.capped, 0);
}

TEST(BackwardEuler, ConjugateGradientAgreesWithEigens) {
  expectAgreesWithEigen<double>(1e-8);
  expectAgreesWithEigen<float>(1e-3);
}

TEST(BackwardEuler, FixedParticlesStayPut) {
  World<float> sim = makeWorld<float>(scene("course2022"), Method::BackwardEuler, 4e-3);
  const Mat4X<float> start = sim.cloth->particles.position;
  for (int s = 0; s < 50; ++s) step(sim);  // 0.2 s: before the spheres arrive
  for (int corner : {0, 24, 600, 624}) {
    EXPECT_EQ(sim.cloth->particles.velocity.col(corner).norm(), 0.0f);
    EXPECT_EQ(sim.cloth->particles.position.col(corner), start.col(corner));
  }
  // while the free cloth fell
  EXPECT_LT(sim.cloth->particles.position(1, 312), -0.01f);
}

TEST(BackwardEuler, IsFirstOrderOnTheDampedSpring) {
  const Scene& spring = scene("spring");
  const SpringProblem problem = springProblem(spring);
  std::vector<double> dts, errors;
  for (double dt : {1e-2, 5e-3, 2.5e-3, 1.25e-3, 6.25e-4}) {
    World<double> sim = makeWorld<double>(spring, Method::BackwardEuler, dt);
    const int steps = static_cast<int>(std::lround(1.0 / dt));
    double worst = 0;
    for (int s = 1; s <= steps; ++s) {
      step(sim);
      const double exact = springState(problem, s * dt).position[0];
      worst = std::max(worst, std::abs(sim.cloth->particles.position(0, 1) - exact));
    }
    dts.push_back(dt);
    errors.push_back(worst);
  }
  // the same fit and tolerance as clothref verify's order checks
  EXPECT_NEAR(fitOrder(dts, errors), 1.0, 0.2);
}

TEST(BackwardEuler, StaysStableOnCourse2022AtTenTimesTheExplicitLimit) {
  const Scene& course = scene("course2022");
  const StabilityCriterion criterion = stabilityCriterion(course);
  // the largest limit of the explicit-type methods (RK4's, about 3.7e-4 s) times 10, rounded up
  const double dt = 4e-3;
  EXPECT_TRUE(runIsStable(course, Method::BackwardEuler, Precision::Float, dt, criterion));
  EXPECT_TRUE(runIsStable(course, Method::BackwardEuler, Precision::Double, dt, criterion));
  // the criterion can fail: the explicit methods blow up there
  EXPECT_FALSE(runIsStable(course, Method::Rk4, Precision::Float, dt, criterion));
}

template <typename T>
long allocationsPerSteps(const char* name, int steps) {
  World<T> sim = makeWorld<T>(scene(name), Method::BackwardEuler, 2e-3);
  step(sim);
  step(sim);
  const long before = g_allocations.load();
  for (int s = 0; s < steps; ++s) step(sim);
  return g_allocations.load() - before;
}

TEST(BackwardEuler, AllocatesNothingPerStepOnceSized) {
  EXPECT_EQ(allocationsPerSteps<float>("course2022", 20), 0);
  EXPECT_EQ(allocationsPerSteps<double>("course2022", 20), 0);
  EXPECT_EQ(allocationsPerSteps<double>("spring", 20), 0);
  // the counter counts: building a world allocates
  const long before = g_allocations.load();
  makeWorld<float>(scene("spring"), Method::BackwardEuler);
  EXPECT_GT(g_allocations.load() - before, 0);
}

}  // namespace
}  // namespace clothref
