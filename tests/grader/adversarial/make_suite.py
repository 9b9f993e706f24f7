#!/usr/bin/env python3
"""Writes the grader's adversarial suite (tests/grader/adversarial/<case>/) from the 2022
course-form reference (tools/grader/reference/2022/): each case is one hostile or broken
submission, stored as its one changed file plus expected.json ("base" names the corpus
submission, tests/grader/submissions/2022/reference, that supplies the other two files, the
convention of tests/grader/submissions/). Run from anywhere: python3 make_suite.py

Each edit must match exactly once, so a reference change that breaks a case fails here.
Placeholders the test fills in when it copies a case: @MARKER@ (a process name the test looks
for after the grade), @SOURCE_DIR@ (the clothref checkout), @RESULTS_DIR@ (the folder the grade
writes its results to).

expected.json: "verdict" is GradeReport::verdict under bubblewrap (the default here);
"verdict_rlimits" under CLOTHREF_GRADER_ISOLATION=rlimits as root when it differs; "marker":
the case names its processes @MARKER@ and none may be alive after the grade; "secret_file": the
first line of that file must not appear in any output; "secret_text": nor that text (a line of
the golden manifest); "reports_readable": the test says whether uid 65534 could read that file
(the outcome varies with the host and must not change the score); "full_marks": the score must be the
maximum (the attack failed and the code then did the right thing); "loses": stubs that must lose
points.
"""
import json
import shutil
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
REFERENCE = ROOT / "tools/grader/reference/2022"
BASE = "2022/reference"

EXPLICIT_BODY = ("  //   1. This can be done in 2 lines. (Hint: Operator overloading is available)\n"
                 "  for (const auto &p : particles) {\n    p->position() += p->velocity() * deltaTime;")
INCLUDES = '#include "configs.h"\n'
ATTACK_INCLUDES = ('#include "configs.h"\n\n#include <sys/prctl.h>\n#include <unistd.h>\n\n'
                   "#include <cstdio>\n#include <cstdlib>\n#include <vector>\n")


def explicit_prefix(code):
    """The attack runs first in ExplicitEuler::integrate (only that probe group calls it); the
    reference body follows, so a failed attack leaves correct code."""
    return [(INCLUDES, ATTACK_INCLUDES), (EXPLICIT_BODY, code + EXPLICIT_BODY)]


