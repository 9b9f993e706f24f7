// PLACEHOLDER, replaced by the issue that builds `clothref diff`.
#include "commands.h"

namespace clothref::cli {

Command addDiffCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand("diff", "(not built yet)");
  return {app, [] { return kExitBadInput; }};
}

}  // namespace clothref::cli
