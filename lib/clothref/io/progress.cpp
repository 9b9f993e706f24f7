#include "clothref/io/progress.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>
#include <unistd.h>

namespace clothref {

std::string formatDuration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  if (s < 60) return std::to_string(s) + "s";
  return fmt::format("{}m{:02}s", s / 60, s % 60);
}

ProgressStyle progressStyleForStderr(bool quiet) {
  if (quiet) return ProgressStyle::Silent;
  return ::isatty(STDERR_FILENO) ? ProgressStyle::Terminal : ProgressStyle::Lines;
}

Progress::Progress(std::string label, std::int64_t total, std::string unit, ProgressStyle style,
                   std::ostream& out, double delay_seconds)
    : label_(std::move(label)),
      total_(total),
      unit_(std::move(unit)),
      style_(total > 0 ? style : ProgressStyle::Silent),
      out_(out),
      start_(std::chrono::steady_clock::now()),
      delay_(delay_seconds) {}

Progress::~Progress() { finish(); }

std::string Progress::rateAndEta(std::int64_t done) const {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (done <= 0 || elapsed <= 0) return "ETA unknown";
  const double rate = static_cast<double>(done) / elapsed;
  return fmt::format("{:.0f} {}/s, ETA {}", rate, unit_,
                     formatDuration(static_cast<double>(total_ - std::min(done, total_)) / rate));
}

bool Progress::due() {
  if (delay_.count() <= 0) return true;
  if (std::chrono::steady_clock::now() - start_ < delay_) return false;
  delay_ = std::chrono::duration<double>(0);  // once due, stay due without reading the clock
  return true;
}

void Progress::update(std::int64_t done, const std::string& note) {
  note_ = note;
  update(done);
}

void Progress::update(std::int64_t done) {
  if (style_ == ProgressStyle::Silent || finished_) return;
  done = std::clamp<std::int64_t>(done, 0, total_);
  // integer arithmetic: 100 * done never overflows for the step counts the CLI accepts in time
  const int percent = static_cast<int>(done * 100 / total_);
  const int shown = style_ == ProgressStyle::Lines ? percent / 10 : percent;
  if (shown <= shown_ || !due()) return;
  shown_ = shown;
  if (style_ == ProgressStyle::Lines) {
    if (shown == 0) return;  // "0 %" says nothing in a log
    out_ << fmt::format("{}: {}% ({} of {} {}){}\n", label_, shown * 10, done, total_, unit_,
                        note_.empty() ? "" : ", " + note_);
  } else {
    // \x1b[K clears what a longer earlier line left behind
    out_ << fmt::format("\r{}: {}% ({} of {} {}){}\x1b[K", label_, percent, done, total_, unit_,
                        note_.empty() ? "" : ", " + note_);
    line_open_ = true;
  }
  out_.flush();
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (line_open_) {
    out_ << "\r\x1b[K";
    out_.flush();
  }
}

}  // namespace clothref
