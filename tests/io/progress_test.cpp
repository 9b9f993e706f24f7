// Progress lines on stderr: a line per 10 % in logs, one rewritten line on a terminal, silence
// when asked or before the delay.
#include "clothref/io/progress.h"

#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace clothref {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(Progress, LinesStyleWritesOneLinePerTenthAndNothingElse) {
  std::ostringstream out;
  {
    Progress progress("clothref trace", 1000, "steps", ProgressStyle::Lines, out, 0);
    for (int done = 0; done <= 1000; ++done) progress.update(done);
  }
  const std::vector<std::string> written = lines(out.str());
  ASSERT_EQ(written.size(), 10u) << out.str();
  EXPECT_EQ(written.front(), "clothref trace: 10% (100 of 1000 steps)");
  EXPECT_EQ(written[4], "clothref trace: 50% (500 of 1000 steps)");
  EXPECT_EQ(written.back(), "clothref trace: 100% (1000 of 1000 steps)");
  EXPECT_EQ(out.str().find('\r'), std::string::npos);
}

TEST(Progress, LinesStyleSkipsTenthsItJumpsOverAndNeverGoesBack) {
  std::ostringstream out;
  Progress progress("golden", 10, "entries", ProgressStyle::Lines, out, 0);
  progress.update(7);
  progress.update(3);   // backwards: nothing
  progress.update(99);  // clamped to the total
  EXPECT_EQ(out.str(), "golden: 70% (7 of 10 entries)\ngolden: 100% (10 of 10 entries)\n");
}

TEST(Progress, TerminalStyleRewritesOneLineAndClearsItAtFinish) {
  std::ostringstream out;
  Progress progress("clothref trace", 200, "steps", ProgressStyle::Terminal, out, 0);
  progress.update(1);  // 0 %: still shown on a terminal, so the user sees the run started
  progress.update(2);  // 1 %
  progress.update(3);  // still 1 %: nothing
  progress.finish();
  progress.update(200);  // after finish: nothing
  EXPECT_EQ(out.str(),
            "\rclothref trace: 0% (1 of 200 steps)\x1b[K"
            "\rclothref trace: 1% (2 of 200 steps)\x1b[K"
            "\r\x1b[K");
}

TEST(Progress, SilentStyleZeroTotalAndTheDelayWriteNothing) {
  std::ostringstream silent, empty, early;
  {
    Progress quiet("a", 10, "steps", ProgressStyle::Silent, silent, 0);
    Progress nothing("b", 0, "steps", ProgressStyle::Terminal, empty, 0);
    Progress delayed("c", 10, "steps", ProgressStyle::Terminal, early, 3600);
    for (int done = 0; done <= 10; ++done) {
      quiet.update(done);
      nothing.update(done);
      delayed.update(done);
    }
  }
  EXPECT_EQ(silent.str(), "");
  EXPECT_EQ(empty.str(), "");
  EXPECT_EQ(early.str(), "");
}

TEST(Progress, NoteFollowsTheCountAndTheLatestNoteIsShown) {
  std::ostringstream out;
  {
    Progress progress("clothref grade", 2, "submissions", ProgressStyle::Lines, out, 0);
    progress.update(1, "0 failed, ETA 5s");
    progress.update(2, "1 failed, ETA 0s");
  }
  EXPECT_EQ(out.str(),
            "clothref grade: 50% (1 of 2 submissions), 0 failed, ETA 5s\n"
            "clothref grade: 100% (2 of 2 submissions), 1 failed, ETA 0s\n");
}

TEST(Progress, QuietAlwaysSilent) {
  EXPECT_EQ(progressStyleForStderr(true), ProgressStyle::Silent);
  EXPECT_NE(progressStyleForStderr(false), ProgressStyle::Silent);
}

TEST(Progress, DurationsAndRateWithEta) {
  EXPECT_EQ(formatDuration(0), "0s");
  EXPECT_EQ(formatDuration(59.4), "59s");
  EXPECT_EQ(formatDuration(125), "2m05s");
  EXPECT_EQ(formatDuration(-3), "0s");
  std::ostringstream out;
  Progress progress("clothref trace", 1000, "steps", ProgressStyle::Lines, out, 0);
  EXPECT_EQ(progress.rateAndEta(0), "ETA unknown");
  const std::string note = progress.rateAndEta(500);
  EXPECT_NE(note.find(" steps/s, ETA "), std::string::npos) << note;
  EXPECT_EQ(note.back(), 's') << note;
}

}  // namespace
}  // namespace clothref
