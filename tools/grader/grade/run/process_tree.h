// The CPU time a process and everything it started have used, and how long they waited for a CPU,
// read from /proc: whether a run at the wall-clock limit computed all that time (an endless
// loop), slept, or was held back (runnable, but the machine's other work had the CPUs).
#pragma once
#include <sys/types.h>

namespace clothref::grader {

// User and system CPU time (s) of `root` and its living descendants, with what their reaped
// children used; threads count in their process. -1 when `root` cannot be read.
double treeCpuSeconds(pid_t root);

// treeCpuSeconds, and the longest time (s) any living process of the tree spent runnable but
// waiting for a CPU (/proc/<pid>/schedstat's run delay, of its main thread): what the machine's
// load, or the tree's other processes, took from it. -1 each when `root` cannot be read (the wait
// also when the kernel keeps no schedstat).
struct TreeTimes {
  double cpu = -1;
  double waited = -1;
  double waited_total = -1;  // summed over the tree's processes
};
TreeTimes treeTimes(pid_t root);

}  // namespace clothref::grader
