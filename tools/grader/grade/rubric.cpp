#include "grader/grade/rubric.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/text.h"

namespace clothref::grader {

// The catalogue's kinds and default deductions (tools/grader/diagnoses.json, generated into
// cause_ids.h; docs/grading-reference.md, "Points follow mistakes"): a slip costs little, a missing
// piece of physics more, a wrong method half the stub; the kind "never" (a crash, a timeout, a
// symptom or a guess) has no deduction.
const std::vector<CauseDeduction>& causeDeductions() {
  static const std::vector<CauseDeduction> table = [] {
    std::vector<CauseDeduction> rows;
    for (const cause::Entry& entry : cause::entries())
      rows.push_back({entry.id, entry.kind, entry.deduction});
    return rows;
  }();
  return table;
}

Rubric defaultRubric(int edition) {
  Rubric rubric;
  for (const StubInfo& info : stubTable()) {
    const double points = edition == 2024 ? info.points_2024 : info.points_2022;
    if (points > 0) rubric.stub_points[info.name] = points;
  }
  for (const std::string& variant : acceptedVariantNames())
    rubric.accepted_variants[variant] = true;
  for (const CauseDeduction& cause : causeDeductions())
    if (cause.deduction >= 0) rubric.deductions[cause.id] = cause.deduction;
  return rubric;
}

namespace {

[[noreturn]] void rubricError(const std::string& source, const std::string& pointer,
                              const std::string& problem) {
  throw InputError(source + ": " + pointer + ": " + problem);
}

// "/" + the key, cut short: a key is user text and may be megabytes long
std::string child(const std::string& pointer, const std::string& key) {
  return pointer + "/" + excerpt(key);
}

void requireObject(const nlohmann::json& value, const std::string& source,
                   const std::string& pointer) {
  if (!value.is_object())
    rubricError(source, pointer, "expected an object, got " + excerpt(value.dump()));
}

double nonNegative(const nlohmann::json& value, const std::string& source,
                   const std::string& pointer) {
  if (!value.is_number() || !(value.get<double>() >= 0))
    rubricError(source, pointer, "expected a number >= 0, got " + excerpt(value.dump()));
  return value.get<double>();
}

}  // namespace

Rubric loadRubric(const std::string& path, Rubric base) {
  return rubricFromJson(readJsonFile(path, "rubric"), path, std::move(base));
}

Rubric rubricFromJson(const nlohmann::json& document, const std::string& source, Rubric rubric) {
  requireObject(document, source, "/");
  for (const auto& [key, value] : document.items()) {
    const std::string pointer = child("", key);
    if (key == "stubs") {
      requireObject(value, source, pointer);
      for (const auto& [stub, points] : value.items()) {
        bool known = false;
        for (const auto& name : stubNames()) known = known || name == stub;
        if (!known) rubricError(source, child(pointer, stub), "unknown stub");
        rubric.stub_points[stub] = nonNegative(points, source, child(pointer, stub));
      }
    } else if (key == "tests") {
      requireObject(value, source, pointer);
      for (const auto& [test, weight] : value.items())
        rubric.test_weights[test] = nonNegative(weight, source, child(pointer, test));
    } else if (key == "tolerances") {
      requireObject(value, source, pointer);
      for (const auto& [name, tolerance] : value.items()) {
        const double t = nonNegative(tolerance, source, child(pointer, name));
        if (name == "force_rel")
          rubric.tolerances.force_rel = t;
        else if (name == "collide_rel")
          rubric.tolerances.collide_rel = t;
        else if (name == "integrate_rel")
          rubric.tolerances.integrate_rel = t;
        else if (name == "rest_length_rel")
          rubric.tolerances.rest_length_rel = t;
        else if (name == "order")
          rubric.tolerances.order = t;
        else
          rubricError(source, child(pointer, name), "unknown tolerance");
      }
    } else if (key == "accepted_variants") {
      requireObject(value, source, pointer);
      for (const auto& [name, on] : value.items()) {
        const auto& names = acceptedVariantNames();
        if (std::find(names.begin(), names.end(), name) == names.end())
          rubricError(source, child(pointer, name), "unknown variant");
        if (!on.is_boolean())
          rubricError(source, child(pointer, name),
                      "expected true or false, got " + excerpt(on.dump()));
        rubric.accepted_variants[name] = on.get<bool>();
      }
    } else if (key == "visibility") {
      requireObject(value, source, pointer);
      for (const auto& [name, shown] : value.items()) {
        // a stub's name, or a test's "<stub>: <check>"
        const std::string stub = name.substr(0, name.find(": "));
        const auto& stubs = stubNames();
        if (std::find(stubs.begin(), stubs.end(), stub) == stubs.end())
          rubricError(source, child(pointer, name), "unknown stub (a stub or \"<stub>: <check>\")");
        const auto& names = visibilityNames();
        if (!shown.is_string() ||
            std::find(names.begin(), names.end(), shown.get<std::string>()) == names.end())
          rubricError(source, child(pointer, name),
                      "expected visible, hidden, after_due_date or after_published, got " +
                          excerpt(shown.dump()));
        rubric.visibility[name] = shown.get<std::string>();
      }
    } else if (key == "scoring") {
      if (value == scoringName(Scoring::PerMistake))
        rubric.scoring = Scoring::PerMistake;
      else if (value == scoringName(Scoring::PerCheck))
        rubric.scoring = Scoring::PerCheck;
      else
        rubricError(source, pointer,
                    "expected \"per-mistake\" or \"per-check\", got " + excerpt(value.dump()));
    } else if (key == "deductions") {
      requireObject(value, source, pointer);
      for (const auto& [id, share] : value.items()) {
        const auto& table = causeDeductions();
        const auto cause = std::find_if(table.begin(), table.end(),
                                        [&](const CauseDeduction& c) { return id == c.id; });
        if (cause == table.end())
          rubricError(source, child(pointer, id), "unknown cause (not in diagnoses.json)");
        if (share.is_null()) {  // this cause is scored per check
          rubric.deductions.erase(id);
          continue;
        }
        if (cause->deduction < 0)
          rubricError(source, child(pointer, id),
                      "never scored per mistake (a crash, a timeout, a symptom or a guess): "
                      "only null is accepted, got " +
                          excerpt(share.dump()));
        if (!share.is_number() || !(share.get<double>() >= 0 && share.get<double>() <= 1))
          rubricError(source, child(pointer, id),
                      "expected a share of the stub's points from 0 to 1 (or null), got " +
                          excerpt(share.dump()));
        rubric.deductions[id] = share.get<double>();
      }
    } else {
      rubricError(source, pointer, "unknown field");
    }
  }
  return rubric;
}

}  // namespace clothref::grader
