// Cloth::initializeSpring: the student's spring set, compared as a set with ours at N = 25 and at
// a second N (unordered endpoints, rest length within a tolerance, type label). Order does not
// matter; duplicates, missing or foreign springs, wrong rest lengths and labels do.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "clothref/core/cloth.h"
#include "clothref/formula/course_formulas.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/replay.h"
#include "grader/grade/explain/spring_set_fit.h"
#include "grader/grade/probes/util.h"
#include "grader/grade/run/build.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace {

const std::string& kStub = stubName(Stub::InitializeSpring);
constexpr const auto& kTypeNames = kSpringTypeNames;

// Rows of springsChecks(), the probe's check table.
enum SpringCheck { kConnections, kRestLengths, kTypeLabels, kSecondSize };

// Ours on an n x n cloth of the course's size, height and particle mass.
SpringSet referenceSprings(int n, const Edition& course) {
  Cloth<float> cloth;
  cloth.particles = initializeVertex<float>(n, static_cast<float>(course.cloth_half_extent),
                                            static_cast<float>(course.cloth_height),
                                            static_cast<float>(course.particle_mass));
  initializeSpring(cloth, n);
  SpringSet set;
  for (const auto& s : cloth.springs) {
    set.pairs[{int(std::min(s.start, s.end)), int(std::max(s.start, s.end))}].push_back(
        {s.rest_length, static_cast<int>(s.type)});
    ++set.count;
  }
  return set;
}

std::optional<SpringSet> studentSprings(const probe::ProbeMessage& answer, int n,
                                        std::string& problem) {
  const auto& start = answer.i(key::kSpringStart);
  const auto& end = answer.i(key::kSpringEnd);
  const auto& type = answer.i(key::kSpringType);
  const auto& rest = answer.f(key::kSpringRest);
  if (start.size() != end.size() || start.size() != type.size() || start.size() != rest.size()) {
    problem = "the probe returned inconsistent spring arrays";
    return std::nullopt;
  }
  SpringSet set;
  for (std::size_t k = 0; k < start.size(); ++k) {
    const auto a = start[k], b = end[k];
    if (a < 0 || b < 0 || a >= n * n || b >= n * n) {
      problem = "spring " + std::to_string(k) + " connects particle " + std::to_string(a) +
                " and " + std::to_string(b) + ", outside the " + std::to_string(n * n) +
                " particles of an " + std::to_string(n) + "x" + std::to_string(n) + " cloth";
      return std::nullopt;
    }
    set.pairs[{int(std::min(a, b)), int(std::max(a, b))}].push_back({rest[k], int(type[k])});
    ++set.count;
  }
  return set;
}

// The grid family of a pair: "structural horizontal", ..., or "" for a non-neighbour pair.
std::string family(std::pair<int, int> pair, int n) {
  static const char* names[] = {
      "structural horizontal (i,j)-(i,j+1)", "structural vertical (i,j)-(i+1,j)",
      "shear down-right (i,j)-(i+1,j+1)",    "shear down-left (i,j)-(i+1,j-1)",
      "bend horizontal (i,j)-(i,j+2)",       "bend vertical (i,j)-(i+2,j)"};
  const int f = springFamily(pair, n);
  return f < 0 ? "" : names[f];
}

std::string pairText(std::pair<int, int> pair, int n) {
  return std::to_string(pair.first) + "-" + std::to_string(pair.second) + " (row " +
         std::to_string(pair.first / n) + " col " + std::to_string(pair.first % n) + " to row " +
         std::to_string(pair.second / n) + " col " + std::to_string(pair.second % n) + ")";
}

struct Comparison {
  int missing = 0, extra = 0, duplicates = 0, wrong_rest = 0, wrong_type = 0, matched = 0;
  std::map<std::string, int> missing_by_family, extra_by_family, family_size;
  std::vector<std::string> connection_examples, rest_examples, type_examples;
  std::map<int, std::vector<double>> rest_ratio_by_type;  // student / reference rest, per ref type
  std::map<std::pair<int, int>, int> label_swaps;         // (ref type, student type) -> count
  std::vector<std::string> diagnoses;
  Sketch connections_sketch, rest_sketch, type_sketch;  // the pairs behind each count, drawn
};

