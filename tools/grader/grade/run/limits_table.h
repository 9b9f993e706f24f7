// The limits of every kind of run of student code, as one table (docs/reliability.md, "Limits of
// every run"), made from the constants and functions that set them, so the docs cannot drift:
// tests/grader/run/limits_table_test.cpp checks the docs' table against this one.
#pragma once
#include <string>
#include <vector>

namespace clothref::grader {

// One kind of run and its limits, as the docs show them (wall and CPU time, memory, processes,
// open files, files and disk).
struct RunLimitsRow {
  std::string run, wall, cpu, memory, processes, open_files, disk;
};

// The rows for a grade with `timeout` seconds per probe run (--timeout): a compile or link of a
// student file, the two runs of a probe, the sanitizer build and its run, the repair run (not
// yet), the whole run.
std::vector<RunLimitsRow> runLimitsTable(double timeout = 20);

// The same as a Markdown table (header, separator, one line per row).
std::string runLimitsMarkdown(double timeout = 20);

}  // namespace clothref::grader