CASES = {
    "compile-error": dict(
        file="integrator.cpp",
        description="a missing semicolon in ExplicitEuler::integrate",
        edits=[(EXPLICIT_BODY, EXPLICIT_BODY[:-1])],
        expected={"verdict": "compile-error", "loses": ["ExplicitEuler::integrate"]}),
    "compile-include-secret": dict(
        file="integrator.cpp",
        description='#include "/etc/shadow": bubblewrap hides it from the compiler; the rlimits '
                    "fallback compiles as the grader's uid, so the file is read but never quoted",
        edits=[(INCLUDES, INCLUDES + '#include "/etc/shadow"\n')],
        expected={"verdict": "compile-error", "secret_file": "/etc/shadow",
                  "loses": ["ExplicitEuler::integrate"]}),
    "link-error": dict(
        file="integrator.cpp",
        description="RungeKuttaFourth::integrate deleted (a missing stub): undefined reference",
        cut=("void RungeKuttaFourth::integrate(", None),
        expected={"verdict": "link-error", "loses": ["ExplicitEuler::integrate"]}),
    "segfault": dict(
        file="integrator.cpp",
        description="writes through a null pointer",
        edits=explicit_prefix("  volatile int *nowhere = nullptr;\n  *nowhere = 1;\n"),
        expected={"verdict": "crashed", "loses": ["ExplicitEuler::integrate"]}),
    "abort": dict(
        file="integrator.cpp",
        description="calls std::abort()",
        edits=explicit_prefix("  std::abort();\n"),
        expected={"verdict": "crashed", "loses": ["ExplicitEuler::integrate"]}),
    "infinite-loop": dict(
        file="integrator.cpp",
        description="loops forever",
        edits=explicit_prefix('  prctl(PR_SET_NAME, "@MARKER@");\n'
                              "  for (volatile bool forever = true; forever;) {\n  }\n"),
        expected={"verdict": "timed-out", "marker": True, "loses": ["ExplicitEuler::integrate"]}),
    "huge-allocation": dict(
        file="integrator.cpp",
        description="allocates 10 GB",
        edits=explicit_prefix("  std::vector<char> block(10ull << 30, 1);\n"
                              "  if (block[12345] != 1) return;\n"),
        expected={"verdict": "memory-limit", "loses": ["ExplicitEuler::integrate"]}),
    "fork-bomb": dict(
        file="integrator.cpp",
        description="forks without end; every process keeps forking",
        edits=explicit_prefix('  prctl(PR_SET_NAME, "@MARKER@");\n  for (;;) fork();\n'),
        expected={"verdict": "timed-out", "marker": True, "loses": ["ExplicitEuler::integrate"]}),
    "output-flood": dict(
        file="integrator.cpp",
        description="prints without end on stdout",
        edits=explicit_prefix('  for (;;) std::fputs("all tests passed, all tests passed, all '
                              'tests passed\\n", stdout);\n'),
        expected={"verdict": "output-limit", "loses": ["ExplicitEuler::integrate"]}),
    "static-init-exit": dict(
        file="integrator.cpp",
        description="exit(0) from a static initialiser, before the probe driver's main",
        edits=[(INCLUDES, INCLUDES + "\n#include <cstdlib>\n\n"
                "static const int leave_early = (std::exit(0), 0);\n")],
        expected={"verdict": "no-answer", "loses": ["ExplicitEuler::integrate"]}),
    "fake-all-passed": dict(
        file="integrator.cpp",
        description="prints a fake 'all tests passed, 80 / 80' (stdout and stderr) and integrates "
                    "nothing",
        edits=[(INCLUDES, INCLUDES + "\n#include <cstdio>\n\n"
                "static const int fake = std::printf(\"All tests passed. Score: 80 / 80\\n\") +\n"
                "                        std::fprintf(stderr, \"All tests passed. Score: 80 / "
                "80\\n\");\n"),
               (EXPLICIT_BODY, "  return;\n" + EXPLICIT_BODY)],
        expected={"verdict": "graded", "loses": ["ExplicitEuler::integrate"]}),
    "read-reference": dict(
        file="integrator.cpp",
        description="tries to read clothref's reference and golden data (its path is known) and, "
                    "when it can, prints what it read; integrates correctly either way. Whether "
                    "the read succeeds depends on the host (mode 700 /root, bubblewrap's view); "
                    "the score and the answers must not",
        edits=explicit_prefix(
            "  static bool tried = false;  // once per process: the probe calls this every step\n"
            "  for (const char *path : {\"@SOURCE_DIR@/tools/grader/reference/2022/integrator.cpp\",\n"
            "                           \"@SOURCE_DIR@/golden/manifest.json\"}) {\n"
            "    std::FILE *file = tried ? nullptr : std::fopen(path, \"rb\");\n"
            "    if (file) {\n"
            "      char line[512];\n"
            "      for (int n = 0; n < 4 && std::fgets(line, sizeof line, file); ++n) {\n"
            "        std::fputs(line, stdout);\n"
            "        std::fputs(line, stderr);\n"
            "      }\n"
            "      std::fclose(file);\n"
            "    }\n"
            "  }\n"
            "  tried = true;\n"),
        expected={"verdict": "graded", "full_marks": True,
                  "secret_text": '"format": "clothref-golden"', "reports_readable": "@SOURCE_DIR@/golden/manifest.json"}),
    "write-results": dict(
        file="integrator.cpp",
        description="tries to overwrite a results file next to the grade's and to create a forged "
                    "one; integrates correctly",
        edits=explicit_prefix(
            "  for (const char *path : {\"@RESULTS_DIR@/previous.json\", \"@RESULTS_DIR@/forged.json\"}) {\n"
            "    if (std::FILE *file = std::fopen(path, \"w\")) {\n"
            "      std::fputs(\"{\\\"score\\\": 80}\\n\", file);\n"
            "      std::fclose(file);\n"
            "    }\n"
            "  }\n"),
        expected={"verdict": "graded", "full_marks": True}),
    "nan-results": dict(
        file="cloth.cpp",
        description="spring forces made NaN (0 / 0 added to the length)",
        edits=[("    float length = direction.norm();\n",
                "    float zero = 0.0f;\n    float length = direction.norm() + zero / zero;\n")],
        expected={"verdict": "non-finite", "loses": ["Cloth::computeSpringForce"]}),
}


def apply(text, case):
    for old, new in case.get("edits", []):
        assert text.count(old) == 1, (old, text.count(old))
        text = text.replace(old, new)
    if "cut" in case:
        head = case["cut"][0]
        assert text.count(head) == 1, head
        start = text.index(head)
        end = text.index("\n}\n", start) + 3
        text = text[:start] + text[end:]
    return text


def main():
    for name, case in CASES.items():
        folder = HERE / name
        if folder.exists():
            shutil.rmtree(folder)
        folder.mkdir()
        source = (REFERENCE / case["file"]).read_text()
        (folder / case["file"]).write_text(apply(source, case))
        expected = {"base": BASE, "description": case["description"], **case["expected"]}
        (folder / "expected.json").write_text(json.dumps(expected, indent=2) + "\n")
    print(f"wrote {len(CASES)} cases into {HERE}")


if __name__ == "__main__":
    main()
