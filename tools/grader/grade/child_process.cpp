#include "child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

namespace clothref::grader {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void setLimit(int resource, std::uint64_t value) {
  rlimit limit{static_cast<rlim_t>(value), static_cast<rlim_t>(value)};
  setrlimit(resource, &limit);
}

std::string readHead(const std::filesystem::path& path, std::size_t max_bytes, int max_lines) {
  std::ifstream in(path, std::ios::binary);
  std::string out, line;
  int lines = 0;
  while (lines < max_lines && out.size() < max_bytes && std::getline(in, line)) {
    out += line.substr(0, max_bytes - out.size());
    out += '\n';
    ++lines;
  }
  return out;
}

std::string signalName(int signal) {
  switch (signal) {
    case SIGSEGV:
      return "SIGSEGV, segmentation fault";
    case SIGABRT:
      return "SIGABRT, abort";
    case SIGFPE:
      return "SIGFPE, arithmetic error";
    case SIGBUS:
      return "SIGBUS, bus error";
    case SIGILL:
      return "SIGILL, illegal instruction";
    case SIGKILL:
      return "SIGKILL";
    case SIGXCPU:
      return "SIGXCPU, CPU time limit";
    case SIGXFSZ:
      return "SIGXFSZ, output file size limit";
    default:
      return "signal " + std::to_string(signal);
  }
}

// Child side of fork: never returns.
// argv and env are built before fork: after fork in a threaded grader only async-signal-safe
// calls are allowed (no allocation).
struct ExecArgs {
  std::vector<std::string> strings;
  std::vector<char*> argv;
  std::string dir;
  explicit ExecArgs(const std::vector<std::string>& command, const std::filesystem::path& where)
      : strings(command), dir(where.string()) {
    for (std::string& a : strings) argv.push_back(a.data());
    argv.push_back(nullptr);
  }
};

[[noreturn]] void execChild(const ExecArgs& exec, int stdin_fd, int stdout_fd, int stderr_fd,
                            int answer_fd, const ChildLimits* limits) {
  setpgid(0, 0);
  dup2(stdin_fd, 0);
  dup2(stdout_fd, 1);
  dup2(stderr_fd, 2);
  if (answer_fd >= 0) {
    dup2(answer_fd, probe::kResultFd);
  } else {
    int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, probe::kResultFd);
  }
  for (int fd = probe::kResultFd + 1; fd < 1024; ++fd) close(fd);
  if (chdir(exec.dir.c_str()) != 0) _exit(126);
  if (limits) {
    setLimit(RLIMIT_CPU, limits->cpu_seconds);
    setLimit(RLIMIT_AS, limits->address_space_bytes);
    setLimit(RLIMIT_FSIZE, limits->file_size_bytes);
    setLimit(RLIMIT_NOFILE, limits->open_files);
    setLimit(RLIMIT_CORE, 0);
  }
  // A clean environment: nothing of the grader's leaks into student code.
  char path_env[] = "PATH=/usr/local/bin:/usr/bin:/bin";
  char lang_env[] = "LC_ALL=C";
  char* env[] = {path_env, lang_env, nullptr};
  execve(exec.argv[0], exec.argv.data(), env);
  if (errno == ENOENT) execvpe(exec.argv[0], exec.argv.data(), env);
  _exit(127);
}

}  // namespace

std::string ChildRun::describe() const {
  std::ostringstream out;
  switch (status) {
    case ChildStatus::Ok:
      out << "finished";
      break;
    case ChildStatus::Crashed:
      out << "crashed (" << signalName(signal) << ")";
      break;
    case ChildStatus::TimedOut:
      out << "timed out after " << static_cast<int>(seconds + 0.5) << " s";
      break;
    case ChildStatus::ExitedNonZero:
      out << "exited with code " << exit_code;
      break;
    case ChildStatus::NoAnswer:
      out << "exited without sending the probe results";
      break;
  }
  return out.str();
}

