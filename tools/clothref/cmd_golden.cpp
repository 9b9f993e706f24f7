// PLACEHOLDER, replaced by the issue that builds `clothref golden`.
#include "commands.h"

namespace clothref::cli {

Command addGoldenCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand("golden", "(not built yet)");
  return {app, [] { return kExitBadInput; }};
}

}  // namespace clothref::cli