Comparison compare(const SpringSet& student, const SpringSet& reference, int n, double rest_rel) {
  Comparison c;
  for (Sketch* sketch : {&c.connections_sketch, &c.rest_sketch, &c.type_sketch}) sketch->grid = n;
  c.connections_sketch.differing_means = "pushed more than once";
  c.rest_sketch.differing_means = "wrong rest length";
  c.type_sketch.differing_means = "wrong type label";
  const auto pairOf = [](std::pair<int, int> pair) {
    return std::array<int, 2>{pair.first, pair.second};
  };
  for (const auto& [pair, entries] : reference.pairs) {
    const std::string fam = family(pair, n);
    ++c.family_size[fam];
    auto it = student.pairs.find(pair);
    if (it == student.pairs.end()) {
      ++c.missing;
      ++c.missing_by_family[fam];
      c.connections_sketch.missing.push_back(pairOf(pair));
      if (c.connection_examples.size() < 3)
        c.connection_examples.push_back("missing: " + pairText(pair, n) + ", a " + fam + " spring");
      continue;
    }
    ++c.matched;
    if (it->second.size() > 1) {
      c.duplicates += static_cast<int>(it->second.size()) - 1;
      c.connections_sketch.differing.push_back(pairOf(pair));
      if (c.connection_examples.size() < 3)
        c.connection_examples.push_back("pushed " + std::to_string(it->second.size()) +
                                        " times: " + pairText(pair, n));
    }
    const auto [ref_rest, ref_type] = entries.front();
    const auto [rest, type] = it->second.front();
    c.rest_ratio_by_type[ref_type].push_back(double(rest) / double(ref_rest));
    if (!(std::abs(double(rest) - double(ref_rest)) <= rest_rel * double(ref_rest))) {
      ++c.wrong_rest;
      c.rest_sketch.differing.push_back(pairOf(pair));
      if (c.rest_examples.size() < 3)
        c.rest_examples.push_back(util::compareNumbers(
            "rest length of " + pairText(pair, n) + " (" + kTypeNames[ref_type] + ")", ref_rest,
            rest, util::Tolerance{0, rest_rel}, "m"));
    }
    if (type != ref_type) {
      ++c.wrong_type;
      ++c.label_swaps[{ref_type, type}];
      c.type_sketch.differing.push_back(pairOf(pair));
      if (c.type_examples.size() < 3)
        c.type_examples.push_back(pairText(pair, n) + ": expected " + kTypeNames[ref_type] +
                                  ", yours " + (type >= 0 && type < 3 ? kTypeNames[type] : "?"));
    }
  }
  for (const auto& [pair, entries] : student.pairs) {
    if (reference.pairs.count(pair)) continue;
    c.extra += static_cast<int>(entries.size());
    c.connections_sketch.unexpected.push_back(pairOf(pair));
    const std::string fam = family(pair, n);
    ++c.extra_by_family[fam.empty() ? "not a grid neighbour of any type" : fam];
    if (c.connection_examples.size() < 4)
      c.connection_examples.push_back("unexpected: " + pairText(pair, n));
  }
  if (c.missing) c.diagnoses.push_back(cause::kMissingSprings);
  if (c.duplicates) c.diagnoses.push_back(cause::kDuplicateSprings);
  if (c.extra) c.diagnoses.push_back(cause::kWrongSpringEndpoints);
  // Rest length signatures: shear at the structural length, bend wrong, close-but-not-exact.
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 1.0 : v[v.size() / 2];
  };
  const double shear = median(c.rest_ratio_by_type[1]);
  const double bend = median(c.rest_ratio_by_type[2]);
  if (std::abs(shear - 1 / std::sqrt(2.0)) < 1e-3) c.diagnoses.push_back(cause::kShearRestLength);
  if (std::abs(bend - 1) > 1e-3) c.diagnoses.push_back(cause::kBendRestLength);
  for (const auto& [type, ratios] : c.rest_ratio_by_type) {
    const double r = median(ratios);
    if (std::abs(r - 1) > rest_rel && std::abs(r - 1) < 1e-2 &&
        !(type == 1 && std::abs(shear - 1 / std::sqrt(2.0)) < 1e-3))
      c.diagnoses.push_back(cause::kApproximateSqrt2);
  }
  if (c.wrong_type) c.diagnoses.push_back(cause::kSwappedSpringTypes);
  std::sort(c.diagnoses.begin(), c.diagnoses.end());
  c.diagnoses.erase(std::unique(c.diagnoses.begin(), c.diagnoses.end()), c.diagnoses.end());
  return c;
}

