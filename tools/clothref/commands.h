// Subcommands of the clothref CLI. Each add*Command registers its options on `root` and returns
// the command; main runs the one the user named. A run returns the process exit code.
#pragma once

#include <charconv>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "clothref/base/enum_table.h"

namespace clothref::cli {

struct Command {
  CLI::App* app;
  std::function<int()> run;
};

// Exit codes shared by every command (README.md: 0 ok, 1 differ, 2 bad input).
inline constexpr int kExitOk = 0;
inline constexpr int kExitDiffer = 1;    // diff: traces differ; golden: a file does not match
inline constexpr int kExitBadInput = 2;  // bad flag, file or content

// Accepts exactly the names of an enum table (the one table per enum, base/enum_table.h); the
// option's string then parses with parseEnum.
// An integer option's lower bound: "--steps: must be >= 0 (got -1)".
inline CLI::Validator atLeast(long long minimum) {
  return CLI::Validator(
      [minimum](std::string& text) -> std::string {
        // from_chars refuses what does not fit (strtoll would clamp 10^20 to 2^63-1)
        long long value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error == std::errc::result_out_of_range) return "too large (got " + text + ")";
        if (error != std::errc() || end != text.data() + text.size())
          return "expected an integer, got '" + text + "'";
        if (value < minimum) return "must be >= " + std::to_string(minimum) + " (got " + text + ")";
        return "";
      },
      ">= " + std::to_string(minimum));
}

// A finite number > 0: "--dt: must be a finite number > 0 (got nan)".
inline CLI::Validator finitePositive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value)) return "expected a number, got '" + text + "'";
        if (!(value > 0 && value <= std::numeric_limits<double>::max()))
          return "must be a finite number > 0 (got " + text + ")";
        return "";
      },
      "> 0");
}

template <typename E, std::size_t N>
CLI::IsMember oneOf(const EnumTable<E, N>& table) {
  std::vector<std::string> names;
  for (const EnumName<E>& entry : table) names.emplace_back(entry.name);
  return CLI::IsMember(names);
}

Command addTraceCommand(CLI::App& root);
Command addDiffCommand(CLI::App& root);
Command addGoldenCommand(CLI::App& root);
Command addVerifyCommand(CLI::App& root);
Command addScenesCommand(CLI::App& root);
Command addBenchCommand(CLI::App& root);
Command addStabilityCommand(CLI::App& root);
Command addSweepCommand(CLI::App& root);
Command addPlotCommand(CLI::App& root);
Command addGradeCommand(CLI::App& root);
Command addGradescopeCommand(CLI::App& root);
Command addViewCommand(CLI::App& root);

}  // namespace clothref::cli
