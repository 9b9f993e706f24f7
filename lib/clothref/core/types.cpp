#include "clothref/core/types.h"

namespace clothref {

std::string_view precisionName(Precision precision) {
  return precision == Precision::Float ? "float" : "double";
}

bool parsePrecision(std::string_view name, Precision& precision) {
  if (name == "float") {
    precision = Precision::Float;
    return true;
  }
  if (name == "double") {
    precision = Precision::Double;
    return true;
  }
  return false;
}

}  // namespace clothref
