#!/usr/bin/env bash
# Checks (or with --fix, applies) clang-format on the project's own C++ files. Left out: files
# written to look like the course's (the grader's course stand-in, its course-form reference and
# the student-style submissions under test), which keep the course's layout on purpose.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h' |
  grep -v -e '^tools/grader/course/' -e '^tools/grader/reference/' -e '^tests/grader/submissions/' \
    -e '^tests/grader/adversarial/' -e '^tests/grader/corpus/' -e '^tests/grader/handwritten/' \
    -e '^tests/grader/blind/' -e '^tests/grader/blind2/' -e '^tests/grader/blind3/' -e '^tests/grader/blind4/')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
else
  clang-format --dry-run -Werror "${files[@]}"
fi
