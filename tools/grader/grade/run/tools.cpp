#include "grader/grade/run/tools.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "grader/grade/run/spawn.h"

namespace clothref::grader {
using namespace spawn;

namespace {

// A tool's log as the grader reads it: its size, whether any byte is not white space (read up to
// kScannedLogBytes; a larger log has text), and the lines kept for the messages: at most 4000
// lines and 200000 bytes, blank lines left out.
struct ToolLog {
  std::uint64_t bytes = 0;
  bool has_text = false;
  std::string kept;
};
constexpr std::uint64_t kScannedLogBytes = 64ull << 20;

ToolLog readToolLog(const std::filesystem::path& path) {
  ToolLog log;
  const long size = fileSize(path);
  log.bytes = size > 0 ? static_cast<std::uint64_t>(size) : 0;
  log.has_text = log.bytes > kScannedLogBytes;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  int lines = 0;
  std::uint64_t scanned = 0;
  while (scanned < kScannedLogBytes && std::getline(in, line)) {
    scanned += line.size() + 1;
    if (line.find_first_not_of(" \t\r\v\f") == std::string::npos) continue;
    log.has_text = true;
    if (lines >= 4000 || log.kept.size() >= 200000) continue;
    log.kept += line.substr(0, 200000 - log.kept.size()) + "\n";
    ++lines;
  }
  return log;
}

// The fallback's confinement of one compile or link (docs/grading-reference.md, "Sandbox"): as
// root, the tool uid, and (where a private mount namespace can be made) our folders covered. A
// command writing outside `work_dir` (the precompiled header into the cache) compiles only our own
// headers and keeps the grader's uid.
void confineTool(const Isolation& isolation, const std::vector<std::string>& command,
                 const std::filesystem::path& work_dir, ExecLimits& how) {
  if (isolation.tool_uid < 0) return;
  const auto under = [](const std::filesystem::path& path, const std::filesystem::path& root) {
    const std::string p = path.lexically_normal().string(), r = root.lexically_normal().string();
    return p == r || (p.size() > r.size() && p.compare(0, r.size(), r) == 0 && p[r.size()] == '/');
  };
  for (std::size_t k = 0; k + 1 < command.size(); ++k)
    if (command[k] == "-o" && !under(command[k + 1], work_dir)) return;
  // The tool uid writes its objects into the scratch folder, nowhere else.
  if (chown(work_dir.c_str(), static_cast<uid_t>(isolation.tool_uid),
            static_cast<gid_t>(isolation.tool_uid)) != 0 ||
      chmod(work_dir.c_str(), 0700) != 0)
    return;
  how.uid = isolation.tool_uid;
  if (isolation.kind != IsolationKind::Rlimits || !isolation.private_mounts) return;
  how.new_mount_namespace = true;
  std::error_code error;
  for (const std::filesystem::path& folder : isolation.ours) {
    if (folder.empty() || under(work_dir, folder) || !std::filesystem::is_directory(folder, error))
      continue;
    bool named = false;
    for (std::size_t k = 1; k < command.size() && !named; ++k) {
      const std::string arg = command[k].rfind("-I", 0) == 0 ? command[k].substr(2) : command[k];
      named = !arg.empty() && arg[0] == '/' && (under(arg, folder) || under(folder, arg));
    }
    if (!named) how.hide.push_back(folder.lexically_normal().string());
  }
}
}  // namespace

std::vector<ToolRun> runTools(const std::vector<std::vector<std::string>>& commands,
                              const std::filesystem::path& work_dir, int jobs, double wall_seconds,
                              const Isolation* isolation) {
  struct Running {
    pid_t pid;
    std::size_t index;
    Clock::time_point start;
    int setup_fd, status_fd;
  };
  std::vector<ToolRun> results(commands.size());
  std::vector<int> attempts(commands.size(), 0);
  std::vector<Running> running;
  std::vector<std::size_t> queue;
  for (std::size_t k = commands.size(); k-- > 0;) queue.push_back(k);
  const auto log_path = [&](std::size_t i) {
    return work_dir / ("tool-" + std::to_string(i) + ".log");
  };
  const auto null_in = std::filesystem::path("/dev/null");
  const bool boxed = isolation && isolation->kind == IsolationKind::Bubblewrap;
  // A failure of ours (the tool not started, bubblewrap failing) is tried again once, then
  // reported as ours: never as the student's compile error.
  const auto ours = [&](std::size_t index, const std::string& why) {
    if (attempts[index]++ == 0) {
      queue.push_back(index);
      return;
    }
    results[index].ok = false;
    results[index].ours = true;
    results[index].output = "grader: " + why + "\n";
  };
  while (!queue.empty() || !running.empty()) {
    while (!queue.empty() && static_cast<int>(running.size()) < std::max(1, jobs)) {
      const std::size_t index = queue.back();
      queue.pop_back();
      const auto log = log_path(index);
      int in_fd = open(null_in.c_str(), O_RDONLY | O_CLOEXEC);
      int log_fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      int setup_fds[2] = {-1, -1}, status_fds[2] = {-1, -1};
      const bool pipes = pipe2(setup_fds, O_CLOEXEC) == 0 &&
                         (!boxed || pipe2(status_fds, O_CLOEXEC | O_NONBLOCK) == 0);
      ExecLimits how;
      how.tool_seconds = wall_seconds;
      if (isolation && isolation->kind != IsolationKind::None)
        confineTool(*isolation, commands[index], work_dir, how);
      how.injected_fault = injectFault("tool-setup");
      std::vector<std::string> argv = commands[index];
      if (boxed) argv = bubblewrapToolArgv(*isolation, commands[index], work_dir, kInfoFd);
      const ExecArgs exec(argv, work_dir);
      const bool fork_fault = injectFault("tool-fork");
      const pid_t pid = in_fd < 0 || log_fd < 0 || !pipes || fork_fault ? -1 : fork();
      if (pid == 0) {
        ChildFds fds;
        fds.in = in_fd;
        fds.out = fds.err = log_fd;
        fds.info = status_fds[1];
        fds.setup = setup_fds[1];
        execChild(exec, fds, how);
      }
      const int fork_error = errno;
      for (int fd : {in_fd, log_fd, setup_fds[1], status_fds[1]})
        if (fd >= 0) close(fd);
      if (pid < 0) {
        for (int fd : {setup_fds[0], status_fds[0]})
          if (fd >= 0) close(fd);
        ours(index, fork_fault ? setupFailureText(kSetupInjected)
                               : std::string("cannot start the tool (fork: ") +
                                     std::strerror(fork_error) + ")");
        continue;
      }
      setpgid(pid, pid);
      running.push_back({pid, index, Clock::now(), setup_fds[0], status_fds[0]});
    }
    for (std::size_t r = 0; r < running.size();) {
      int status = 0;
      const pid_t done = waitpid(running[r].pid, &status, WNOHANG);
      const bool late = secondsSince(running[r].start) > wall_seconds;
      if (done == running[r].pid || late) {
        if (late && done != running[r].pid) {
          killGroup(running[r].pid);
          waitpid(running[r].pid, &status, 0);
        }
        const Running finished = running[r];
        running.erase(running.begin() + static_cast<long>(r));
        std::string json;
        if (finished.status_fd >= 0) {
          readAvailable(finished.status_fd, json);
          close(finished.status_fd);
        }
        const unsigned char why = setupReport(finished.setup_fd);
        close(finished.setup_fd);
        const ToolLog log = readToolLog(log_path(finished.index));
        const std::string& output = log.kept;
        if (why) {
          ours(finished.index, setupFailureText(why));
          continue;
        }
        if (boxed && !late && !bubblewrapExitCode(json)) {
          ours(finished.index, "bubblewrap failed: " + output.substr(0, output.find('\n')));
          continue;
        }
        // A compiler or linker that fails says why; one that fails in silence was stopped from
        // outside (seen: killed by another root's grader under the same uid), not by the code.
        // Judged on the raw bytes of the log and the exit status, never on the lines kept: a
        // `#line` naming the file with thousands of newlines makes every message start blank.
        const bool exited_ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
        if (!late && !exited_ok && !log.has_text) {
          ours(finished.index, WIFSIGNALED(status)
                                   ? "the tool was stopped by signal " +
                                         std::to_string(WTERMSIG(status)) + " without a message"
                                   : "the tool failed without a message (exit " +
                                         std::to_string(WEXITSTATUS(status)) + ")");
          continue;
        }
        ToolRun& result = results[finished.index];
        result.ok = !late && exited_ok;
        result.seconds = secondsSince(finished.start);
        result.output = output;
        if (late)
          result.output += "\n(stopped after " + std::to_string(int(wall_seconds)) + " s)\n";
      } else {
        ++r;
      }
    }
    usleep(5000);
  }
  return results;
}

}  // namespace clothref::grader
