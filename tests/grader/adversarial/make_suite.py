#!/usr/bin/env python3
"""Writes the grader's adversarial suite (tests/grader/adversarial/<case>/) from the 2022
course-form reference (tools/grader/reference/2022/): each case is one hostile or broken
submission, stored as its one changed file plus expected.json ("base" names the corpus
submission, tests/grader/submissions/2022/reference, that supplies the other two files, the
convention of tests/grader/submissions/). Run from anywhere: python3 make_suite.py

Each edit must match exactly once, so a reference change that breaks a case fails here.
Placeholders the test fills in when it copies a case: @MARKER@ (a process name the test looks
for after the grade, and the name of the files a case leaves in the shared temporary folders),
@SOURCE_DIR@ (the clothref checkout), @RESULTS_DIR@ (the folder the grade writes its results to),
@SECRET_FILE@ (a file only root may read, made by the test). A case may replace more than its one
file ("files": name -> whole text).

expected.json: "verdict" is GradeReport::verdict under bubblewrap (the default here);
"verdict_rlimits" under CLOTHREF_GRADER_ISOLATION=rlimits as root when it differs; "marker":
the case names its processes @MARKER@ and none may be alive after the grade; "secret_file": the
first line of that file must not appear in any output; "secret_text": nor that text (a line of
the golden manifest, or of our reference); "keep_work": the grade keeps its scratch folder, in
which that text must not appear either (and which stays small: links are not followed);
"no_files_left": nothing named @MARKER@* is left in /tmp, /var/tmp or /dev/shm; "score": the
score must be exactly this; "reports_readable": the test says whether uid 65534 could read that file
(the outcome varies with the host and must not change the score); "full_marks": the score must be the
maximum (the attack failed and the code then did the right thing); "loses": stubs that must lose
points; "quoted": text results.json must quote (the student's own compile error); "timeout": the
grade's --timeout in seconds (default: 3 for a case that ends by time, else 30).
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
    # The reference is one #include away (issue 30): each file is only an #include of ours.
    "include-reference": dict(
        file="cloth.cpp",
        description="each of the three files is only an #include of our reference file of the "
                    "same name (the path is documented): the compiles see no folder of ours, so "
                    "each include finds nothing and the grade is that of three empty files",
        whole='#include "@SOURCE_DIR@/tools/grader/reference/2022/cloth.cpp"\n',
        files={name: '#include "@SOURCE_DIR@/tools/grader/reference/2022/%s"\n' % name
               for name in ("sphere.cpp", "integrator.cpp")},
        expected={"verdict": "compile-error", "score": 0,
                  "secret_text": "clothref's reference solution for the 2022 edition",
                  "loses": ["Cloth::computeSpringForce", "Spheres::collide(Cloth*)",
                            "RungeKuttaFourth::integrate"]}),
    "include-reference-relative": dict(
        file="cloth.cpp",
        description="the reference included by a relative spelling that climbs out of the "
                    "scratch folder (../ repeated, then the absolute path)",
        whole='#include "' + "../" * 24 + '@SOURCE_DIR@/tools/grader/reference/2022/cloth.cpp"\n',
        expected={"verdict": "compile-error",
                  "secret_text": "clothref's reference solution for the 2022 edition",
                  "loses": ["Cloth::initializeSpring", "Cloth::computeSpringForce"]}),
    "incbin-reference": dict(
        file="sphere.cpp",
        description="the reference's bytes pulled in with .incbin and printed (then abort, so "
                    "stderr is quoted) by a static initialiser",
        edits=[('#include "sphere.h"\n', '#include "sphere.h"\n\n#include <cstdio>\n#include <cstdlib>\n'
                'extern "C" const char stolen_reference[];\n'
                'asm(".section .rodata\\nstolen_reference:\\n.incbin '
                '\\"@SOURCE_DIR@/tools/grader/reference/2022/sphere.cpp\\"\\n.byte 0\\n.previous");\n'
                'static const int leak = (std::fputs(stolen_reference, stderr), std::abort(), 0);\n')],
        expected={"verdict": "compile-error",
                  "secret_text": "clothref's reference solution for the 2022 edition",
                  "loses": ["Spheres::collide(Cloth*)", "Spheres::collide()"]}),
    "formula-symbol": dict(
        file="cloth.cpp",
        description="computeSpringForce calls the course-form spring force the probe driver has "
                    "inside (declared by hand, not defined): our symbols are local to the driver, "
                    "so it does not link",
        edits=[('#include "sphere.h"\n', '#include "sphere.h"\n\nnamespace clothref::formula {\n'
                'template <typename T>\nvoid springForce(const T* x_start, const T* x_end, const T* '
                'v_start, const T* v_end, T rest, T k_spring, T k_damper, T* force);\n}\n'),
               ("    Eigen::Vector4f force =\n        direction * (damperCoef * relativeVelocity.dot("
                "direction) + springCoef * (length - spring.length()));\n",
                "    Eigen::Vector4f force;\n    clothref::formula::springForce<float>(\n"
                "        _particles.position(start).data(), _particles.position(end).data(),\n"
                "        _particles.velocity(start).data(), _particles.velocity(end).data(), "
                "spring.length(),\n        springCoef, damperCoef, force.data());\n")],
        expected={"verdict": "link-error", "loses": ["Cloth::computeSpringForce"]}),
    "disk-filler": dict(
        file="integrator.cpp",
        description="writes 8 MiB files without end into its folder and every world-writable folder "
                    "(/tmp, /var/tmp, /dev/shm, /run/lock): each is a bounded filesystem of its "
                    "own (the writes fail once it is full, so the loop runs into the time limit), "
                    "nothing left behind",
        edits=explicit_prefix(
            "  std::vector<char> block(8 << 20, 'x');\n"
            "  for (unsigned k = 0;; ++k)\n"
            "    for (const char *where : {\".\", \"/tmp\", \"/var/tmp\", \"/dev/shm\", \"/run/lock\"}) {\n"
            "      char name[256];\n"
            "      std::snprintf(name, sizeof name, \"%s/@MARKER@-%u\", where, k);\n"
            "      if (std::FILE *file = std::fopen(name, \"wb\")) {\n"
            "        std::fwrite(block.data(), 1, block.size(), file);\n"
            "        std::fclose(file);\n"
            "      }\n"
            "    }\n"),
        expected={"verdict": "timed-out", "no_files_left": True,
                  "loses": ["ExplicitEuler::integrate"]}),
    # Fourth round (issue 36).
    "disk-burst": dict(
        file="integrator.cpp",
        description="holds 5 x 30 MiB in its folder at once (each file under the file-size "
                    "limit), allocated in one burst (fallocate: faster than any poll): a bounded "
                    "filesystem refuses the part past the limit at write time; had it held more "
                    "than 128 MiB, it would abort. It then removes its files and integrates "
                    "correctly",
        edits=[(INCLUDES, ATTACK_INCLUDES + "#include <fcntl.h>\n#include <sys/stat.h>\n"),
               (EXPLICIT_BODY,
                "  static bool tried = false;  // once per process: the probe calls this every step\n"
                "  if (!tried) {\n"
                "    tried = true;\n"
                "    long long held = 0;\n"
                "    for (int k = 0; k < 5; ++k) {\n"
                "      char name[64];\n"
                "      std::snprintf(name, sizeof name, \"@MARKER@-%d\", k);\n"
                "      const int fd = open(name, O_WRONLY | O_CREAT | O_TRUNC, 0600);\n"
                "      if (fd < 0) continue;\n"
                "      (void)posix_fallocate(fd, 0, 30ll << 20);\n"
                "      struct stat info {};\n"
                "      if (fstat(fd, &info) == 0) held += static_cast<long long>(info.st_blocks) * 512;\n"
                "      close(fd);\n"
                "    }\n"
                "    if (held > (128ll << 20)) std::abort();\n"
                "    for (int k = 0; k < 5; ++k) {\n"
                "      char name[64];\n"
                "      std::snprintf(name, sizeof name, \"@MARKER@-%d\", k);\n"
                "      unlink(name);\n"
                "    }\n"
                "  }\n" + EXPLICIT_BODY)],
        expected={"verdict": "graded", "full_marks": True}),
    "line-rename": dict(
        file="integrator.cpp",
        description="a #line directive renames the file to 5000 newlines then 'cloth.cpp' above a "
                    "real error (a missing semicolon): the log looks empty for its first 5000 "
                    "lines, and is still the student's compile error, quoted",
        edits=[(INCLUDES, INCLUDES + '#line 1 "' + "\\n" * 5000 + 'cloth.cpp"\n'),
               (EXPLICIT_BODY, EXPLICIT_BODY[:-1])],
        expected={"verdict": "compile-error", "quoted": "error: expected ';'",
                  "loses": ["ExplicitEuler::integrate"]}),
    "sanitizer-fork-bomb": dict(
        file="integrator.cpp",
        description="crashes at -O2 (null pointer) and, rebuilt with the sanitizers, forks without "
                    "end: the sanitizer run holds the uid's process slots for its whole time "
                    "limit, which the other probes of the grade wait out instead of failing as "
                    "the grader's error",
        edits=explicit_prefix("#if defined(__SANITIZE_ADDRESS__)\n"
                              '  prctl(PR_SET_NAME, "@MARKER@");\n'
                              "  for (;;) fork();\n"
                              "#else\n"
                              "  volatile int *nowhere = nullptr;\n"
                              "  *nowhere = 1;\n"
                              "#endif\n"),
        expected={"verdict": "crashed", "marker": True, "timeout": 3,
                  "loses": ["ExplicitEuler::integrate"]}),
    "link-out": dict(
        file="integrator.cpp",
        description="links a root-only host file and a large host folder into its own folder, for "
                    "the grader to copy (--keep-work) as root; integrates correctly",
        edits=[(INCLUDES, ATTACK_INCLUDES),
               (EXPLICIT_BODY, '  static const bool planted = (symlink("@SECRET_FILE@", "leak") + '
                'symlink("/usr", "usr") + symlink("/nonexistent", "dangling"), true);\n'
                "  (void)planted;\n" + EXPLICIT_BODY)],
        expected={"verdict": "graded", "full_marks": True, "keep_work": True,
                  "secret_file": "@SECRET_FILE@"}),
    "nan-results": dict(
        file="cloth.cpp",
        description="spring forces made NaN (0 / 0 added to the length)",
        edits=[("    float length = direction.norm();\n",
                "    float zero = 0.0f;\n    float length = direction.norm() + zero / zero;\n")],
        expected={"verdict": "non-finite", "loses": ["Cloth::computeSpringForce"]}),
    # Undefined behaviour that neither crashes nor varies by itself (issue 38): both runs of a
    # probe read the same stack, unless the driver fills it differently before each run.
    "uninitialised-sum": dict(
        file="cloth.cpp",
        description="the spring force summed into an uninitialised Eigen::Vector4f (Hooke, then "
                    "the damper): it starts from whatever the stack held",
        edits=[("    Eigen::Vector4f force =\n        direction * (damperCoef * relativeVelocity.dot("
                "direction) + springCoef * (length - spring.length()));\n",
                "    Eigen::Vector4f force;  // spring + damper\n"
                "    force += direction * (springCoef * (length - spring.length()));\n"
                "    force += direction * (damperCoef * relativeVelocity.dot(direction));\n")],
        expected={"verdict": "results-vary", "loses": ["Cloth::computeSpringForce"]}),
}


def apply(text, case):
    if "whole" in case:
        return case["whole"]
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


HEADER = "// clothref's reference solution for the 2022 edition"


def without_header(text, name):
    """A case carries no line of our reference's header comment, so a test can look for that
    line in the outputs (a reference file read by the attack) without finding the case's own."""
    lines = text.split("\n")
    assert lines[0].startswith(HEADER), lines[0]
    rest = 1
    while lines[rest].startswith("//"):
        rest += 1
    return "// adversarial case %s (tests/grader/adversarial/make_suite.py)\n" % name + \
        "\n".join(lines[rest:])


def main():
    for name, case in CASES.items():
        folder = HERE / name
        if folder.exists():
            shutil.rmtree(folder)
        folder.mkdir()
        source = without_header((REFERENCE / case["file"]).read_text(), name)
        (folder / case["file"]).write_text(apply(source, case))
        for name, text in case.get("files", {}).items():
            (folder / name).write_text(text)
        expected = {"base": BASE, "description": case["description"], **case["expected"]}
        (folder / "expected.json").write_text(json.dumps(expected, indent=2) + "\n")
    print(f"wrote {len(CASES)} cases into {HERE}")


if __name__ == "__main__":
    main()
