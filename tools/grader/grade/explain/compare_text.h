// Numbers as every output shows them, and the one way a probe writes an expected value beside the
// student's: the components beyond the tolerance marked, by how much and how many tolerances
// (docs/grading-reference.md, "Reading a check"; report/outputs.h's kNumberLegend says it once in
// every report).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace clothref::grader::util {

namespace detail {
inline std::string printed(const char* format, double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, format, value == 0 ? 0.0 : value);  // never "-0"
  return buffer;
}
// True when %.6g writes `value` in scientific notation.
inline bool needsScientific(double value) {
  const double a = std::abs(value);
  return std::isfinite(a) && a != 0 && (a < 1e-4 || a >= 999999.5);
}
}  // namespace detail

// A number: 6 significant digits, trailing zeros dropped, decimal from 1e-4 up to 1e6 and
// scientific outside (C's %.6g); "NaN", "inf", "-inf" for the values that are not finite.
inline std::string num(double value) { return detail::printed("%.6g", value); }

// Numbers that are read together (one vector, one comparison): all in %.6g when each is decimal
// there, else each nonzero one in scientific notation with 6 significant digits, so -0.000371004
// never stands beside 7.45961e-05.
inline std::vector<std::string> nums(const std::vector<double>& values) {
  bool scientific = false;
  for (double v : values) scientific = scientific || detail::needsScientific(v);
  std::vector<std::string> out;
  for (double v : values)
    out.push_back(scientific && v != 0 && std::isfinite(v) ? detail::printed("%.5e", v) : num(v));
  if (!scientific) return out;
  // %.5e keeps trailing zeros: drop them as %.6g does ("1.50000e-05" -> "1.5e-05")
  for (std::string& s : out) {
    const std::size_t e = s.find('e');
    if (e == std::string::npos || s.find('.') == std::string::npos) continue;
    std::size_t end = e;
    while (end > 0 && s[end - 1] == '0') --end;
    if (end > 0 && s[end - 1] == '.') --end;
    s.erase(end, e - end);
  }
  return out;
}

// A ratio to a tolerance, or a tolerance: 2 significant digits, decimal up to 1e6 for a ratio
// ("4.5", "410", "82000"), as %.2g otherwise ("1.1e-05", "3.4e+07").
inline std::string ratio(double value) {
  if (!(value >= 10 && value < 1e6)) return detail::printed("%.2g", value);
  const double unit = std::pow(10.0, std::floor(std::log10(value)) - 1);
  return detail::printed("%.0f", std::round(value / unit) * unit);
}
inline std::string tolerance(double value) { return detail::printed("%.2g", value); }

// A 3-vector "(x, y, z)" of one notation.
template <typename V>
std::string vec3(const V& v) {
  const std::vector<std::string> s = nums({double(v[0]), double(v[1]), double(v[2])});
  return "(" + s[0] + ", " + s[1] + ", " + s[2] + ")";
}

// What a comparison allows a component: absolute + relative * |expected| (the probes' rule
// |yours - expected| <= rel (1 + |expected|) is {rel, rel}).
struct Tolerance {
  double absolute = 0;
  double relative = 0;
  double of(double expected) const {
    return absolute + relative * (std::isfinite(expected) ? std::abs(expected) : 0.0);
  }
};

// One quantity, expected beside the student's, as a Markdown list item:
//   - v of sphere 0 after the call: expected (1, **-0.8**, 0) m/s, yours (1, **0.8**, 0) m/s
//     - y differs by 1.6 = 89000 x the tolerance (1.8e-05)
// A component differs when |yours - expected| exceeds the tolerance or either is not finite;
// none differing: "..., yours (...) m/s: the same within the tolerance". Several differing: one
// line, "x differs by ... (...); z by ... = 12 x (...)". `indent` is prefixed to both lines (a
// nested item). `names` name the components ("x", "y", "z" for three).
inline std::string compareValues(const std::string& label, const std::vector<double>& expected,
                                 const std::vector<double>& actual, Tolerance tolerance,
                                 const std::string& unit = "", const std::string& indent = "",
                                 std::vector<std::string> names = {}) {
  const std::size_t n = std::min(expected.size(), actual.size());
  if (names.size() < n)
    names = n == 3 ? std::vector<std::string>{"x", "y", "z"} : std::vector<std::string>(n, "");
  std::vector<bool> differs(n, false);
  for (std::size_t k = 0; k < n; ++k)
    differs[k] = !(std::abs(actual[k] - expected[k]) <= tolerance.of(expected[k]));
  std::vector<double> values(expected.begin(), expected.begin() + long(n));
  values.insert(values.end(), actual.begin(), actual.begin() + long(n));
  const std::vector<std::string> text = nums(values);
  const auto listed = [&](std::size_t offset) {
    std::string out = n == 1 ? "" : "(";
    for (std::size_t k = 0; k < n; ++k) {
      const std::string& value = text[offset + k];
      out += (k ? ", " : "") + (differs[k] ? "**" + value + "**" : value);
    }
    return out + (n == 1 ? "" : ")") + (unit.empty() ? "" : " " + unit);
  };
  std::string out = indent + "- " + label + ": expected " + listed(0) + ", yours " + listed(n);
  // the differing components on one line: "x differs by 0.0045 = 410 x the tolerance (1.1e-05);
  // y by 0.019 = 1300 x (1.4e-05)"
  std::string notes;
  for (std::size_t k = 0; k < n; ++k) {
    if (!differs[k]) continue;
    const bool first = notes.empty();
    notes += first ? "" : "; ";
    const std::string what = names[k].empty() ? "it" : names[k];
    const double d = std::abs(actual[k] - expected[k]), tol = tolerance.of(expected[k]);
    if (!std::isfinite(d)) {
      notes += what + ": " + (std::isfinite(actual[k]) ? "the expected value" : "yours") +
               " is not finite";
      continue;
    }
    notes += what + (first ? " differs by " : " by ") + num(d) +
             (tol > 0 ? " = " + ratio(d / tol) + (first ? " x the tolerance (" : " x (") +
                            util::tolerance(tol) + ")"
                      : std::string(" (the tolerance is 0: equal bit for bit)"));
  }
  return out + (notes.empty() ? ": the same within the tolerance\n"
                              : "\n" + indent + "  - " + notes + "\n");
}

// compareValues for two 3-vectors (Eigen columns, std::array, anything with [0..2]).
template <typename E, typename A>
std::string compareVectors(const std::string& label, const E& expected, const A& actual,
                           Tolerance tolerance, const std::string& unit = "",
                           const std::string& indent = "") {
  return compareValues(label, {double(expected[0]), double(expected[1]), double(expected[2])},
                       {double(actual[0]), double(actual[1]), double(actual[2])}, tolerance, unit,
                       indent);
}

// compareValues for one number.
inline std::string compareNumbers(const std::string& label, double expected, double actual,
                                  Tolerance tolerance, const std::string& unit = "",
                                  const std::string& indent = "") {
  return compareValues(label, {expected}, {actual}, tolerance, unit, indent);
}

}  // namespace clothref::grader::util
