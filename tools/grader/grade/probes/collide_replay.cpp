// Contact models replayed (grader/grade/probes/collide_replay.h).
#include "grader/grade/probes/collide_replay.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "grader/grade/cause_ids.h"
#include "grader/grade/explain/replay.h"
#include "grader/grade/probes/util.h"

namespace clothref::grader::contacts {
namespace {

// `model` replayed on every case (explain/replay.h): its positions and velocities against the
// student's on each case's check, then whether it conserves momentum exactly where the student's
// call does (the momentum check).
Replay replayContacts(const ContactModel& model, const std::vector<Case>& cases,
                      const std::vector<Outcome>& actuals, const std::vector<PlannedTest>& checks,
                      bool sphere_sphere, double rel) {
  Replay replay;
  replay.model = contactModelText(model);
  bool momentum_same = true;
  for (std::size_t k = 0; k < cases.size() && k < actuals.size(); ++k) {
    const Case& c = cases[k];
    State s = c.state;
    collideModel(s.spheres, s.cloth, sphere_sphere, model);
    const Outcome m = outcomeOf(s);
    const Outcome& a = actuals[k];
    replay.checks.push_back({checks[c.check].check,
                             {{"positions", util::closeTo(m.cloth_x, a.cloth_x, rel) &&
                                                util::closeTo(m.sphere_x, a.sphere_x, rel)},
                              {"velocities", util::closeTo(m.cloth_v, a.cloth_v, rel) &&
                                                 util::closeTo(m.sphere_v, a.sphere_v, rel)},
                              {"accelerations", util::closeTo(m.cloth_a, a.cloth_a, rel) &&
                                                    util::closeTo(m.sphere_a, a.sphere_a, rel)}}});
    if (c.free_bodies) momentum_same = momentum_same && conserves(c, m) == conserves(c, a);
  }
  replay.checks.push_back({checks.back().check, {{"total momentum", momentum_same}}});
  return replay;
}

// Every check reproduced on its positions and velocities, and some check not on its accelerations.
bool allButAccelerations(const Replay& replay) {
  bool all_xv = true, accelerations_part = false;
  for (const ReplayCheck& check : replay.checks)
    for (const auto& [quantity, same] : check.quantities)
      if (quantity == "accelerations")
        accelerations_part = accelerations_part || !same;
      else
        all_xv = all_xv && same;
  return all_xv && accelerations_part;
}

}  // namespace

void proveContacts(std::vector<Candidate> candidates, const std::vector<Case>& cases,
                   const std::vector<Outcome>& actuals, const std::vector<PlannedTest>& checks,
                   bool sphere_sphere, double rel, const ContactModel& course,
                   std::vector<TestResult>& tests) {
  const bool failed =
      std::any_of(tests.begin(), tests.end(), [](const TestResult& t) { return !t.passed(); });
  if (!failed) return;
  const auto named = [&](const std::string& id, bool likely_only) {
    for (const TestResult& t : tests)
      for (const Cause& c : t.causes)
        if (c.id == id && (c.likely || !likely_only)) return true;
    return false;
  };
  std::stable_partition(candidates.begin(), candidates.end(),
                        [&](const Candidate& c) { return named(c.ids.front(), true); });
  std::vector<Replay> replays;
  std::string winner;
  for (const Candidate& c : candidates) {
    replays.push_back(replayContacts(c.model, cases, actuals, checks, sphere_sphere, rel));
    if (!replays.back().proven()) continue;
    if (winner.empty()) {
      applyReplay(replays.back(), c.ids, tests);
      winner = c.ids.front();
    } else if (c.ids.front() != winner) {
      alternative(replays.back(), c.ids, winner, tests);
    }
  }
  // Two mistakes at once: each pair of models with different causes, the first that proves.
  for (std::size_t i = 0; i < candidates.size() && winner.empty(); ++i)
    for (std::size_t j = i + 1; j < candidates.size() && winner.empty(); ++j) {
      if (candidates[i].ids == candidates[j].ids) continue;
      const ContactModel both = combined(candidates[i].model, candidates[j].model, course);
      const Replay pair = replayContacts(both, cases, actuals, checks, sphere_sphere, rel);
      if (!pair.proven()) continue;
      std::vector<std::string> ids = candidates[i].ids;
      ids.insert(ids.end(), candidates[j].ids.begin(), candidates[j].ids.end());
      applyReplay(pair, ids, tests);
      winner = ids.front();
    }
  // A model that gives every position and velocity but not the accelerations: no contact model
  // changes an acceleration, so there the student's call did (collide-changes-acceleration, read
  // directly: e.g. friction added to them). With that read the model accounts for every number
  // of the stub, and its causes and the read one (on the checks whose accelerations changed) are
  // proven. The course's collide is tried first: when it is that model, the read is all.
  const auto withTheRead = [&](const Replay& replay, const std::vector<std::string>& ids) {
    Replay joint = replay;
    joint.model +=
        " (and the accelerations as your call changed them, which the course's "
        "collide leaves alone)";
    std::set<std::string> changed;
    for (ReplayCheck& check : joint.checks)
      for (auto& [quantity, same] : check.quantities)
        if (quantity == "accelerations" && !same) same = true, changed.insert(check.check);
    applyReplay(joint, ids, tests);
    for (TestResult& t : tests)
      if (!t.passed() && changed.count(t.check)) {
        Cause& read = t.addCause(cause::kCollideChangesAcceleration, true);
        read.likely = true;
        read.proof = joint.line();
      }
  };
  if (winner.empty()) {
    const Replay plain = replayContacts(course, cases, actuals, checks, sphere_sphere, rel);
    if (allButAccelerations(plain)) {
      withTheRead(plain, {});
      winner = cause::kCollideChangesAcceleration;
    }
  }
  for (std::size_t m = 0; m < candidates.size() && winner.empty(); ++m)
    if (allButAccelerations(replays[m])) {
      withTheRead(replays[m], candidates[m].ids);
      winner = candidates[m].ids.front();
    }
  // The causes named that no model proved: their best model's line.
  for (std::size_t m = 0; m < candidates.size(); ++m) {
    const std::string& id = candidates[m].ids.front();
    if (!named(id, false)) continue;
    std::size_t best = m;
    for (std::size_t q = 0; q < candidates.size(); ++q)
      if (candidates[q].ids.front() == id && replays[q].reproduced() > replays[best].reproduced())
        best = q;
    if (best == m && !replays[m].proven()) applyReplay(replays[m], candidates[m].ids, tests);
  }
}

}  // namespace clothref::grader::contacts
