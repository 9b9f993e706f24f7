// clothref verify: run every analytic check (lib/clothref/verify/verify.h) and print the table, or
// with
// --json the same as JSON. Exit 0 when every check passes, 1 when one fails.
#include <iostream>
#include <memory>

#include "clothref/verify/verify.h"
#include "commands.h"

namespace clothref::cli {

namespace {

struct VerifyOptions {
  bool json = false;
};

int runVerify(const VerifyOptions& options) {
  const VerifyReport report = runVerification();
  if (options.json)
    std::cout << reportToJson(report).dump(2) << '\n';
  else
    std::cout << reportTable(report);
  return report.passed() ? kExitOk : kExitDiffer;
}

}  // namespace

Command addVerifyCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "verify",
      "Run the analytic checks (closed forms, convergence orders, impacts, momentum) in float and "
      "double; exit 1 if one fails (docs/verification.md)");
  auto options = std::make_shared<VerifyOptions>();
  app->add_flag("--json", options->json,
                "Print {\"orders\", \"float_floor\", \"studies\", \"checks\", \"passed\"} as JSON");
  return {app, [options] { return runVerify(*options); }};
}

}  // namespace clothref::cli
