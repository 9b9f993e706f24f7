// Trace comparison: `clothref diff A B` as a library (docs/trace-format.md, "Diff").
//
// Inputs: two trace files and DiffOptions (tolerances: a global one, optionally per body and per
// field from a tolerance file; whether to compare only common steps).
// Outputs: a DiffReport with the verdict, header differences, the first step beyond tolerance,
// the worst difference, counts and per-body-per-field statistics; formatted as text (only what
// differs) or as one JSON object. Bad input (missing file, malformed line, different bodies or
// step sets) throws InputError "FILE:LINE: problem", which the CLI maps to exit 2.
//
// Values: positions in metres, velocities in m/s, t in seconds. A value pair passes when
//   - both are the same non-finite kind (NaN and NaN, +inf and +inf, -inf and -inf);
//     finite vs non-finite, or different kinds, never pass (infinite difference);
//   - both |a| and |b| are below `floor` (exodiff's floor: noise near zero is ignored);
//   - otherwise by mode: Absolute |a-b| <= abs; Relative |a-b| / max(|a|,|b|) <= rel;
//     Combined either of the two (numdiff's rule: absolute near zero, relative elsewhere);
//     Ulps: the distance in units in the last place, counted in the trace's precision (t is
//     always double), is <= ulps. The default, Ulps with ulps = 0, is bit-exact (-0 == +0).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "clothref/base/enum_table.h"
#include "clothref/base/precision.h"

namespace clothref {

enum class ToleranceMode { Ulps, Absolute, Relative, Combined };
// Names in tolerance files and reports.
inline constexpr EnumTable<ToleranceMode, 4> kToleranceModeNames{{
    {ToleranceMode::Ulps, "ulps"},
    {ToleranceMode::Absolute, "absolute"},
    {ToleranceMode::Relative, "relative"},
    {ToleranceMode::Combined, "combined"},
}};

struct Tolerance {
  ToleranceMode mode = ToleranceMode::Ulps;
  double abs = 0;         // same unit as the field
  double rel = 0;         // fraction of max(|a|, |b|)
  double floor = 0;       // pairs with both |a|, |b| < floor pass
  std::int64_t ulps = 0;  // units in the last place
};

// The compared fields. Time has no body.
enum class Field { Position, Velocity, Time };
// Names in reports (and, for position and velocity, in tolerance files).
inline constexpr EnumTable<Field, 3> kFieldNames{{
    {Field::Position, "position"},
    {Field::Velocity, "velocity"},
    {Field::Time, "time"},
}};

struct BodyTolerances {
  std::optional<Tolerance> position;
  std::optional<Tolerance> velocity;
};

struct DiffOptions {
  Tolerance global;                              // every field without an override
  std::optional<Tolerance> time;                 // override for t
  std::map<std::string, BodyTolerances> bodies;  // overrides per body name
  bool common_steps = false;  // compare only steps both traces have instead of exit 2
};

// The tolerance that applies to `field` of `body` (body ignored for Field::Time).
Tolerance toleranceFor(const DiffOptions& options, const std::string& body, Field field);

// Reads a tolerance file (JSON, docs/trace-format.md). Throws InputError naming the file and the
// JSON pointer. The file's "default", if any, replaces options.global.
DiffOptions readToleranceFile(const std::string& path);
DiffOptions toleranceOptionsFromJson(const nlohmann::json& document, const std::string& source);

// One compared value pair.
struct ValueDiff {
  std::int64_t step = 0;
  double t = 0;
  std::string body;  // empty for time
  Field field = Field::Position;
  std::int64_t particle = -1;  // -1 for time
  int component = -1;          // 0, 1, 2 = x, y, z; -1 for time
  double a = 0, b = 0;
  double abs = 0;          // |a - b|, +inf for a non-finite mismatch
  double rel = 0;          // |a - b| / max(|a|, |b|), 0 when both are 0
  std::uint64_t ulps = 0;  // UINT64_MAX for a non-finite mismatch
};

// Statistics of one field of one body (or of time) over all compared values.
struct FieldStats {
  std::string body;  // empty for time
  Field field = Field::Position;
  Tolerance tolerance;
  std::int64_t compared = 0;  // values in hash-equal steps count as compared and equal
  std::int64_t beyond = 0;    // values beyond tolerance
  std::int64_t nonfinite_mismatches = 0;
  double max_abs = 0, sum_abs = 0;
  double max_rel = 0, sum_rel = 0;
  std::uint64_t max_ulps = 0;
  // Smallest tolerances that would pass every value not exempted by the floor.
  double needed_abs = 0, needed_rel = 0;
  std::uint64_t needed_ulps = 0;
  std::optional<ValueDiff> worst;  // the value furthest beyond (or closest to) its tolerance
  bool worst_beyond = false;       // whether `worst` is beyond tolerance
  double worst_score = -1;         // its measure / tolerance (the measure for a zero tolerance)

