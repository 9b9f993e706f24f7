// Building the probe executables of one submission: each student file is copied alone into a
// scratch folder (so no student header can be found) and compiled once against the edition's
// stand-in headers, precompiled once per edition, compiler and flags (built with clothref, or on
// first use in the object cache); cloth.cpp is compiled a second time with another
// particlesPerEdge for the springs probe. A file that does not compile (or is missing) is replaced
// by our course-form reference version, so the other files are still graded. The objects are linked
// with the probe driver and our framework definitions (built with clothref, one library per
// edition).
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "grader/grade/results.h"
#include "grader/grade/run/folders.h"
#include "grader/grade/run/sandbox.h"
#include "grader/grade/submission/submission.h"

namespace clothref::grader {

// Where the course side lives and how to compile student code.
struct CourseToolchain {
  std::string compiler = "g++";
  std::string optimisation = "-O2";
  std::filesystem::path course_dir;      // tools/grader/course (stand-in headers)
  std::filesystem::path reference_dir;   // tools/grader/reference (<edition>/<file>.cpp)
  std::filesystem::path driver_lib_dir;  // holds libclothref_grader_course_<edition>.a
  std::filesystem::path eigen_include;   // e.g. /usr/include/eigen3
  int jobs = 2;                          // compiles at once
  std::filesystem::path cache_dir;       // object cache keyed by source bytes + flags; empty = off
  // Read-only, built with clothref (clothref_grader_prebuild): the precompiled stand-in headers
  // and our reference objects for the default flags, found under the object cache's keys.
  std::filesystem::path prebuilt_dir;
  // Our own reference files only (prebuildCourse): objects keyed without the confinement.
  bool trusted_sources = false;
  double compile_seconds = 120;  // per compile
  Isolation isolation;  // Bubblewrap: compiles and links see only /usr and the paths they name
  // Where compiles of student code find the course (course_dir and driver_lib_dir point into it
  // then) and the precompiled headers: the kit's copies, never our folders. Null: ours directly.
  const CourseKit* kit = nullptr;
  // Diagnostic build (--sanitize): -fsanitize=address,undefined -g -Og -fno-omit-frame-pointer
  // instead of `optimisation`, linked by g++ with the same -fsanitize (which brings the runtimes;
  // the driver library itself is built without sanitizers).
  bool sanitize = false;
};

// The flags a sanitized build adds (compile and link).
inline constexpr const char* kSanitizeFlag = "-fsanitize=address,undefined";

// The built-in locations (set by CMake) with environment overrides CLOTHREF_GRADER_COURSE_DIR,
// CLOTHREF_GRADER_REFERENCE_DIR, CLOTHREF_GRADER_LIB_DIR and CLOTHREF_GRADER_PREBUILT_DIR.
CourseToolchain defaultToolchain();

// Our folders, which student code must never read: the tree the course folder lives in (the
// source checkout, or an install's share/clothref), the reference, the build, the prebuilt objects
// and the cache; outermost only, and never a system folder (/, /usr, /tmp, ...) even when an
// override points there.
std::vector<std::filesystem::path> ourFolders(const CourseToolchain& toolchain);

inline constexpr int kSecondParticlesPerEdge = 10;  // the springs probe's second cloth size

struct ProbeBuild {
  bool ok = false;  // false: nothing could be linked (report why in `problem`)
  std::string problem;
  std::filesystem::path probe;        // all three files, particlesPerEdge = 25
  std::filesystem::path probe_small;  // springs only, particlesPerEdge = kSecondParticlesPerEdge
  bool small_ok = false;
  std::string small_problem;  // why the second-size cloth.cpp did not build
  std::vector<UsedFile> files;
  // The objects `probe` was linked from, one per student file in studentFileNames() order: the
  // student's, or our reference's standing in for it (rebuildProbe reuses them).
  std::vector<std::filesystem::path> objects;
  double compile_seconds = 0, link_seconds = 0;
};

ProbeBuild buildProbes(const SubmissionFiles& files, int edition, const CourseToolchain& toolchain,
                       const std::filesystem::path& work_dir);

// A repair's probe (issue 38, grade/probes/repair.cpp): the student file `name` replaced by
// `bytes` (the quoted lines repaired in a private copy) and compiled alone as the student's files
// are, then linked with `base`'s objects of the other files: one compile and one link.
// `ok` false, with the compiler's (or linker's) first error in `problem`, when it does not build.
ProbeBuild rebuildWithFile(const ProbeBuild& base, const std::string& name,
                           const std::string& bytes, int edition, const CourseToolchain& toolchain,
                           const std::filesystem::path& work_dir);

// Probes built again from one grade's build (`base`, made by buildProbes in another folder) with
// some files compiled with `toolchain`'s flags (the sanitizer's, docs/grading-reference.md
// "Diagnosing crashes") and every other file's object taken from `base` as it is: one file
// rebuilt costs one compile (against the precompiled header of those flags, from the cache when
// another grade compiled the same bytes) and a link. A file of `base` that is our reference (the
// student's was missing or did not build) is rebuilt from our reference (prebuilt with clothref
// when it matches). Each set is built in a new folder of its own (`folder(name)`, the tool uid's):
// its student compiles run before any object or probe of ours is there, as in buildProbes. Each
// file is compiled at most once per rebuilder, whatever sets ask for it; the rebuilt objects come
// first in the link, so the inline functions and templates they share with the others are
// theirs. Thread-safe.
class ProbeRebuilder {
 public:
  using Folder = std::function<std::filesystem::path(const std::string& name)>;
  ProbeRebuilder(const ProbeBuild& base, const SubmissionFiles& files, int edition,
                 const CourseToolchain& toolchain, Folder folder);
  // The probe with the student files `rebuilt` (names of studentFileNames()) compiled again,
  // linked in that set's folder; empty when a compile or the link failed.
  std::filesystem::path probe(const std::vector<std::string>& rebuilt);
  // The student files compiled again so far (and built), in studentFileNames() order.
  std::vector<std::string> rebuiltFiles();

 private:
  const ProbeBuild& base_;
  const SubmissionFiles& files_;
  int edition_;
  CourseToolchain toolchain_;
  Folder folder_;
  std::mutex mutex_;
  std::map<std::string, std::filesystem::path> objects_;  // by file; empty: it failed
  std::map<std::string, std::filesystem::path> probes_;   // by the rebuilt set; empty: failed
};

// Fills `out_dir` (a `prebuilt_dir`) with what grading needs whatever the submission: per edition
// the precompiled stand-in headers and our three reference objects, for the default flags and for
// the sanitizer's (its diagnostic build), and the sanitizer's defaults object; removes what it
// holds for other headers or flags. Run with clothref's build; false (and why) when something
// fails.
bool prebuildCourse(const CourseToolchain& toolchain, const std::vector<int>& editions,
                    const std::filesystem::path& out_dir, const std::filesystem::path& work_dir,
                    std::string* problem);

// The object cache's file for compile `command` of `source`: keyed by the source's bytes, the
// flags, the stand-in headers, the compiler's `--version` and the isolation the compile ran in
// (an unconfined object may hold host bytes read with `.incbin`). `work_dir` is where the
// version query runs.
std::filesystem::path objectCachePath(const CourseToolchain& toolchain,
                                      const std::vector<std::string>& command,
                                      const std::filesystem::path& source,
                                      const std::filesystem::path& work_dir);

}  // namespace clothref::grader
