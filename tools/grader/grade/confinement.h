// What a grade's student code may reach: the uids and the folders of ours it must never read
// (isolationFor), and the refusal to grade where it could read one anyway (checkConfinement).
#pragma once
#include <filesystem>
#include <vector>

#include "grader/grade/run/build.h"
#include "grader/grade/run/folders.h"
#include "grader/grade/run/sandbox.h"

namespace clothref::grader {

// This grade's own uids (leased host-wide when root), and the folders of ours its student's
// processes must never read: the grader's (sources, build, install data, reference, cache), the
// `private_paths` the caller names (other submissions, the batch folder) and the neighbours of
// `submission` (another submission beside it).
Isolation isolationFor(const CourseToolchain& toolchain,
                       const std::vector<std::filesystem::path>& private_paths,
                       const std::filesystem::path& submission);

// Refuses to grade (InputError, one line) where student code could read a folder of ours: the
// scratch folder or the course kit inside one (TMPDIR in our tree), a student uid that cannot
// reach its own folder (TMPDIR inside a closed folder), or, without bubblewrap and without a
// private mount namespace to cover them, a folder of ours that a student uid can reach by its
// permissions (docs/grading-reference.md, "Installing the grader where students' code runs").
void checkConfinement(const Isolation& isolation, const GradeScratch& scratch,
                      const CourseKit* kit);

}  // namespace clothref::grader
