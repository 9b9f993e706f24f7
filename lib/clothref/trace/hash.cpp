#include "clothref/trace/hash.h"

// XXH3_state_t on the stack needs the static-linking declarations
#define XXH_STATIC_LINKING_ONLY
#include <xxhash.h>

#include <bit>

#include <fmt/format.h>

namespace clothref {

namespace {

// Feeds x, y, z of every 4-value column (skipping w, which the trace does not carry).
template <typename T>
void hashColumns(XXH3_state_t* state, const T* columns, int count) {
  for (int i = 0; i < count; ++i) XXH3_64bits_update(state, columns + 4 * i, 3 * sizeof(T));
}

}  // namespace

template <typename T>
std::uint64_t stateHash(std::span<const BodyView<T>> bodies) {
  static_assert(std::endian::native == std::endian::little,
                "the trace hash is defined on little-endian bytes");
  XXH3_state_t state;
  XXH3_64bits_reset(&state);
  for (const BodyView<T>& body : bodies) {
    hashColumns(&state, body.position, body.particles);
    hashColumns(&state, body.velocity, body.particles);
  }
  return XXH3_64bits_digest(&state);
}

std::string hashToHex(std::uint64_t hash) { return fmt::format("{:016x}", hash); }

template std::uint64_t stateHash(std::span<const BodyView<float>>);
template std::uint64_t stateHash(std::span<const BodyView<double>>);

}  // namespace clothref
