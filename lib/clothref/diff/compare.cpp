// Trace comparison: values under their tolerance (ulps, absolute, relative, combined), headers
// by JSON pointer, and the two traces step by step into a DiffReport.
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

// Sign-magnitude bits mapped to an unsigned order in which adjacent floats differ by 1 and
// -0 == +0 (the mapping GoogleTest's AlmostEquals uses).
template <typename Bits>
std::uint64_t biased(Bits bits) {
  constexpr Bits kSign = Bits(1) << (sizeof(Bits) * 8 - 1);
  return (bits & kSign) ? std::uint64_t(Bits(~bits + 1)) : std::uint64_t(bits | kSign);
}

std::uint64_t ulpDistance(double a, double b, Precision precision) {
  std::uint64_t ua, ub;
  if (precision == Precision::Float) {
    ua = biased(std::bit_cast<std::uint32_t>(static_cast<float>(a)));
    ub = biased(std::bit_cast<std::uint32_t>(static_cast<float>(b)));
  } else {
    ua = biased(std::bit_cast<std::uint64_t>(a));
    ub = biased(std::bit_cast<std::uint64_t>(b));
  }
  return ua > ub ? ua - ub : ub - ua;
}

struct Outcome {
  bool pass = true;
  bool floored = false;    // exempted by the floor
  bool nonfinite = false;  // finite vs non-finite, or different non-finite kinds
  double score = 0;        // how far beyond the tolerance, for "worst"
};

// measure / tolerance, or the measure itself for a zero tolerance
double ratio(double measure, double tolerance) {
  return tolerance > 0 ? measure / tolerance : measure;
}

// Fills the differences of `diff` (a and b already set) and decides pass or fail.
Outcome compareValue(ValueDiff& diff, const Tolerance& tolerance, Precision precision) {
  const double a = diff.a, b = diff.b;
  Outcome outcome;
  if (!std::isfinite(a) || !std::isfinite(b)) {
    // the same non-finite kind is equal; anything else is an infinite difference
    const bool same = (std::isnan(a) && std::isnan(b)) || a == b;
    diff.abs = diff.rel = same ? 0 : kInfinity;
    diff.ulps = same ? 0 : kInfiniteUlps;
    outcome.pass = same;
    outcome.nonfinite = !same;
    outcome.score = same ? 0 : kInfinity;
    return outcome;
  }
  diff.abs = std::abs(a - b);
  const double magnitude = std::max(std::abs(a), std::abs(b));
  diff.rel = magnitude > 0 ? diff.abs / magnitude : 0;
  diff.ulps = ulpDistance(a, b, precision);
  if (std::abs(a) < tolerance.floor && std::abs(b) < tolerance.floor) {
    outcome.floored = true;
    return outcome;
  }
  switch (tolerance.mode) {
    case ToleranceMode::Absolute:
      outcome.pass = diff.abs <= tolerance.abs;
      outcome.score = ratio(diff.abs, tolerance.abs);
      break;
    case ToleranceMode::Relative:
      outcome.pass = diff.rel <= tolerance.rel;
      outcome.score = ratio(diff.rel, tolerance.rel);
      break;
    case ToleranceMode::Combined:
      outcome.pass = diff.abs <= tolerance.abs || diff.rel <= tolerance.rel;
      outcome.score = std::min(ratio(diff.abs, tolerance.abs), ratio(diff.rel, tolerance.rel));
      break;
    case ToleranceMode::Ulps:
      outcome.pass = diff.ulps <= std::uint64_t(tolerance.ulps);
      outcome.score = ratio(double(diff.ulps), double(tolerance.ulps));
      break;
  }
  return outcome;
}

// ---------------------------------------------------------------------------------------------
// Header comparison

const ordered_json kMissing(ordered_json::value_t::discarded);

// Walks two JSON values key by key (arrays index by index), recording every leaf that differs.
void compareJson(const ordered_json& a, const ordered_json& b, const std::string& pointer,
                 std::vector<HeaderDiff>& out) {
  if (a.is_object() && b.is_object()) {
    for (const auto& item : a.items()) {
      const std::string child = pointer + "/" + item.key();
      const auto other = b.find(item.key());
      if (other == b.end())
        out.push_back({child, item.value(), kMissing});
      else
        compareJson(item.value(), *other, child, out);
    }
    for (const auto& item : b.items())
      if (!a.contains(item.key()))
        out.push_back({pointer + "/" + item.key(), kMissing, item.value()});
    return;
  }
  if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (std::size_t i = 0; i < a.size(); ++i)
      compareJson(a[i], b[i], fmt::format("{}/{}", pointer, i), out);
    return;
  }
  if (a.is_array() && b.is_array()) {
    out.push_back({pointer, a, b});
    return;
  }
  if (a != b) out.push_back({pointer, a, b});
}

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0 &&
         (text.size() == prefix.size() || text[prefix.size()] == '/');
}

