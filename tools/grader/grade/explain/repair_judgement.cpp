// Issue 38's repairs judged: what a repaired build's checks prove about the cause repaired
// (repair_proof.h; the patterns that make the repairs are in repair_proof.cpp).
#include <algorithm>

#include "grader/grade/explain/repair_proof.h"
#include "grader/grade/text.h"

namespace clothref::grader {

bool applyRepair(const Repair& repair, bool built, const std::string& problem,
                 const std::vector<TestResult>& repaired, std::vector<TestResult>& tests) {
  const std::string with = "With " + repair.what;
  std::size_t total = 0, passing = 0, mended = 0;
  bool same_shape = built && repaired.size() == tests.size();
  for (std::size_t k = 0; same_shape && k < tests.size(); ++k)
    same_shape = repaired[k].check == tests[k].check;
  std::vector<std::string> others;  // the proven causes of the checks still failing
  bool others_explained = true;
  std::size_t still = 0, broken = 0;
  if (same_shape)
    for (std::size_t k = 0; k < tests.size(); ++k) {
      ++total;
      passing += repaired[k].passed();
      if (!tests[k].passed() && repaired[k].passed()) ++mended;
      if (tests[k].passed() && !repaired[k].passed()) ++broken;
      if (repaired[k].passed()) continue;
      ++still;
      bool explained = false;
      for (const Cause& c : repaired[k].causes)
        if (c.proven()) {
          explained = true;
          if (std::find(others.begin(), others.end(), c.id) == others.end()) others.push_back(c.id);
        }
      others_explained = others_explained && explained;
    }
  // Two mistakes in one stub, where the repaired one does not mend a check alone: the repair
  // proves its cause when the repaired build's failed checks are all explained by proven causes
  // that did not explain the stub as handed in (so the repair changed the numbers, into those of
  // the course with the other mistakes).
  bool before_explained = true;
  for (std::size_t k = 0; same_shape && k < tests.size(); ++k) {
    if (tests[k].passed()) continue;
    bool explained = false;
    for (const Cause& c : tests[k].causes)
      explained = explained || (c.proven() && c.id != repair.cause &&
                                std::find(others.begin(), others.end(), c.id) != others.end());
    before_explained = before_explained && explained;
  }
  const bool jointly = same_shape && mended == 0 && still > 0 && others_explained &&
                       !before_explained && !others.empty();
  std::string line;
  const bool proven = same_shape && (mended > 0 || jointly) && broken == 0;
  if (!built) {
    line = "Not proven: with " + repair.what + ", " + repair.file + " does not build" +
           (problem.empty() ? "" : " (" + problem.substr(0, problem.find('\n')) + ")") +
           ", so the repair shows nothing.";
  } else if (!same_shape) {
    line = "Not proven: with " + repair.what + ", the stub could not be probed again.";
  } else if (!proven) {
    line = "Not proven: with " + repair.what + ", " +
           (broken ? std::to_string(broken) + " checks that passed fail" : "the same checks fail") +
           ": the repair does not mend your numbers.";
  } else {
    std::string ids;
    for (std::size_t k = 0; k < others.size(); ++k)
      ids += (k == 0 ? "" : k + 1 == others.size() ? " and " : ", ") + codeSpan(others[k]);
    const std::string other = "the other " + std::to_string(still) + (still == 1 ? " is" : " are");
    if (jointly)
      line = with + ": the " + std::to_string(still) + " failed " +
             (still == 1 ? "check is" : "checks are") + " then explained by " + ids +
             " (proven), which " + (others.size() == 1 ? "does" : "do") +
             " not explain your numbers as handed in: this mistake and " +
             (others.size() == 1 ? "that one" : "those") + " together give them.";
    else
      line = with + ": " + std::to_string(passing) + " of " + std::to_string(total) +
             (total == 1 ? " check passes" : " checks pass") +
             (still == 0         ? "."
              : others_explained ? "; " + other + " explained by " + ids + " (proven)."
                                 : "; " + other + " not explained by a proven mistake.");
  }
  for (std::size_t k = 0; k < tests.size(); ++k) {
    TestResult& t = tests[k];
    if (t.passed()) continue;
    if (!proven) {
      if (!t.names(repair.cause)) continue;
      Cause& cause = t.addCause(repair.cause, false);
      if (!cause.proven()) {
        cause.likely = false;
        cause.proof = line;
        cause.quotes = repair.lines;
      }
      continue;
    }
    if (repaired[k].passed()) {
      // Mended: the repaired lines were this check's mistake; what else was named was not.
      for (Cause& other : t.causes)
        if (other.id != repair.cause && other.likely) {
          other.likely = false;
          other.proof = "Not the mistake: with " + with.substr(5) + ", this check passes.";
        }
      Cause& cause = t.addCause(repair.cause, true);
      cause.likely = true;
      cause.proof = line;
      cause.quotes = repair.lines;
    } else {
      // Still failing: the repaired build's causes, with the repair named first (likely when it
      // and the repaired build's proven causes explain this check together).
      std::vector<Cause> causes;
      Cause mine{repair.cause, jointly, {}, {}, {}, {}, {}, line};
      mine.quotes = repair.lines;
      causes.push_back(mine);
      for (Cause c : repaired[k].causes) {
        if (c.id == repair.cause) continue;
        if (!c.proof.empty())
          c.proof = with + " (the numbers of the repaired build): " +
                    (c.proof.rfind("Proven: ", 0) == 0 ? c.proof.substr(8) : c.proof);
        causes.push_back(c);
      }
      std::stable_partition(causes.begin(), causes.end(), [](const Cause& c) { return c.likely; });
      t.causes = causes;
    }
  }
  return proven;
}

bool applyUnsetStart(const Repair& probe, bool built, const std::vector<TestResult>& started,
                     std::vector<TestResult>& tests) {
  if (!built || started.size() != tests.size()) return false;
  std::size_t changed = 0;
  for (std::size_t k = 0; k < tests.size(); ++k) {
    if (started[k].check != tests[k].check) return false;
    changed += tests[k].passed() && !started[k].passed();
  }
  if (changed == 0) return false;
  const std::string line = "Proven: with " + probe.what + ", " + std::to_string(changed) + " of " +
                           std::to_string(tests.size()) +
                           (changed == 1 ? " check fails" : " checks fail") +
                           ": your numbers rest on a value your code never sets, and your build "
                           "gave the course's by chance.";
  for (std::size_t k = 0; k < tests.size(); ++k) {
    TestResult& t = tests[k];
    if (!t.passed() || started[k].passed()) continue;
    t.fraction = 0;
    t.output = "Your build passes this check, but with " + probe.what + " it does not:\n\n" +
               started[k].output;
    Cause& cause = t.addCause(probe.cause, true);
    cause.likely = true;
    cause.proof = line;
    cause.quotes = probe.lines;
  }
  return true;
}

}  // namespace clothref::grader
