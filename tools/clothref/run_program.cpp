#include "run_program.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <iostream>

#include "clothref/io/error.h"

namespace clothref::cli {

int runProgram(const std::vector<std::string>& argv,
               const std::vector<std::pair<std::string, std::string>>& env,
               const std::string& what) {
  if (argv.empty() || ::access(argv[0].c_str(), X_OK) != 0)
    throw InputError(what + ": cannot run '" + (argv.empty() ? "" : argv[0]) + "'");
  std::vector<std::string> copy = argv;
  std::vector<char*> raw;
  for (std::string& a : copy) raw.push_back(a.data());
  raw.push_back(nullptr);
  const pid_t child = ::fork();
  if (child < 0) throw InputError(what + ": cannot start " + argv[0]);
  if (child == 0) {
    for (const auto& [name, value] : env) ::setenv(name.c_str(), value.c_str(), 1);
    ::execv(raw[0], raw.data());
    std::cerr << "clothref: " << what << ": cannot run " << argv[0] << '\n';
    std::_Exit(127);
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  throw InputError(what + ": " + argv[0] + " ended by signal " + std::to_string(WTERMSIG(status)));
}

}  // namespace clothref::cli
