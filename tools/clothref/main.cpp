// clothref: the reference for the course's particle-system assignment. One subcommand per task;
// `clothref SUBCOMMAND --help` for each.
#include <iostream>

#include "clothref/io/error.h"
#include "commands.h"

int main(int argc, char** argv) {
  using namespace clothref::cli;
  CLI::App root{"clothref: deterministic reference, traces and checks for the cloth-and-spheres "
                "particle-system assignment"};
  root.require_subcommand(1);
  const std::vector<Command> commands = {
      addTraceCommand(root), addDiffCommand(root), addGoldenCommand(root),
      addVerifyCommand(root), addScenesCommand(root)};
  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = root.exit(error);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  try {
    for (const Command& command : commands)
      if (command.app->parsed()) return command.run();
  } catch (const clothref::InputError& error) {
    std::cerr << "clothref: " << error.what() << '\n';
    return kExitBadInput;
  }
  return kExitBadInput;
}
