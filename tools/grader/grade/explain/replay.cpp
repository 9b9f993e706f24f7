#include "grader/grade/explain/replay.h"

#include <algorithm>

namespace clothref::grader {

int Replay::reproduced() const {
  return int(std::count_if(checks.begin(), checks.end(),
                           [](const ReplayCheck& c) { return c.reproduced(); }));
}

bool Replay::proven() const { return !checks.empty() && reproduced() == int(checks.size()); }

namespace {

std::string checksWord(int n) { return std::to_string(n) + (n == 1 ? " check" : " checks"); }

std::string listed(const std::vector<std::string>& words) {
  std::string out;
  for (std::size_t k = 0; k < words.size(); ++k)
    out += (k == 0 ? "" : k + 1 == words.size() ? " and " : ", ") + words[k];
  return out;
}

}  // namespace

std::string Replay::line() const {
  const int total = int(checks.size()), same = reproduced();
  if (proven())
    return "Proven: " + model + " gives your numbers on " + std::to_string(same) + " of " +
           checksWord(total) + ".";
  // Where they part: the unreproduced checks grouped by what the model gets right there.
  std::vector<std::pair<std::string, std::vector<std::string>>> parts;  // (how, checks)
  for (const ReplayCheck& c : checks) {
    if (c.reproduced()) continue;
    std::vector<std::string> right, wrong;
    for (const auto& [quantity, ok] : c.quantities) (ok ? right : wrong).push_back(quantity);
    const std::string how = right.empty()
                                ? "none of your " + listed(wrong)
                                : "your " + listed(right) + " but not your " + listed(wrong);
    auto it =
        std::find_if(parts.begin(), parts.end(), [&](const auto& p) { return p.first == how; });
    if (it == parts.end()) {
      parts.push_back({how, {}});
      it = parts.end() - 1;
    }
    it->second.push_back(c.check);
  }
  std::string out = "Not proven: " + model + " gives your numbers on " + std::to_string(same) +
                    " of " + checksWord(total);
  for (std::size_t k = 0; k < parts.size() && k < 2; ++k) {
    const auto& [how, names] = parts[k];
    out += std::string(k == 0 ? "; " : "; ") + "on " + std::to_string(names.size()) + " (“" +
           names.front() + "”" + (names.size() > 1 ? ", ..." : "") + ") it gives " + how;
  }
  if (parts.size() > 2) out += "; and it parts from yours elsewhere";
  return out + ".";
}

void applyReplay(const Replay& replay, const std::vector<std::string>& ids,
                 std::vector<TestResult>& tests) {
  const bool proven = replay.proven();
  const std::string line = replay.line();
  for (TestResult& t : tests) {
    if (t.passed()) continue;
    for (const std::string& id : ids) {
      if (!proven && !t.names(id)) continue;
      const bool before = std::any_of(t.causes.begin(), t.causes.end(),
                                      [&](const Cause& c) { return c.id == id && c.proven(); });
      if (before) continue;  // proven already (by another model of the same cause)
      // A likely cause without its proof becomes a guess that says where its model parts.
      Cause& cause = t.addCause(id, false);
      cause.likely = proven;
      if (proven || cause.proof.empty()) cause.proof = line;
    }
  }
}

void alternative(const Replay& replay, const std::vector<std::string>& ids,
                 const std::string& named, std::vector<TestResult>& tests) {
  const std::string line = replay.line();
  const std::string also =
      "Gives your numbers too: " + (line.rfind("Proven: ", 0) == 0 ? line.substr(8) : line) +
      " The cause named is `" + named + "`.";
  for (TestResult& t : tests)
    for (Cause& cause : t.causes)
      if (!t.passed() && std::find(ids.begin(), ids.end(), cause.id) != ids.end() &&
          cause.id != named && !cause.proven()) {
        cause.likely = false;
        cause.proof = also;
      }
}

void requireProofs(std::vector<TestResult>& tests, const std::vector<std::string>& observed) {
  for (TestResult& t : tests) {
    for (Cause& cause : t.causes)
      if (cause.likely && cause.proof.empty() &&
          std::find(observed.begin(), observed.end(), cause.id) == observed.end())
        cause.likely = false;
    // The likely causes first, as everywhere (results.h, TestResult::causes).
    std::stable_partition(t.causes.begin(), t.causes.end(),
                          [](const Cause& c) { return c.likely; });
  }
}

}  // namespace clothref::grader
