// Rendering a verify report: JSON (`clothref verify --json`) and the text table.
#include "clothref/verify/verify.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <random>

#include "clothref/core/world.h"
#include "clothref/scene/make_world.h"
#include "clothref/solver/backward_euler.h"
#include "clothref/verify/analytic.h"
#include "clothref/verify/check_support.h"

namespace clothref {

using namespace verify_support;

nlohmann::ordered_json reportToJson(const VerifyReport& report) {
  using ordered_json = nlohmann::ordered_json;
  ordered_json orders = ordered_json::object();
  ordered_json floors = ordered_json::object();
  for (const ConvergenceStudy& study : report.studies) {
    const std::string method(methodName(study.method));
    const std::string precision(precisionName(study.precision));
    orders[method][precision] = study.order ? ordered_json(*study.order) : ordered_json(nullptr);
    if (study.precision == Precision::Float)
      floors[method] = *std::max_element(study.roundoff.begin(), study.roundoff.end());
  }
  ordered_json studies = ordered_json::array();
  for (const ConvergenceStudy& study : report.studies) {
    studies.push_back(
        {{"scene", "spring"},
         {"method", methodName(study.method)},
         {"precision", precisionName(study.precision)},
         {"expected_order", study.expected_order},
         {"end_time", study.end_time},
         {"fit", "least squares of log error on log dt over the fitted points"},
         {"dts", study.dts},
         {"errors", study.errors},
         {"roundoff", study.roundoff},
         {"fitted", study.fitted},
         {"order", study.order ? ordered_json(*study.order) : ordered_json(nullptr)}});
  }
  ordered_json checks = ordered_json::array();
  for (const CheckRow& row : report.checks) {
    checks.push_back({{"check", row.check},
                      {"method", row.method},
                      {"precision", precisionName(row.precision)},
                      {"expected", row.expected},
                      {"observed", row.observed},
                      {"tolerance", row.tolerance},
                      {"rule", row.rule == CheckRule::Within ? "within" : "at_most"},
                      {"pass", row.pass}});
  }
  return {{"orders", orders},
          {"float_floor", floors},
          {"studies", studies},
          {"checks", checks},
          {"passed", report.passed()}};
}

std::string reportTable(const VerifyReport& report) {
  // every column as wide as its longest entry (a method name like backward-euler, "<= 1e-05")
  const auto expectedText = [](const CheckRow& row) {
    return row.rule == CheckRule::AtMost ? fmt::format("<= {:.6g}", row.expected)
                                         : fmt::format("{:.6g}", row.expected);
  };
  std::size_t width = 5, method_width = 6, expected_width = 8;
  for (Method method : kAllMethods)
    method_width = std::max(method_width, std::string(methodName(method)).size());
  for (const CheckRow& row : report.checks) {
    width = std::max(width, row.check.size());
    method_width = std::max(method_width, row.method.size());
    expected_width = std::max(expected_width, expectedText(row).size());
  }
  std::string table = fmt::format("{:<{}}  {:<{}}  {:<6}  {:>{}}  {:>12}  {:>10}  {}\n", "check",
                                  width, "method", method_width, "prec", "expected", expected_width,
                                  "observed", "tolerance", "pass");
  int failed = 0;
  for (const CheckRow& row : report.checks) {
    table +=
        fmt::format("{:<{}}  {:<{}}  {:<6}  {:>{}}  {:>12.4e}  {:>10.3e}  {}\n", row.check, width,
                    row.method, method_width, precisionName(row.precision), expectedText(row),
                    expected_width, row.observed, row.tolerance, row.pass ? "yes" : "NO");
    failed += row.pass ? 0 : 1;
  }
  // one line per method: the orders side by side, and where the float floor lies
  table +=
      "\norders on spring (least squares of log error on log dt, pass |p - expected| <= 0.2);\n"
      "float floor = largest |x_float - x_double| in the ladder; null = < 3 dt above 10x floor:\n";
  for (Method method : kAllMethods) {
    std::string line = fmt::format("  {:<{}}  expected {}", methodName(method), method_width,
                                   methodInfo(method).order);
    for (const ConvergenceStudy& study : report.studies) {
      if (study.method != method) continue;
      line += fmt::format("  {} {}", precisionName(study.precision),
                          study.order ? fmt::format("{:.3f}", *study.order) : "null");
      if (study.precision == Precision::Float)
        line += fmt::format("  float floor {:.2e} m",
                            *std::max_element(study.roundoff.begin(), study.roundoff.end()));
    }
    table += line + "\n";
  }
  table += fmt::format("\n{} checks, {} failed\n", report.checks.size(), failed);
  return table;
}

}  // namespace clothref
