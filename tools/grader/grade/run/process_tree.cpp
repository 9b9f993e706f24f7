#include "grader/grade/run/process_tree.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace clothref::grader {
namespace {

struct Stat {
  pid_t parent = 0;
  double ticks = 0;  // utime + stime + cutime + cstime
};

// /proc/<pid>/stat: the name (field 2) is in parentheses and may hold spaces, so the fields are
// read after its last ')': state, ppid, ..., utime (14), stime, cutime, cstime (17).
bool readStat(const std::filesystem::path& file, Stat& stat) {
  std::ifstream in(file);
  std::string text;
  if (!std::getline(in, text)) return false;
  const std::size_t close = text.rfind(')');
  if (close == std::string::npos) return false;
  std::istringstream fields(text.substr(close + 1));
  std::string field;
  std::vector<std::string> after;  // fields 3, 4, ...
  while (after.size() < 15 && fields >> field) after.push_back(field);
  if (after.size() < 15) return false;
  try {
    stat.parent = static_cast<pid_t>(std::stol(after[1]));
    for (std::size_t k = 11; k < 15; ++k) stat.ticks += std::stod(after[k]);
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

// Every process of /proc with its parent and ticks, and the pids of `root`'s tree (empty when
// `root` is not there).
std::vector<pid_t> treeOf(pid_t root, std::map<pid_t, Stat>& all) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", error)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    Stat stat;
    if (readStat(entry.path() / "stat", stat)) all[static_cast<pid_t>(std::stol(name))] = stat;
  }
  if (!all.count(root)) return {};
  std::map<pid_t, std::vector<pid_t>> children;
  for (const auto& [pid, stat] : all) children[stat.parent].push_back(pid);
  std::vector<pid_t> tree, todo = {root};
  while (!todo.empty()) {
    const pid_t pid = todo.back();
    todo.pop_back();
    tree.push_back(pid);
    for (pid_t child : children[pid]) todo.push_back(child);
  }
  return tree;
}

}  // namespace

double treeCpuSeconds(pid_t root) { return treeTimes(root).cpu; }

TreeTimes treeTimes(pid_t root) {
  std::map<pid_t, Stat> all;
  const std::vector<pid_t> tree = treeOf(root, all);
  TreeTimes times;
  if (tree.empty()) return times;
  double ticks = 0;
  for (const pid_t pid : tree) {
    ticks += all[pid].ticks;
    // schedstat: time on a CPU (ns), time runnable waiting for one (ns), timeslices run.
    std::ifstream in("/proc/" + std::to_string(pid) + "/schedstat");
    double on_cpu = 0, waiting = 0;
    if (!(in >> on_cpu >> waiting)) continue;
    times.waited = std::max(times.waited, waiting / 1e9);
    times.waited_total = std::max(times.waited_total, 0.0) + waiting / 1e9;
  }
  const long per_second = sysconf(_SC_CLK_TCK);
  times.cpu = ticks / double(per_second > 0 ? per_second : 100);
  return times;
}

}  // namespace clothref::grader
