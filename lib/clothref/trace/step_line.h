// One trace step line (docs/trace-format.md): {"step":S,"t":T,"hash":"H","bodies":{"cloth":
// {"position":[[x,y,z],...],"velocity":[...]},"spheres":{...}}} and a newline. Numbers are
// shortest round-trip text in T's precision; non-finite values are the strings "NaN", "Infinity"
// and "-Infinity", so a blown-up run is still valid JSON.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "clothref/trace/body_view.h"

namespace clothref {

// Appends the line for `bodies` at step `step`, time `t` (seconds), hashing them (trace/hash.h).
template <typename T>
void appendStepLine(std::string& out, std::int64_t step, double t,
                    std::span<const BodyView<T>> bodies);

}  // namespace clothref
