// Rendering a DiffReport: the text report, its JSON form, and the observed tolerances file.
#include "clothref/diff/diff.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "clothref/diff/diff_support.h"
#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"
#include "clothref/trace/format.h"
#include "clothref/trace/reader.h"

namespace clothref {

using namespace diff_support;

namespace {

using json = nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Formatting

const char* const kComponentNames[] = {"x", "y", "z"};

std::string formatValue(double value, Precision precision) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "Infinity" : "-Infinity";
  return precision == Precision::Float ? fmt::format("{}", static_cast<float>(value))
                                       : fmt::format("{}", value);
}

ordered_json jsonNumber(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "Infinity" : "-Infinity";
  return value;
}

ordered_json jsonUlps(std::uint64_t ulps) {
  return ulps == kInfiniteUlps ? ordered_json("Infinity") : ordered_json(ulps);
}

std::string describeTolerance(const Tolerance& t) {
  std::string text;
  switch (t.mode) {
    case ToleranceMode::Ulps:
      text = t.ulps == 0 ? "exact" : fmt::format("{} ulp", t.ulps);
      break;
    case ToleranceMode::Absolute:
      text = fmt::format("abs {:g}", t.abs);
      break;
    case ToleranceMode::Relative:
      text = fmt::format("rel {:g}", t.rel);
      break;
    case ToleranceMode::Combined:
      text = fmt::format("abs {:g} or rel {:g}", t.abs, t.rel);
      break;
  }
  if (t.floor > 0) text += fmt::format(", floor {:g}", t.floor);
  return text;
}

std::string where(const ValueDiff& d) {
  if (d.field == Field::Time) return fmt::format("step {}: time", d.step);
  return fmt::format("step {} (t {}): {} {} particle {} {}", d.step, d.t, d.body,
                     fieldName(d.field), d.particle, kComponentNames[d.component]);
}

std::string describeValue(const ValueDiff& d, Precision precision) {
  const Precision p = d.field == Field::Time ? Precision::Double : precision;
  const std::string ulps = d.ulps == kInfiniteUlps ? "inf" : fmt::format("{}", d.ulps);
  return fmt::format("{}: {} vs {} (abs {:.3g}, rel {:.3g}, {} ulp)", where(d), formatValue(d.a, p),
                     formatValue(d.b, p), d.abs, d.rel, ulps);
}

ordered_json valueToJson(const ValueDiff& d) {
  ordered_json out;
  out["step"] = d.step;
  out["t"] = d.t;
  out["body"] = d.field == Field::Time ? ordered_json(nullptr) : ordered_json(d.body);
  out["field"] = fieldName(d.field);
  out["particle"] = d.particle < 0 ? ordered_json(nullptr) : ordered_json(d.particle);
  out["component"] =
      d.component < 0 ? ordered_json(nullptr) : ordered_json(kComponentNames[d.component]);
  out["a"] = jsonNumber(d.a);
  out["b"] = jsonNumber(d.b);
  out["abs"] = jsonNumber(d.abs);
  out["rel"] = jsonNumber(d.rel);
  out["ulps"] = jsonUlps(d.ulps);
  return out;
}

// Arrays of different lengths (sphere lists, particle lists) are summarised by their length.
std::string describeHeaderValue(const ordered_json& value) {
  if (value.is_array()) return fmt::format("{} items", value.size());
  return compact(value);
}

std::string fieldLabel(const FieldStats& stats) {
  return stats.field == Field::Time ? "time"
                                    : stats.body + " " + std::string(fieldName(stats.field));
}

}  // namespace

std::string formatReport(const DiffReport& r) {
  std::string out;
  const std::int64_t significant = std::count_if(r.header_diffs.begin(), r.header_diffs.end(),
                                                 [](const HeaderDiff& d) { return d.significant; });
  const std::string step_counts = r.steps_a == r.steps_b && r.steps_a == r.steps_compared
                                      ? fmt::format("{} steps", r.steps_compared)
                                      : fmt::format("{} common steps ({} in A, {} in B)",
                                                    r.steps_compared, r.steps_a, r.steps_b);
  if (r.verdict == Verdict::Identical) {
    out += fmt::format("identical: {} vs {}: {}, {} values\n", r.path_a, r.path_b, step_counts,
                       r.values_compared);
  } else {
    std::string summary;
    if (significant) summary += fmt::format("{} header differences, ", significant);
    summary += fmt::format("{} of {} values beyond tolerance", r.values_beyond, r.values_compared);
    out += fmt::format("{}: {} vs {}: {}; {}\n",
                       r.verdict == Verdict::Differ ? "DIFFER" : "within tolerance", r.path_a,
                       r.path_b, step_counts, summary);
  }
  for (const HeaderDiff& d : r.header_diffs)
    out += fmt::format("  {} {}: {} vs {}\n", d.significant ? "header" : "info  ", d.pointer,
                       describeHeaderValue(d.a), describeHeaderValue(d.b));
  if (r.verdict == Verdict::Identical) return out;

  out += fmt::format("  steps  {} compared, {} skipped (equal hash and bytes)", r.steps_compared,
                     r.steps_equal_hash);
  if (r.steps_equal_values_different_hash)
    out += fmt::format(", {} with equal values but different hashes (-0 vs +0?)",
                       r.steps_equal_values_different_hash);
  out += '\n';
  if (r.first_beyond)
    out += fmt::format("  first  {}; {} beyond tolerance in that step\n",
                       describeValue(*r.first_beyond, r.precision), r.first_step_beyond_count);
  if (r.worst) out += fmt::format("  worst  {}\n", describeValue(*r.worst, r.precision));
  bool table = false;
  for (const FieldStats& s : r.fields) {
    if (!s.anyDifference()) continue;
    if (!table) {
      out += fmt::format("  {:<18} {:<22} {:>21} {:>10} {:>10} {:>10} {:>10} {:>12}\n", "field",
                         "tolerance", "beyond/compared", "max abs", "mean abs", "max rel",
                         "mean rel", "max ulp");
      table = true;
    }
    std::string beyond = fmt::format("{}/{}", s.beyond, s.compared);
    out += fmt::format("  {:<18} {:<22} {:>21} {:>10.3g} {:>10.3g} {:>10.3g} {:>10.3g} {:>12}\n",
                       fieldLabel(s), describeTolerance(s.tolerance), beyond, s.max_abs,
                       s.meanAbs(), s.max_rel, s.meanRel(), s.max_ulps);
    if (s.nonfinite_mismatches)
      out += fmt::format("  {:<18} {} finite vs non-finite (or NaN vs Infinity) values\n", "",
                         s.nonfinite_mismatches);
  }
  return out;
}