std::string describeBodies(const TraceHeader& header) {
  std::string text;
  for (const TraceBody& body : header.bodies)
    text += fmt::format("{}{} ({} particles)", text.empty() ? "" : ", ", body.name, body.particles);
  return text.empty() ? "no bodies" : text;
}

// Header differences, significant ones first. Throws for different bodies, or different step
// sets without --common-steps.
std::vector<HeaderDiff> compareHeaders(const TraceReader& a, const TraceReader& b,
                                       bool common_steps) {
  const TraceHeader& ha = a.header();
  const TraceHeader& hb = b.header();
  if (ha.json["bodies"] != hb.json["bodies"])
    throw InputError(fmt::format("different bodies: {} has {}, {} has {}", a.path(),
                                 describeBodies(ha), b.path(), describeBodies(hb)));
  if (!common_steps && (ha.steps != hb.steps || ha.stride != hb.stride))
    throw InputError(
        fmt::format("different step sets: {} has steps {} stride {}, {} has steps {} stride {} "
                    "(--common-steps compares the steps both have)",
                    a.path(), ha.steps, ha.stride, b.path(), hb.steps, hb.stride));
  std::vector<HeaderDiff> all;
  compareJson(ha.json, hb.json, "", all);
  std::vector<HeaderDiff> significant, informational;
  for (HeaderDiff& diff : all) {
    // what was built, what a scene is called and how much was recorded do not change results
    diff.significant = !(startsWith(diff.pointer, "/build") || diff.pointer == "/scene/name" ||
                         diff.pointer == "/scene/description" || diff.pointer == "/steps" ||
                         diff.pointer == "/stride" || diff.pointer == "/hash");
    (diff.significant ? significant : informational).push_back(std::move(diff));
  }
  significant.insert(significant.end(), informational.begin(), informational.end());
  return significant;
}

// ---------------------------------------------------------------------------------------------
// Accumulation

// True when `candidate` should replace `current` as the worst: beyond tolerance beats within,
// then the higher score; ties keep the earlier value.
bool worse(bool candidate_beyond, double candidate_score, bool current_beyond, double current_score,
           bool has_current) {
  if (!has_current) return true;
  if (candidate_beyond != current_beyond) return candidate_beyond;
  return candidate_score > current_score;
}

struct Accumulator {
  DiffReport& report;
  bool worst_beyond = false;
  double worst_score = -1;

  void add(FieldStats& stats, ValueDiff& diff, Precision precision) {
    const Outcome outcome = compareValue(diff, stats.tolerance, precision);
    ++stats.compared;
    ++report.values_compared;
    if (outcome.nonfinite) {
      ++stats.nonfinite_mismatches;
    } else {
      stats.max_abs = std::max(stats.max_abs, diff.abs);
      stats.sum_abs += diff.abs;
      stats.max_rel = std::max(stats.max_rel, diff.rel);
      stats.sum_rel += diff.rel;
      stats.max_ulps = std::max(stats.max_ulps, diff.ulps);
      if (!outcome.floored) {
        stats.needed_abs = std::max(stats.needed_abs, diff.abs);
        stats.needed_rel = std::max(stats.needed_rel, diff.rel);
        stats.needed_ulps = std::max(stats.needed_ulps, diff.ulps);
      }
    }
    if (!outcome.pass) {
      ++stats.beyond;
      ++report.values_beyond;
      if (!report.first_beyond) report.first_beyond = diff;
      if (report.first_beyond->step == diff.step) ++report.first_step_beyond_count;
    }
    // equal values are never "worst"; that keeps the report of equal traces empty
    if (diff.abs == 0 && diff.ulps == 0 && !outcome.nonfinite) return;
    const bool beyond = !outcome.pass;
    if (worse(beyond, outcome.score, stats.worst_beyond, stats.worst_score,
              stats.worst.has_value())) {
      stats.worst = diff;
      stats.worst_beyond = beyond;
      stats.worst_score = outcome.score;
    }
    if (worse(beyond, outcome.score, worst_beyond, worst_score, report.worst.has_value())) {
      report.worst = diff;
      worst_beyond = beyond;
      worst_score = outcome.score;
    }
  }
};

// Part of a step line after the prefix (the writer puts "bodies" last); empty if not found.
std::string_view bodiesPart(std::string_view line) {
  const std::size_t at = line.find("\"bodies\":");
  return at == std::string_view::npos ? std::string_view() : line.substr(at);
}

}  // namespace

namespace {

DiffReport diffReaders(TraceReader& a, TraceReader& b, const DiffOptions& options);

}  // namespace

DiffReport diffTraces(const std::string& path_a, const std::string& path_b,
                      const DiffOptions& options) {
  TraceReader a(path_a);
  TraceReader b(path_b);
  return diffReaders(a, b, options);
}

DiffReport diffTraces(std::istream& a, const std::string& name_a, std::istream& b,
                      const std::string& name_b, const DiffOptions& options) {
  TraceReader reader_a(a, name_a);
  TraceReader reader_b(b, name_b);
  return diffReaders(reader_a, reader_b, options);
}

