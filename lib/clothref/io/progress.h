// Progress of long work (a trace, a golden check) on stderr, one helper for every command:
//   Terminal  one line rewritten in place ("\r... 42% (4200 of 10000 steps)"), cleared at finish
//   Lines     a plain line per 10 % (logs, CI), nothing else
//   Silent    nothing (--quiet)
// Nothing is shown before `delay_seconds` have passed, so short runs stay quiet in every style.
#pragma once

#include <chrono>
#include <cstdint>
#include <ostream>
#include <string>

namespace clothref {

enum class ProgressStyle { Silent, Lines, Terminal };

// A duration as progress lines show it: "42s", "2m05s".
std::string formatDuration(double seconds);

// Terminal when standard error is a terminal, else Lines; Silent when `quiet`.
ProgressStyle progressStyleForStderr(bool quiet);

class Progress {
 public:
  // Reports `done` of `total` `unit`s (e.g. "steps") under `label` (e.g. "clothref trace") on
  // `out`. `total` <= 0 shows nothing.
  Progress(std::string label, std::int64_t total, std::string unit, ProgressStyle style,
           std::ostream& out, double delay_seconds = 1.0);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Cheap when nothing changes: writes only when the shown percentage (Terminal) or tenth (Lines)
  // moves. `done` is clamped to [0, total].
  void update(std::int64_t done);
  // The same, with `note` appended to the line ("..., 2 failed, ETA 1m05s").
  void update(std::int64_t done, const std::string& note);
  // The rate since construction and the time left at that rate, for a note: "2315 steps/s, ETA
  // 12s" (no ETA before the first unit is done).
  std::string rateAndEta(std::int64_t done) const;
  // Terminal: clears the line, so the command's summary takes its place. Called by the destructor.
  void finish();

 private:
  bool due();

  std::string label_;
  std::int64_t total_;
  std::string unit_;
  std::string note_;  // shown after the count when not empty
  ProgressStyle style_;
  std::ostream& out_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::duration<double> delay_;
  int shown_ = -1;          // last percentage (Terminal) or tenth (Lines) written
  bool line_open_ = false;  // Terminal: a line is on screen
  bool finished_ = false;
};

}  // namespace clothref
