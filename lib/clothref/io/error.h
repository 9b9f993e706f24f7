// InputError: bad input from a user (a file, a flag, a scene). what() is one line naming the file
// or field and the problem; the CLI prints it and exits 2.
#pragma once

#include <stdexcept>
#include <string>

namespace clothref {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace clothref