namespace {

DiffReport diffReaders(TraceReader& a, TraceReader& b, const DiffOptions& options) {
  DiffReport report;
  report.path_a = a.path();
  report.path_b = b.path();
  report.options = options;
  report.header_diffs = compareHeaders(a, b, options.common_steps);
  const TraceHeader& ha = a.header();
  report.precision = ha.precision == b.header().precision ? ha.precision : Precision::Double;
  // hashes can stand in for values only when both traces define them the same way
  const bool use_hash = ha.json["hash"] == b.header().json["hash"];

  // fields: per body (A's order, B has the same bodies) position and velocity, then time
  auto addField = [&](const std::string& body, Field field) {
    FieldStats& stats = report.fields.emplace_back();
    stats.body = body;
    stats.field = field;
    stats.tolerance = toleranceFor(options, body, field);
  };
  for (const TraceBody& body : ha.bodies)
    for (Field field : {Field::Position, Field::Velocity}) addField(body.name, field);
  addField("", Field::Time);
  FieldStats& time_stats = report.fields.back();
  std::vector<std::size_t> b_index;
  for (const TraceBody& body : ha.bodies)
    for (std::size_t j = 0; j < b.header().bodies.size(); ++j)
      if (b.header().bodies[j].name == body.name) b_index.push_back(j);

  Accumulator accumulator{report};
  TraceStep step_a, step_b;
  bool more_a = a.next(), more_b = b.next();
  report.steps_a = more_a, report.steps_b = more_b;
  auto advance = [&](TraceReader& reader, std::int64_t& count) {
    const bool more = reader.next();
    count += more;
    return more;
  };
  while (more_a && more_b) {
    const StepPrefix& pa = a.prefix();
    const StepPrefix& pb = b.prefix();
    if (pa.step != pb.step) {
      // only reachable with --common-steps: the readers enforce each header's step set
      if (pa.step < pb.step)
        more_a = advance(a, report.steps_a);
      else
        more_b = advance(b, report.steps_b);
      continue;
    }
    ++report.steps_compared;
    ValueDiff time{pa.step, pa.t, "", Field::Time, -1, -1, pa.t, pb.t};
    accumulator.add(time_stats, time, Precision::Double);

    const std::string_view rest_a = bodiesPart(a.line());
    if (use_hash && pa.hash == pb.hash && !rest_a.empty() && rest_a == bodiesPart(b.line())) {
      // equal hash and equal bytes: every value is equal, no need to parse
      ++report.steps_equal_hash;
      for (std::size_t i = 0; i < ha.bodies.size(); ++i)
        for (std::size_t f = 0; f < 2; ++f) {
          report.fields[2 * i + f].compared += 3 * ha.bodies[i].particles;
          report.values_compared += 3 * ha.bodies[i].particles;
        }
    } else {
      a.parseStep(step_a);
      b.parseStep(step_b);
      bool all_equal = true;
      for (std::size_t i = 0; i < ha.bodies.size(); ++i) {
        const BodyState& body_a = step_a.bodies[i];
        const BodyState& body_b = step_b.bodies[b_index[i]];
        for (std::size_t f = 0; f < 2; ++f) {
          FieldStats& stats = report.fields[2 * i + f];
          const std::vector<double>& va = f == 0 ? body_a.position : body_a.velocity;
          const std::vector<double>& vb = f == 0 ? body_b.position : body_b.velocity;
          ValueDiff diff{pa.step, pa.t, stats.body, stats.field};
          for (std::size_t k = 0; k < va.size(); ++k) {
            diff.particle = std::int64_t(k / 3);
            diff.component = int(k % 3);
            diff.a = va[k];
            diff.b = vb[k];
            accumulator.add(stats, diff, report.precision);
            all_equal = all_equal && diff.abs == 0 && diff.ulps == 0;
          }
        }
      }
      // equal values, different hashes: -0 vs +0 (the reader has already refused a step whose
      // hash does not match its own values, so neither is a corrupt record)
      if (all_equal && pa.hash != pb.hash) ++report.steps_equal_values_different_hash;
    }
    more_a = advance(a, report.steps_a);
    more_b = advance(b, report.steps_b);
  }
  // read the rest so a malformed tail is still reported
  while (more_a) more_a = advance(a, report.steps_a);
  while (more_b) more_b = advance(b, report.steps_b);

  bool any_difference = false;
  for (const FieldStats& stats : report.fields) any_difference |= stats.anyDifference();
  const bool significant_header =
      std::any_of(report.header_diffs.begin(), report.header_diffs.end(),
                  [](const HeaderDiff& d) { return d.significant; });
  if (significant_header || report.values_beyond > 0)
    report.verdict = Verdict::Differ;
  else if (any_difference)
    report.verdict = Verdict::WithinTolerance;
  else
    report.verdict = Verdict::Identical;
  return report;
}

}  // namespace

}  // namespace clothref