  double meanAbs() const { return compared ? sum_abs / double(compared) : 0; }
  double meanRel() const { return compared ? sum_rel / double(compared) : 0; }
  bool anyDifference() const { return max_abs > 0 || max_ulps > 0 || nonfinite_mismatches > 0; }
};

// A header key that differs. `significant` ones (scene parameters, integrator, dt, precision,
// unknown keys) make the verdict Differ; build info, scene name/description, steps and stride
// (with --common-steps) are informational.
struct HeaderDiff {
  std::string pointer;          // JSON pointer, e.g. "/scene/cloth/spring_coef"
  nlohmann::ordered_json a, b;  // the values; a missing key is a discarded value
  bool significant = true;
};

enum class Verdict {
  Identical,        // headers equal (build aside), every common step bit-identical
  WithinTolerance,  // some values differ, all within tolerance
  Differ            // a significant header difference or a value beyond tolerance
};
// Names in the JSON report.
inline constexpr EnumTable<Verdict, 3> kVerdictNames{{
    {Verdict::Identical, "identical"},
    {Verdict::WithinTolerance, "within_tolerance"},
    {Verdict::Differ, "differ"},
}};

struct DiffReport {
  std::string path_a, path_b;
  Verdict verdict = Verdict::Identical;
  Precision precision = Precision::Float;  // of positions and velocities (double if A, B differ)
  DiffOptions options;
  std::vector<HeaderDiff> header_diffs;
  std::int64_t steps_a = 0, steps_b = 0;  // recorded steps in each trace
  std::int64_t steps_compared = 0;        // common steps
  std::int64_t steps_equal_hash = 0;      // of which skipped: equal hash and equal bytes
  std::int64_t steps_equal_values_different_hash = 0;  // e.g. -0 vs +0
  std::int64_t values_compared = 0, values_beyond = 0;
  std::optional<ValueDiff> first_beyond;  // first value beyond tolerance (first step, file order)
  std::int64_t first_step_beyond_count = 0;  // values beyond tolerance in that step
  std::optional<ValueDiff> worst;            // worst value of all fields (see FieldStats::worst)
  std::vector<FieldStats> fields;            // per body (header order) x position, velocity; time
};

// Compares two trace files. Throws InputError on bad input (exit 2).
DiffReport diffTraces(const std::string& path_a, const std::string& path_b,
                      const DiffOptions& options);

// Compares two traces read from streams (a pipe, a string); `name_a` and `name_b` name them in the
// report and in messages.
DiffReport diffTraces(std::istream& a, const std::string& name_a, std::istream& b,
                      const std::string& name_b, const DiffOptions& options);

// Human-readable report, only what differs; one line when the traces are identical.
std::string formatReport(const DiffReport& report);

// The same report as one JSON object (schema in docs/trace-format.md).
nlohmann::ordered_json reportToJson(const DiffReport& report);

// A tolerance file that makes this same diff pass (per body per field, the observed maxima in the
// mode in use). Values that cannot pass (non-finite mismatches) are listed in its "comment".
nlohmann::ordered_json observedTolerances(const DiffReport& report);

nlohmann::ordered_json toleranceToJson(const Tolerance& tolerance);
constexpr std::string_view fieldName(Field field) { return enumName(kFieldNames, field); }
constexpr std::string_view toleranceModeName(ToleranceMode mode) {
  return enumName(kToleranceModeNames, mode);
}

}  // namespace clothref
