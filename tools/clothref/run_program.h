// Running a helper program of the project (python3 scripts behind `plot` and `gradescope`) as a
// child process with a few environment variables set, waiting for it.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace clothref::cli {

// Runs argv[0] (a path) with `argv` and the environment plus `env` (name, value); stdin, stdout
// and stderr are ours. Returns the child's exit code; throws InputError naming `what` when it
// cannot start or ends by a signal.
int runProgram(const std::vector<std::string>& argv,
               const std::vector<std::pair<std::string, std::string>>& env,
               const std::string& what);

}  // namespace clothref::cli
