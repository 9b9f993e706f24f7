#include "clothref/core/cloth.h"

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

  const T structural_length = (x.col(0) - x.col(1)).norm();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - 1; ++j)
      add(i * n + j, i * n + j + 1, structural_length, SpringType::Structural);
  for (int i = 0; i < n - 1; ++i)
    for (int j = 0; j < n; ++j)
      add(i * n + j, i * n + j + n, structural_length, SpringType::Structural);

  const T shear_length = (x.col(0) - x.col(n + 1)).norm();
  for (int i = 0; i < n - 1; ++i)
    for (int j = 0; j < n - 1; ++j)
      add(i * n + j, i * n + j + n + 1, shear_length, SpringType::Shear);
  for (int i = 0; i < n - 1; ++i)
    for (int j = 1; j < n; ++j) add(i * n + j, i * n + j + n - 1, shear_length, SpringType::Shear);

  // a 2 x 2 cloth has no bend springs (and no particle 2 in its first row)
  if (n < 3) return;
  const T bend_length = (x.col(0) - x.col(2)).norm();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - 2; ++j) add(i * n + j, i * n + j + 2, bend_length, SpringType::Bend);
  for (int i = 0; i < n - 2; ++i)
    for (int j = 0; j < n; ++j) add(i * n + j, i * n + j + 2 * n, bend_length, SpringType::Bend);
}

template <typename T>
void computeSpringForce(Cloth<T>& cloth) {
  Particles<T>& p = cloth.particles;
  const T k_s = cloth.spring_coef;
  const T k_d = cloth.damper_coef;
  for (const Spring<T>& spring : cloth.springs) {
    const int s = static_cast<int>(spring.start);
    const int e = static_cast<int>(spring.end);
    // Eigen's 4-wide norm, normalize and dot: the course's own reductions, so the bits match
    Vec4<T> d = p.position.col(s) - p.position.col(e);
    const T length = d.norm();
    d.normalize();
    const Vec4<T> force = d * (k_d * (p.velocity.col(s) - p.velocity.col(e)).dot(d) +
                               k_s * (length - spring.rest_length));
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
