#include "grader/grade/run/limits_table.h"

#include <sstream>

#include "grader/grade/run/build.h"
#include "grader/grade/run/child_process.h"
#include "grader/grade/run/sanitize.h"
#include "grader/grade/run/tools.h"

namespace clothref::grader {

namespace {

std::string bytes(std::uint64_t value) {
  std::ostringstream out;
  if (value % (1ull << 30) == 0)
    out << (value >> 30) << " GiB";
  else if (value % (1ull << 20) == 0)
    out << (value >> 20) << " MiB";
  else
    out << value << " B";
  return out.str();
}

std::string seconds(double value) {
  std::ostringstream out;
  out << value << " s";
  return out.str();
}

// The memory cell of a probe-like run: its address space and its memory cgroup.
std::string memory(const ChildLimits& limits) {
  const bool unlimited = limits.address_space_bytes == ~std::uint64_t{0};
  return (unlimited ? std::string("no address-space limit")
                    : bytes(limits.address_space_bytes) + " address space") +
         "; " + bytes(limits.memory_bytes) + " memory cgroup";
}

RunLimitsRow probeRow(const std::string& run, const ChildLimits& limits) {
  return {run,
          seconds(limits.wall_seconds),
          seconds(double(limits.cpu_seconds)),
          memory(limits),
          std::to_string(limits.processes) + " (the probe uid)",
          std::to_string(limits.open_files),
          "folder " + bytes(kRunFolderBytes) + ", each other writable place " +
              bytes(kPrivateTmpBytes) + ", each file " + bytes(limits.file_size_bytes) + "; " +
              bytes(limits.disk_bytes) + " counted every " +
              std::to_string(int(kDiskCheckSeconds * 1000)) + " ms; removed when it ends"};
}

}  // namespace

std::vector<RunLimitsRow> runLimitsTable(double timeout) {
  const ChildLimits probe = limitsForTimeout(timeout);
  const double compile = CourseToolchain{}.compile_seconds;
  const RunLimitsRow tool = {"",
                             seconds(compile),
                             seconds(compile + 1),
                             bytes(kToolAddressSpace) + " address space",
                             std::to_string(kToolProcesses) + " (the tool uid)",
                             std::to_string(kToolOpenFiles),
                             "each file " + bytes(kToolFileSize) +
                                 "; what the tool uid leaves in shared folders removed when the "
                                 "grade ends"};
  RunLimitsRow compile_row = tool, sanitizer_build = tool;
  compile_row.run = "compile or link of a student file (each)";
  sanitizer_build.run = "sanitizer build (each compile or link)";
  ChildLimits sanitizer = sanitizerLimits(probe);
  RunLimitsRow sanitizer_row = probeRow("sanitizer run", sanitizer);
  sanitizer_row.memory += " (the probe's address space + 1/8 for ASan's shadow + " +
                          bytes(kSanitizerRuntimeBytes) + "); ASan's hard_rss_limit_mb the same";
  return {compile_row,
          probeRow("probe, first run", probe),
          probeRow("probe, second run", probe),
          sanitizer_build,
          sanitizer_row,
          {"repair run", "not yet (issue 38)", "", "", "", "", ""},
          probeRow("whole run (information only, once)", probe)};
}

std::string runLimitsMarkdown(double timeout) {
  std::string out =
      "| run | wall | CPU | memory | processes | open files | files and disk |\n"
      "|---|---|---|---|---|---|---|\n";
  for (const RunLimitsRow& row : runLimitsTable(timeout))
    out += "| " + row.run + " | " + row.wall + " | " + row.cpu + " | " + row.memory + " | " +
           row.processes + " | " + row.open_files + " | " + row.disk + " |\n";
  return out;
}

}  // namespace clothref::grader
