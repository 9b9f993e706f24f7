// The contact models of a student's collide replayed on the probe's cases (issue 38, "likely
// means proven"): each model a cause stands for (explain/replay.h) against the student's
// positions, velocities and momentum on every case, and the causes named from what they prove.
#pragma once
#include <string>
#include <vector>

#include "grader/grade/mistakes/formula_variants.h"
#include "grader/grade/probes/collide_cases.h"
#include "grader/grade/results.h"

namespace clothref::grader::contacts {

// A model of the student's collide and the causes it stands for.
struct Candidate {
  std::vector<std::string> ids;
  ContactModel model;
};

// Names the causes the replays prove (explain/replay.h): the first model (those of the causes
// named likely first) that gives the student's numbers on every check, else the first pair of
// models that does together; another proving model is an alternative reading, a guess saying so.
// A cause named that no model proves becomes a guess whose line says where its best model parts.
void proveContacts(std::vector<Candidate> candidates, const std::vector<Case>& cases,
                   const std::vector<Outcome>& actuals, const std::vector<PlannedTest>& checks,
                   bool sphere_sphere, double rel, const ContactModel& course,
                   std::vector<TestResult>& tests);

}  // namespace clothref::grader::contacts
