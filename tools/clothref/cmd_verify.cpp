// PLACEHOLDER, replaced by the issue that builds `clothref verify`.
#include "commands.h"

namespace clothref::cli {

Command addVerifyCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand("verify", "(not built yet)");
  return {app, [] { return kExitBadInput; }};
}

}  // namespace clothref::cli
