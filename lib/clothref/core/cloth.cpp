#include "clothref/core/cloth.h"

#include "clothref/formula/course_formulas.h"

namespace clothref {

template <typename T>
Particles<T> initializeVertex(int particles_per_edge, T half_extent, T y, T particle_mass) {
  const int n = particles_per_edge;
  Particles<T> particles = makeParticles<T>(n * n, particle_mass);
  // the course writes 2.0f * clothWidth / (particlesPerEdge - 1): one rounding, in T
  const T step = T(2) * half_extent / T(n - 1);
  int current = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      // two roundings per coordinate, as the course's -clothWidth + j * wStep
      particles.position.col(current++) =
          Vec4<T>(-half_extent + T(j) * step, y, -half_extent + T(i) * step, T(1));
    }
  }
  return particles;
}

template <typename T>
void initializeSpring(Cloth<T>& cloth, int particles_per_edge) {
  const int n = particles_per_edge;
  const Mat4X<T>& x = cloth.particles.position;
  auto add = [&cloth](int start, int end, T rest_length, SpringType type) {
    cloth.springs.push_back(Spring<T>{static_cast<std::uint32_t>(start),
                                      static_cast<std::uint32_t>(end), rest_length, type});
  };
  cloth.springs.reserve(cloth.springs.size() + 2 * n * (n - 1) + 2 * (n - 1) * (n - 1) +
                        (n > 2 ? 2 * n * (n - 2) : 0));

  // rest lengths measured once from the first particles, as the course does; a 2 x 2 cloth has
  // no bend springs (and no particle 2 in its first row)
  const T structural_length = (x.col(0) - x.col(1)).norm();
  const T shear_length = (x.col(0) - x.col(n + 1)).norm();
  const T bend_length = n < 3 ? T(0) : (x.col(0) - x.col(2)).norm();
  // the course's six passes, in push order (course_formulas.h, shared with fast::matchCourseGrid)
  formula::forEachGridSpring(n, [&](int family, int start, int end) {
    switch (formula::kGridFamilyRest[family]) {
      case formula::GridRest::Structural:
        return add(start, end, structural_length, SpringType::Structural);
      case formula::GridRest::Shear:
        return add(start, end, shear_length, SpringType::Shear);
      case formula::GridRest::Bend:
        return add(start, end, bend_length, SpringType::Bend);
    }
  });
}

template <typename T>
void computeSpringForce(Cloth<T>& cloth) {
  Particles<T>& p = cloth.particles;
  const T k_s = cloth.spring_coef;
  const T k_d = cloth.damper_coef;
  for (const Spring<T>& spring : cloth.springs) {
    const int s = static_cast<int>(spring.start);
    const int e = static_cast<int>(spring.end);
    // F = n (k_d ((v_s - v_e) . n) + k_s (|x_s - x_e| - rest)), n = (x_s - x_e) / |x_s - x_e|:
    // course_formulas.h, in the order of Eigen's 4-wide reductions, so the bits are the course's
    Vec4<T> force;
    formula::springForce(p.position.col(s).data(), p.position.col(e).data(),
                         p.velocity.col(s).data(), p.velocity.col(e).data(), spring.rest_length,
                         k_s, k_d, force.data());
    p.acceleration.col(s) -= force * p.inverse_mass[s];
    p.acceleration.col(e) += force * p.inverse_mass[e];
  }
}

template Particles<float> initializeVertex(int, float, float, float);
template Particles<double> initializeVertex(int, double, double, double);
template void initializeSpring(Cloth<float>&, int);
template void initializeSpring(Cloth<double>&, int);
template void computeSpringForce(Cloth<float>&);
template void computeSpringForce(Cloth<double>&);

}  // namespace clothref