ordered_json reportToJson(const DiffReport& r) {
  ordered_json out;
  out["verdict"] = enumName(kVerdictNames, r.verdict);
  out["a"] = r.path_a;
  out["b"] = r.path_b;
  out["precision"] = std::string(precisionName(r.precision));
  ordered_json headers = ordered_json::array();
  for (const HeaderDiff& d : r.header_diffs) {
    ordered_json entry = {{"pointer", d.pointer}};
    // a key missing on one side is left out of the entry
    if (!d.a.is_discarded()) entry["a"] = d.a;
    if (!d.b.is_discarded()) entry["b"] = d.b;
    entry["significant"] = d.significant;
    headers.push_back(std::move(entry));
  }
  out["header_differences"] = headers;
  out["steps"] = {{"a", r.steps_a},
                  {"b", r.steps_b},
                  {"compared", r.steps_compared},
                  {"skipped_equal_hash", r.steps_equal_hash},
                  {"equal_values_different_hash", r.steps_equal_values_different_hash}};
  out["values"] = {{"compared", r.values_compared}, {"beyond_tolerance", r.values_beyond}};
  if (r.first_beyond) {
    out["first_beyond"] = valueToJson(*r.first_beyond);
    out["first_beyond"]["beyond_in_step"] = r.first_step_beyond_count;
  } else {
    out["first_beyond"] = nullptr;
  }
  out["worst"] = r.worst ? valueToJson(*r.worst) : ordered_json(nullptr);
  ordered_json fields = ordered_json::array();
  for (const FieldStats& s : r.fields) {
    ordered_json f;
    f["body"] = s.field == Field::Time ? ordered_json(nullptr) : ordered_json(s.body);
    f["field"] = fieldName(s.field);
    f["tolerance"] = toleranceToJson(s.tolerance);
    f["compared"] = s.compared;
    f["beyond_tolerance"] = s.beyond;
    f["nonfinite_mismatches"] = s.nonfinite_mismatches;
    f["max_abs"] = s.max_abs;
    f["mean_abs"] = s.meanAbs();
    f["max_rel"] = s.max_rel;
    f["mean_rel"] = s.meanRel();
    f["max_ulps"] = s.max_ulps;
    f["worst"] = s.worst ? valueToJson(*s.worst) : ordered_json(nullptr);
    fields.push_back(std::move(f));
  }
  out["fields"] = fields;
  // the options as given, in the tolerance-file schema
  ordered_json tolerances = {{"default", toleranceToJson(r.options.global)}};
  if (r.options.time) tolerances["time"] = toleranceToJson(*r.options.time);
  ordered_json bodies = ordered_json::object();
  for (const auto& [name, body] : r.options.bodies) {
    if (body.position) bodies[name]["position"] = toleranceToJson(*body.position);
    if (body.velocity) bodies[name]["velocity"] = toleranceToJson(*body.velocity);
  }
  tolerances["bodies"] = bodies;
  out["tolerances"] = tolerances;
  out["common_steps"] = r.options.common_steps;
  return out;
}

nlohmann::ordered_json observedTolerances(const DiffReport& r) {
  ordered_json out;
  out["format"] = "clothref-tolerances";
  out["version"] = kToleranceFileVersion;
  std::string comment = fmt::format(
      "written by clothref diff --write-tolerances from {} vs {}: per field, abs/rel/ulps are the "
      "largest differences observed outside the floor; only the ones the mode uses apply",
      r.path_a, r.path_b);
  std::int64_t nonfinite = 0;
  for (const FieldStats& s : r.fields) nonfinite += s.nonfinite_mismatches;
  if (nonfinite)
    comment += fmt::format("; {} finite vs non-finite values cannot be tolerated", nonfinite);
  out["comment"] = comment;
  out["default"] = toleranceToJson(r.options.global);
  ordered_json bodies = ordered_json::object();
  for (const FieldStats& s : r.fields) {
    Tolerance t = s.tolerance;
    t.abs = s.needed_abs;
    t.rel = s.needed_rel;
    t.ulps = std::int64_t(
        std::min<std::uint64_t>(s.needed_ulps, std::numeric_limits<std::int64_t>::max()));
    if (s.field == Field::Time)
      out["time"] = toleranceToJson(t);
    else
      bodies[s.body][std::string(fieldName(s.field))] = toleranceToJson(t);
  }
  out["bodies"] = bodies;
  return out;
}

}  // namespace clothref
