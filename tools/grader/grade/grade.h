// Grading one submission end to end: find the files, detect the edition, build the probes,
// run every probe group (two at a time, each in its own child process), score with the rubric.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "grader/grade/results.h"
#include "grader/grade/rubric.h"
#include "grader/grade/run/build.h"
#include "grader/grade/run/child_process.h"

namespace clothref::grader {

struct GradeOptions {
  int edition = 0;                         // 2022 or 2024; 0 = detect from the files
  std::optional<std::string> rubric_path;  // JSON rubric overriding the course's weights
  CourseToolchain toolchain = defaultToolchain();
  ChildLimits limits;
  std::filesystem::path keep_work;  // copy the scratch folder here (debugging); empty = no
  bool whole_run = true;            // run the information-only whole-run check
  int probe_jobs = 2;               // probe groups at once
  std::uint64_t seed = 20221;
  std::size_t max_file_bytes = kDefaultMaxSourceBytes;  // a larger student file is refused
  // Folders this student's processes must not read besides ours (a batch names its folder and
  // every submission's): covered in a private mount namespace, else closed by their permissions.
  std::vector<std::filesystem::path> private_paths;
};

// The most a --keep-work copy holds (what a probe wrote past it is listed, not copied).
inline constexpr std::uint64_t kKeepWorkBytes = 1ull << 30;

// Throws InputError when the submission cannot be graded at all (not a directory, no student
// file found, our own reference does not build, student code could read a folder of ours).
GradeReport gradeSubmission(const std::filesystem::path& dir, const GradeOptions& options);

// The submission's verdict: the first of verdictTable() that happened, from the files that did
// not build, the probe runs' verdicts (ChildRun::verdict) and the tests' causes. GraderError (a
// probe the grader could not start) comes first: it is ours, and a batch re-grades it.
Verdict submissionVerdict(const GradeReport& report, const std::vector<Verdict>& run_verdicts);

}  // namespace clothref::grader