std::string familyLines(const std::map<std::string, int>& counts,
                        const std::map<std::string, int>& sizes, const char* what) {
  std::string out;
  for (const auto& [fam, count] : counts)
    out += "- " + std::to_string(count) +
           (sizes.count(fam) ? " of " + std::to_string(sizes.at(fam)) : "") + " " +
           (fam.empty() ? "?" : fam) + " springs " + what + "\n";
  return out;
}

// The causes of `ids` that belong to one check (`only`), named as likely on `test`.
void addCauses(TestResult& test, const std::vector<std::string>& ids,
               const std::set<std::string>& only) {
  for (const auto& id : ids)
    if (only.count(id)) test.addCause(id);
}

}  // namespace

std::vector<PlannedTest> springsChecks() {
  return {{kStub, "connections at N = 25", 2},
          {kStub, "rest lengths at N = 25", 1},
          {kStub, "type labels at N = 25", 1},
          {kStub, "all springs at N = " + std::to_string(kSecondParticlesPerEdge), 1}};
}

std::vector<TestResult> probeSprings(const ProbeContext& context) {
  std::vector<TestResult> tests;
  const double rest_rel = context.rubric.tolerances.rest_length_rel;
  probe::ProbeMessage request;
  request.texts[key::kGroup] = group::kSprings;
  util::ProbeFailure failure;
  auto answer = util::runGroup(context, context.probe, group::kSprings, request, failure);
  const std::vector<PlannedTest> checks = springsChecks();
  std::optional<SpringSet> student;
  const int course_n = context.course.particles_per_edge;  // the probe's build and the course's
  const SpringSet reference = referenceSprings(course_n, context.course);
  if (answer) student = studentSprings(*answer, course_n, failure.text);
  bool big_ok = false;
  if (!student) {
    const std::string id = answer ? cause::kWrongSpringEndpoints : failure.causeId();
    for (int k : {kConnections, kRestLengths, kTypeLabels})
      // How the process ended is read, not guessed; endpoints the answer cannot hold are a guess.
      tests.push_back(
          util::failedTest(checks[k], failure.text, {answer ? util::guess(id) : util::likely(id)}));
  } else {
    const Comparison c = compare(*student, reference, course_n, rest_rel);
    const std::string state = "The course cloth: " + std::to_string(course_n) + " x " +
                              std::to_string(course_n) +
                              " particles, built by your `Cloth()` (your `initializeVertex` and "
                              "`initializeSpring`).\n\n";
    TestResult connections = util::test(checks[kConnections]);
    const int errors = c.missing + c.extra + c.duplicates;
    connections.fraction =
        errors == 0 ? 1.0 : std::max(0.0, 1.0 - double(errors) / reference.count);
    if (errors) {
      connections.fraction = std::min(connections.fraction, 0.5);
      connections.output = state + "Expected " + std::to_string(reference.count) +
                           " springs, yours " + std::to_string(student->count) + ": " +
                           std::to_string(c.missing) + " missing, " + std::to_string(c.extra) +
                           " unexpected, " + std::to_string(c.duplicates) + " duplicated.\n\n" +
                           familyLines(c.missing_by_family, c.family_size, "missing") +
                           familyLines(c.extra_by_family, {}, "unexpected") + "\nExamples:\n";
      for (const auto& e : c.connection_examples) connections.output += "- " + e + "\n";
      addCauses(connections, c.diagnoses,
                {cause::kMissingSprings, cause::kDuplicateSprings, cause::kWrongSpringEndpoints});
      connections.sketch = c.connections_sketch;
    } else {
      connections.output = "All " + std::to_string(reference.count) +
                           " springs connect the right particles (order ignored).";
    }
    tests.push_back(connections);

    TestResult rest = util::test(checks[kRestLengths]);
    rest.fraction = c.matched && c.wrong_rest == 0 ? 1.0 : 0.0;
    if (c.wrong_rest || !c.matched) {
      rest.output = state + std::to_string(c.wrong_rest) + " of " + std::to_string(c.matched) +
                    " matching springs have a rest length off by more than " + util::num(rest_rel) +
                    " (relative, the tolerance). Reference rest lengths: structural " +
                    "|p0 - p1|, shear |p0 - p(N+1)|, bend |p0 - p2| of the initial positions.\n\n";
      for (const auto& e : c.rest_examples) rest.output += e;
      addCauses(rest, c.diagnoses,
                {cause::kShearRestLength, cause::kBendRestLength, cause::kApproximateSqrt2});
      if (c.wrong_rest) rest.sketch = c.rest_sketch;
    } else {
      rest.output = "Every spring's rest length matches the initial distance of its ends.";
    }
    tests.push_back(rest);

    TestResult labels = util::test(checks[kTypeLabels]);
    labels.fraction = c.matched && c.wrong_type == 0 ? 1.0 : 0.0;
    if (c.wrong_type || !c.matched) {
      labels.output = state + std::to_string(c.wrong_type) + " of " + std::to_string(c.matched) +
                      " matching springs carry the wrong type label.\n\n";
      for (const auto& [swap, count] : c.label_swaps)
        labels.output +=
            "- " + std::to_string(count) + " " + kTypeNames[swap.first] + " springs labelled " +
            (swap.second >= 0 && swap.second < 3 ? kTypeNames[swap.second] : "?") + "\n";
      for (const auto& e : c.type_examples) labels.output += "- e.g. " + e + "\n";
      if (c.wrong_type) {
        labels.addCause(cause::kSwappedSpringTypes);
        labels.sketch = c.type_sketch;
      }
    } else {
      labels.output = "Every spring has the right type label.";
    }
    tests.push_back(labels);
    big_ok = errors == 0 && c.wrong_rest == 0 && c.wrong_type == 0;
  }

  // The second size: hard-coded 25s show up here.
  const int n = kSecondParticlesPerEdge;
  TestResult small = util::test(checks[kSecondSize]);
  const std::string state =
      "A " + std::to_string(n) + " x " + std::to_string(n) +
      " cloth (your cloth.cpp compiled again with particlesPerEdge = " + std::to_string(n) +
      ").\n\n";
  std::optional<SpringSet> small_set;  // the student's springs at the second size
  if (context.probe_small.empty()) {
    small.output =
        state + "Not run: " +
        (context.small_problem.empty()
             ? std::string("cloth.cpp is not yours")
             : "your cloth.cpp did not build at this size:\n\n" + codeBlock(context.small_problem));
    small.fraction = 0;
  } else {
    util::ProbeFailure small_failure;
    auto small_answer =
        util::runGroup(context, context.probe_small, kSpringsSmallFolder, request, small_failure);
    if (small_answer) small_set = studentSprings(*small_answer, n, small_failure.text);
    if (!small_set) {
      small.output = state + small_failure.text + "\n";
      if (!small_answer)  // the process's own verdict first: a grader error is never yours
        small.addCause(small_failure.causeId(), true);
      if (big_ok && small_failure.verdict != Verdict::GraderError) {
        // Right at 25 and springs to particles a 10 x 10 cloth does not have: measured. A crash
        // at 10 is only suggestive.
        const bool measured = small_answer.has_value();
        small.addCause(cause::kHardCodedN25, measured);
      }
    } else {
      const Comparison c = compare(*small_set, referenceSprings(n, context.course), n, rest_rel);
      const bool ok = c.missing + c.extra + c.duplicates + c.wrong_rest + c.wrong_type == 0;
      small.fraction = ok ? 1.0 : 0.0;
      if (ok) {
        small.output = "All springs match at N = " + std::to_string(n) + ".";
      } else {
        small.output = state + std::to_string(c.missing) + " missing, " + std::to_string(c.extra) +
                       " unexpected, " + std::to_string(c.duplicates) + " duplicated, " +
                       std::to_string(c.wrong_rest) + " wrong rest lengths, " +
                       std::to_string(c.wrong_type) + " wrong labels.\n\n";
        for (const auto& e : c.connection_examples) small.output += "- " + e + "\n";
        small.sketch = c.connections_sketch;
        small.sketch.differing_means = "duplicated, wrong rest length or label";
        for (const Sketch* more : {&c.rest_sketch, &c.type_sketch})
          small.sketch.differing.insert(small.sketch.differing.end(), more->differing.begin(),
                                        more->differing.end());
        if (big_ok) {
          small.addCause(cause::kHardCodedN25);
        } else {
          for (const auto& id : c.diagnoses) small.addCause(id);
        }
      }
    }
  }
  tests.push_back(small);

  // Likely means proven: the model fitted at N = 25, replayed at both sizes. A cause it does not
  // stand for (foreign pairs, hard-coded sizes) is read directly, never proven by it.
  if (student) {
    const SpringModel model = fitSpringModel(*student, reference, course_n);
    const SpringSet at25 = modelSprings(model, reference, course_n);
    const Comparison c25 = compare(*student, at25, course_n, rest_rel);
    Replay replay;
    replay.model = springModelText(model);
    replay.checks.push_back(
        {checks[kConnections].check, {{"springs", c25.missing + c25.extra + c25.duplicates == 0}}});
    replay.checks.push_back({checks[kRestLengths].check, {{"rest lengths", c25.wrong_rest == 0}}});
    replay.checks.push_back({checks[kTypeLabels].check, {{"type labels", c25.wrong_type == 0}}});
    if (small_set) {
      const Comparison c10 = compare(
          *small_set, modelSprings(model, referenceSprings(n, context.course), n), n, rest_rel);
      replay.checks.push_back(
          {checks[kSecondSize].check,
           {{"springs", c10.missing + c10.extra + c10.duplicates == 0},
            {"rest lengths and labels", c10.wrong_rest + c10.wrong_type == 0}}});
    }
    std::vector<std::string> ids;
    if (std::any_of(model.missing.begin(), model.missing.end(), [](bool b) { return b; }))
      ids.push_back(cause::kMissingSprings);
    if (std::any_of(model.copies.begin(), model.copies.end(), [](int k) { return k > 1; }))
      ids.push_back(cause::kDuplicateSprings);
    for (const TestResult& t : tests)
      for (const Cause& cause : t.causes)
        if ((cause.id == cause::kShearRestLength || cause.id == cause::kBendRestLength ||
             cause.id == cause::kApproximateSqrt2 || cause.id == cause::kSwappedSpringTypes) &&
            std::find(ids.begin(), ids.end(), cause.id) == ids.end())
          ids.push_back(cause.id);
    if (!ids.empty()) applyReplay(replay, ids, tests);
  }
  requireProofs(tests, {cause::kHardCodedN25, cause::kWrongSpringEndpoints});
  return tests;
}

// The probe's row of the probe table (probes.h): the course's N and a second size.
std::vector<ProbeGroup> probeRowsSprings() {
  return {{probe::group::kSprings,
           stubName(Stub::InitializeSpring),
           springsChecks(),
           probeSprings,
           {probe::group::kSprings, kSpringsSmallFolder}}};
}

}  // namespace clothref::grader
