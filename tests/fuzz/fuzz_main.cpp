// The libFuzzer entry point of one target, chosen at compile time (CLOTHREF_FUZZ_TARGET names a
// function of fuzz_targets.h). Built only with -DCLOTHREF_FUZZ=ON (clang, ASan + UBSan).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    clothref::fuzz::CLOTHREF_FUZZ_TARGET(
        std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const clothref::InputError&) {
    // bad input, reported as one line by the CLI: the expected outcome
  }
  return 0;
}
