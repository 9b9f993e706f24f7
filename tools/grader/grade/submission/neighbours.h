// The folders beside a submission that a single grade covers, as a batch covers the other
// submissions (issue 36).
#pragma once
#include <filesystem>
#include <vector>

namespace clothref::grader {

// The folders beside a single grade's submission that its student's processes must not read, as
// a batch covers the other submissions (docs/grading-reference.md, "Installing the grader where
// students' code runs"). Where folders can be covered (bubblewrap, a private mount namespace): the
// submission's parent, unless it is a system folder or holds TMPDIR, else the submission and
// every folder beside it. Where they cannot (their permissions must close them, or the grade is
// refused): the folders beside it that hold a student file (another submission); the
// submission itself is the student's own.
std::vector<std::filesystem::path> neighbours(const std::filesystem::path& dir, bool can_cover);

// Whether `path` is `root` or lies inside it, compared lexically after normalising both (no link
// followed): the test of which folder a cover hides.
bool isUnder(const std::filesystem::path& path, const std::filesystem::path& root);

}  // namespace clothref::grader
