// clothref: the reference for the course's particle-system assignment. One subcommand per task;
// `clothref SUBCOMMAND --help` for each.
#include <iostream>
#include <stdexcept>

#include "clothref/fast/simd_path.h"
#include "clothref/io/error.h"
#include "clothref/trace/build_info.h"
#include "commands.h"

int main(int argc, char** argv) {
  using namespace clothref::cli;
  CLI::App root{"clothref: deterministic reference, traces and checks for the cloth-and-spheres "
                "particle-system assignment"};
  root.require_subcommand(1);
  clothref::fast::SimdPath simd;
  try {
    simd = clothref::fast::defaultSimdPath();  // a bad CLOTHREF_SIMD fails here, before any work
  } catch (const std::invalid_argument& error) {
    std::cerr << "clothref: " << error.what() << '\n';
    return kExitBadInput;
  }
  root.set_version_flag("--version", std::string(clothref::build_info::kVersion) + " (" +
                                         clothref::build_info::kCompiler + ", " +
                                         clothref::build_info::kBuildType + ", simd " +
                                         std::string(clothref::fast::simdPathName(simd)) + ")");
  const std::vector<Command> commands = {
      addTraceCommand(root), addDiffCommand(root), addGoldenCommand(root),
      addVerifyCommand(root), addScenesCommand(root), addBenchCommand(root)};
  // name an unknown command instead of CLI11's "A subcommand is required"
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const Command& command : commands) {
      known = known || command.app->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + command.app->get_name();
    }
    if (!known) {
      std::cerr << "clothref: unknown command '" << argv[1] << "' (commands: " << names << ")\n";
      return kExitBadInput;
    }
  }
  try {
    root.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return root.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return root.exit(help);
  } catch (const CLI::CallForVersion& version) {
    std::cout << "clothref " << version.what() << '\n';
    return kExitOk;
  } catch (const CLI::ParseError& error) {
    // one line, like every other bad input
    std::cerr << "clothref: " << error.what() << '\n';
    return kExitBadInput;
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
