// clothref verify: a row and its rule, and running every check family (the families are one file
// each: closed_form_checks, order_checks, collision_checks, conservation_checks,
// stability_checks, course_form_checks, contact_checks, peer_checks; verify_report renders).
#include "clothref/verify/verify.h"

#include <algorithm>
#include <cmath>

namespace clothref {

CheckRow makeRow(std::string check, std::string method, Precision precision, double expected,
                 double observed, double tolerance, CheckRule rule) {
  CheckRow row;
  row.check = std::move(check);
  row.method = std::move(method);
  row.precision = precision;
  row.expected = expected;
  row.observed = observed;
  row.tolerance = tolerance;
  row.rule = rule;
  // written so that a NaN observation fails
  row.pass = rule == CheckRule::Within ? std::abs(observed - expected) <= tolerance
                                       : observed <= expected + tolerance;
  return row;
}

bool VerifyReport::passed() const {
  return std::all_of(checks.begin(), checks.end(), [](const CheckRow& row) { return row.pass; });
}

VerifyReport runVerification() {
  VerifyReport report;
  report.studies = convergenceStudies();
  auto append = [&report](std::vector<CheckRow> rows) {
    report.checks.insert(report.checks.end(), rows.begin(), rows.end());
  };
  append(closedFormChecks());
  append(convergenceChecks(report.studies));
  append(sphereSphereChecks());
  append(sphereClothChecks());
  append(contactChecks());
  append(freeClothMomentumChecks());
  append(energyChecks());
  append(courseFactChecks());
  append(courseFormChecks());
  append(peerChecks());
  return report;
}

}  // namespace clothref
