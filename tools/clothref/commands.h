// Subcommands of the clothref CLI. Each add*Command registers its options on `root` and returns
// the command; main runs the one the user named. A run returns the process exit code.
#pragma once

#include <functional>
#include <vector>

#include <CLI/CLI.hpp>

namespace clothref::cli {

struct Command {
  CLI::App* app;
  std::function<int()> run;
};

// Exit codes shared by every command (product.md).
inline constexpr int kExitOk = 0;
inline constexpr int kExitDiffer = 1;    // diff: traces differ; golden: a file does not match
inline constexpr int kExitBadInput = 2;  // bad flag, file or content

Command addTraceCommand(CLI::App& root);
Command addDiffCommand(CLI::App& root);
Command addGoldenCommand(CLI::App& root);
Command addVerifyCommand(CLI::App& root);
Command addScenesCommand(CLI::App& root);

}  // namespace clothref::cli