ChildRun runChild(const std::vector<std::string>& command, const std::filesystem::path& work_dir,
                  const std::filesystem::path& stdin_file, const ChildLimits& limits,
                  bool expect_answer, std::uint64_t request_nonce) {
  ChildRun run;
  const auto start = Clock::now();
  std::vector<std::string> argv = limits.launcher;
  argv.insert(argv.end(), command.begin(), command.end());
  const auto out_path = work_dir / "child.stdout";
  const auto err_path = work_dir / "child.stderr";
  int in_fd = open(stdin_file.c_str(), O_RDONLY | O_CLOEXEC);
  int out_fd = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  int pipe_fds[2] = {-1, -1};
  if (in_fd < 0 || out_fd < 0 || err_fd < 0 || pipe2(pipe_fds, O_CLOEXEC) != 0) {
    for (int fd : {in_fd, out_fd, err_fd, pipe_fds[0], pipe_fds[1]})
      if (fd >= 0) close(fd);
    run.status = ChildStatus::ExitedNonZero;
    run.exit_code = -1;
    run.stderr_head = "grader: cannot set up the child's files or pipe";
    return run;
  }
  const ExecArgs exec(argv, work_dir);
  const pid_t pid = fork();
  if (pid == 0) execChild(exec, in_fd, out_fd, err_fd, expect_answer ? pipe_fds[1] : -1, &limits);
  close(in_fd);
  close(out_fd);
  close(err_fd);
  close(pipe_fds[1]);
  setpgid(pid, pid);  // also done in the child; whichever runs first wins the race harmlessly

  std::string answer;
  bool timed_out = false;
  const std::size_t max_answer = 512u << 20;
  for (bool open_pipe = true; open_pipe;) {
    const double left = limits.wall_seconds - secondsSince(start);
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd fd{pipe_fds[0], POLLIN, 0};
    const int ready = poll(&fd, 1, static_cast<int>(std::min(left, 0.5) * 1000) + 1);
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    char buffer[65536];
    const ssize_t n = read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      open_pipe = false;
    else if (answer.size() < max_answer)
      answer.append(buffer, static_cast<std::size_t>(n));
  }
  close(pipe_fds[0]);
  int status = 0;
  while (!timed_out) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (secondsSince(start) >= limits.wall_seconds) {
      timed_out = true;
      break;
    }
    usleep(2000);
  }
  if (timed_out) {
    kill(-pid, SIGKILL);
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    run.status = ChildStatus::TimedOut;
  } else {
    kill(-pid, SIGKILL);  // any grandchildren left behind
    if (WIFSIGNALED(status)) {
      run.status = ChildStatus::Crashed;
      run.signal = WTERMSIG(status);
    } else if (WEXITSTATUS(status) != 0) {
      run.status = ChildStatus::ExitedNonZero;
      run.exit_code = WEXITSTATUS(status);
    } else if (expect_answer) {
      run.answer = probe::decodeMessage(answer);
      if (run.answer && run.answer->nonce != request_nonce) run.answer.reset();
      run.status = run.answer ? ChildStatus::Ok : ChildStatus::NoAnswer;
    } else {
      run.status = ChildStatus::Ok;
    }
  }
  run.seconds = secondsSince(start);
  run.stderr_head = readHead(err_path, 2000, 12);
  return run;
}

ChildRun runProbe(const std::filesystem::path& executable, probe::ProbeMessage request,
                  const std::filesystem::path& work_dir, const ChildLimits& limits) {
  std::random_device entropy;
  request.nonce = (std::uint64_t(entropy()) << 32) ^ entropy();
  const auto request_path = work_dir / "request.bin";
  {
    std::ofstream out(request_path, std::ios::binary | std::ios::trunc);
    const std::string frame = probe::encodeMessage(request);
    out.write(frame.data(), static_cast<std::streamsize>(frame.size()));
  }
  return runChild({executable.string()}, work_dir, request_path, limits, true, request.nonce);
}

std::vector<ToolRun> runTools(const std::vector<std::vector<std::string>>& commands,
                              const std::filesystem::path& work_dir, int jobs,
                              double wall_seconds) {
  struct Running {
    pid_t pid;
    std::size_t index;
    Clock::time_point start;
  };
  std::vector<ToolRun> results(commands.size());
  std::vector<Running> running;
  std::size_t next = 0;
  const auto log_path = [&](std::size_t i) {
    return work_dir / ("tool-" + std::to_string(i) + ".log");
  };
  const auto null_in = std::filesystem::path("/dev/null");
  while (next < commands.size() || !running.empty()) {
    while (next < commands.size() && static_cast<int>(running.size()) < std::max(1, jobs)) {
      const auto log = log_path(next);
      int in_fd = open(null_in.c_str(), O_RDONLY | O_CLOEXEC);
      int log_fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      const ExecArgs exec(commands[next], work_dir);
      const pid_t pid = fork();
      if (pid == 0) execChild(exec, in_fd, log_fd, log_fd, -1, nullptr);
      close(in_fd);
      close(log_fd);
      setpgid(pid, pid);
      running.push_back({pid, next, Clock::now()});
      ++next;
    }
    for (std::size_t r = 0; r < running.size();) {
      int status = 0;
      const pid_t done = waitpid(running[r].pid, &status, WNOHANG);
      const bool late = secondsSince(running[r].start) > wall_seconds;
      if (done == running[r].pid || late) {
        if (late && done != running[r].pid) {
          kill(-running[r].pid, SIGKILL);
          waitpid(running[r].pid, &status, 0);
        }
        ToolRun& result = results[running[r].index];
        result.ok = !late && WIFEXITED(status) && WEXITSTATUS(status) == 0;
        result.seconds = secondsSince(running[r].start);
        result.output = readHead(log_path(running[r].index), 200000, 4000);
        if (late)
          result.output += "\n(stopped after " + std::to_string(int(wall_seconds)) + " s)\n";
        running.erase(running.begin() + static_cast<long>(r));
      } else {
        ++r;
      }
    }
    usleep(5000);
  }
  return results;
}

}  // namespace clothref::grader
