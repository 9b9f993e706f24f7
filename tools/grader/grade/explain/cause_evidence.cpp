#include "grader/grade/explain/cause_evidence.h"

#include <algorithm>
#include <map>

#include "grader/grade/cause_ids.h"

namespace clothref::grader {

CauseEvidence makeEvidence(std::size_t cases, std::vector<std::string> ids) {
  CauseEvidence evidence;
  const std::vector<bool> none(ids.size(), false);
  evidence.variant_ids = std::move(ids);
  evidence.differs.assign(cases, none);
  evidence.matches.assign(cases, none);
  evidence.passed.assign(cases, false);
  evidence.measured.assign(cases, {});
  return evidence;
}

bool explainsEveryCase(const CauseEvidence& evidence, std::size_t m) {
  bool explains_a_failure = false;
  for (std::size_t k = 0; k < evidence.passed.size(); ++k) {
    // Where the variant is the course's, the student's numbers must be the course's too.
    if (!evidence.differs[k][m] ? !evidence.passed[k] : !evidence.matches[k][m]) return false;
    explains_a_failure = explains_a_failure || (!evidence.passed[k] && evidence.matches[k][m]);
  }
  return explains_a_failure;
}

std::set<std::string> likelyCauses(const CauseEvidence& evidence) {
  std::set<std::string> likely;
  for (std::size_t m = 0; m < evidence.variant_ids.size(); ++m)
    if (explainsEveryCase(evidence, m)) likely.insert(evidence.variant_ids[m]);
  if (likely.empty())
    for (const CauseEvidence::Finding& f : evidence.findings) likely.insert(f.cause);
  return likely;
}

void nameCauses(const CauseEvidence& evidence, const std::set<std::string>& likely,
                const std::vector<bool>& finding_applies, std::vector<TestResult>& tests) {
  std::map<std::string, std::string> shown;  // cause -> the check above that shows its measurement
  for (std::size_t k = 0; k < tests.size() && k < evidence.passed.size(); ++k) {
    TestResult& t = tests[k];
    if (evidence.passed[k]) continue;
    std::vector<Cause> guesses;
    for (std::size_t m = 0; m < evidence.variant_ids.size(); ++m) {
      if (!evidence.differs[k][m] || !evidence.matches[k][m]) continue;
      const std::string& id = evidence.variant_ids[m];
      if (likely.count(id))
        t.addCause(id);
      else if (std::none_of(guesses.begin(), guesses.end(),
                            [&](const Cause& g) { return g.id == id; }))
        guesses.push_back(Cause{id, false, {}, {}, {}, {}, {}, {}});
    }
    for (const CauseEvidence::Finding& f : evidence.findings) {
      if (!likely.count(f.cause) || !finding_applies[k]) continue;
      Cause& cause = t.addCause(f.cause);
      cause.detail = shown.emplace(f.cause, t.check).second
                         ? "Measured: " + f.text + "."
                         : "Measured as under *" + shown[f.cause] + "* above.";
    }
    if (t.causes.empty())
      for (const std::string& id : evidence.measured[k]) t.addCause(id);
    if (!t.causes.empty()) continue;
    // Nothing explains every case: unknown, with what matched this case as the nearest guesses.
    t.addCause(cause::kUnknown, false);
    t.causes.insert(t.causes.end(), guesses.begin(), guesses.end());
  }
}

}  // namespace clothref::grader
