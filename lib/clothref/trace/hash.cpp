#include "clothref/trace/hash.h"

// XXH3_state_t on the stack needs the static-linking declarations
#define XXH_STATIC_LINKING_ONLY
#include <xxhash.h>

#include <bit>

#include <fmt/format.h>

namespace clothref {

namespace {

// Feeds x, y, z of every column of a 4 x N matrix (skipping w, which the trace does not carry).
template <typename T>
void hashColumns(XXH3_state_t* state, const Mat4X<T>& m) {
  for (Eigen::Index i = 0; i < m.cols(); ++i) XXH3_64bits_update(state, m.col(i).data(), 3 * sizeof(T));
}

}  // namespace

template <typename T>
std::uint64_t stateHash(const World<T>& world) {
  static_assert(std::endian::native == std::endian::little, "the trace hash is defined on little-endian bytes");
  XXH3_state_t state;
  XXH3_64bits_reset(&state);
  auto body = [&state](const Particles<T>& p) {
    hashColumns(&state, p.position);
    hashColumns(&state, p.velocity);
  };
  if (world.cloth) body(world.cloth->particles);
  if (world.spheres) body(world.spheres->particles);
  return XXH3_64bits_digest(&state);
}

std::string hashToHex(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

template std::uint64_t stateHash(const World<float>&);
template std::uint64_t stateHash(const World<double>&);

}  // namespace clothref
