// The CPU time a process and everything it started have used, read from /proc: whether a run
// stopped at the wall-clock limit computed all that time (an endless loop) or waited (for a CPU
// on a loaded machine, or in a sleep).
#pragma once
#include <sys/types.h>

namespace clothref::grader {

// User and system CPU time (s) of `root` and its living descendants, with what their reaped
// children used; threads count in their process. -1 when `root` cannot be read.
double treeCpuSeconds(pid_t root);

}  // namespace clothref::grader
