#!/usr/bin/env bash
# ctest `gradescope` (label gradescope): the autograder archive run the way Gradescope runs it.
# `clothref gradescope` writes the archive; it is unpacked into /autograder/source of a minimal
# Debian 12 root (mmdebstrap, tools/debian_root.sh) with run_autograder copied to /autograder, as
# Gradescope lays it out; setup.sh runs there once (it installs the packages and builds); then
# run_autograder grades eight submissions, and each results.json is checked against Gradescope's
# documented fields and the expected score: among them three that go for our reference by its
# documented path (each file an #include of ours, an .incbin of ours, a run-time read), which
# must get nothing of it: no line of the reference in any output, the score of the same stubs
# without the attack. No bubblewrap in the root: the grader runs in its
# rlimits fallback, as it does on Gradescope. Prints the time of setup.sh and of each grade.
#
# Usage: gradescope_test.sh CLOTHREF_BINARY SOURCE_DIR (works in a new folder under ${TMPDIR:-/tmp})
# Exit: 0 passed, 1 failed, 77 skipped (this host cannot make the root; the reason is printed).
set -uo pipefail
clothref=$1 source_dir=$2
# shellcheck source=tools/debian_root.sh
. "$source_dir/tools/debian_root.sh"
say() { echo "gradescope_test: $*"; }

if ! why=$(debian_root_usable); then say "SKIPPED: $why"; exit 77; fi
work=$(mktemp -d "${TMPDIR:-/tmp}/clothref-gradescope.XXXXXX") || exit 1
root="$work/root"
# shellcheck disable=SC2317  # reached through the trap
finish() {
  local status=$?
  trap - EXIT
  debian_root_release "$root" "$work" || status=1
  exit "$status"
}
trap finish EXIT
trap 'exit 130' INT TERM

"$clothref" gradescope -o "$work/autograder.zip" --timeout 5 || { say "FAILED: no archive"; exit 1; }
start=$(date +%s)
if ! debian_root_make "$root" "$work/mmdebstrap.log"; then
  tail -n 5 "$work/mmdebstrap.log"
  say "SKIPPED: mmdebstrap could not make a Debian 12 root here (no package source?)"
  exit 77
fi
say "Debian 12 root in $(($(date +%s) - start)) s"

# The archive's checks, the submissions and the results are read with the host's python3.
python3 - "$work/autograder.zip" "$root/autograder/source" <<'EOF' || exit 1
import os, sys, zipfile
archive, target = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(archive) as z:
    names = z.namelist()
    for required in ("setup.sh", "run_autograder", "clothref/CMakeLists.txt", "clothref/REVISION"):
        assert required in names, f"{required} missing from the archive"
    assert not any(n.startswith(("clothref/build/", "clothref/.git/")) for n in names), "build or .git"
    for info in z.infolist():
        path = z.extract(info, target)
        mode = (info.external_attr >> 16) & 0o777
        if mode:
            os.chmod(path, mode)
print(f"archive: {len(names)} files")
EOF
cp "$root/autograder/source/run_autograder" "$root/autograder/run_autograder"
debian_root_mount "$root" || { say "FAILED: could not bind /proc, /sys, /dev"; exit 1; }

begin=$(date +%s)
if ! debian_root_run "$root" "bash /autograder/source/setup.sh" >"$work/setup.log" 2>&1; then
  tail -n 30 "$work/setup.log"
  say "FAILED: setup.sh"
  exit 1
fi
say "setup.sh: $(($(date +%s) - begin)) s ($(tail -n 1 "$work/setup.log"))"

# The five submissions: name, then the files laid over the corpus reference.
corpus="$source_dir/tests/grader/submissions/2022"
adversarial="$source_dir/tests/grader/adversarial"
make_submission() {
  local name=$1 dir="$work/submissions/$1"
  mkdir -p "$dir"
  cp "$corpus/reference/src/"*.cpp "$dir/"
  # the corpus reference is a copy of ours: its header line is what a leak would show
  sed -i "s/clothref's reference solution/a student's solution/" "$dir/"*.cpp
  case "$name" in
    wrong) cp "$corpus/force-hooke-sign/cloth.cpp" "$dir/" ;;
    compile-error) cp "$adversarial/compile-error/integrator.cpp" "$dir/" ;;
    loops) sed 's/@MARKER@/gs-loop/g' "$adversarial/infinite-loop/integrator.cpp" >"$dir/integrator.cpp" ;;
    include-reference)
      for file in cloth sphere integrator; do
        sed "s#@SOURCE_DIR@#/autograder/source/clothref#g" \
          "$adversarial/include-reference/$file.cpp" >"$dir/$file.cpp"
      done ;;
    incbin-reference)
      sed "s#@SOURCE_DIR@#/autograder/source/clothref#g" \
        "$adversarial/incbin-reference/sphere.cpp" >"$dir/sphere.cpp" ;;
    read-reference)  # prints what it read, then crashes so that the stderr is quoted
      sed -e "s#@SOURCE_DIR@#/autograder/source/clothref#g" \
          -e 's#std::fclose(file);#std::fclose(file);\n      std::abort();#' \
        "$adversarial/read-reference/integrator.cpp" >"$dir/integrator.cpp" ;;
    big5)  # comments in Big5, as many of the course's students write them
      python3 - "$dir" <<'EOF'
import pathlib, sys
for path in pathlib.Path(sys.argv[1]).glob("*.cpp"):
    comment = "// 計算彈簧力與碰撞 (作業二)\n".encode("big5")
    path.write_bytes(comment + path.read_bytes().replace(b"\n}\n", b"\n}  " + comment, 1))
EOF
      ;;
  esac
}

status=0
# name, expected: "full" (every point) or "loses:STUB" (that stub below its maximum), verdict
for spec in "reference full graded" "wrong loses:Cloth::computeSpringForce graded" \
            "big5 full graded" "compile-error loses:ExplicitEuler::integrate compile-error" \
            "loops loses:ExplicitEuler::integrate timed-out" "include-reference zero compile-error" \
            "incbin-reference loses:Spheres::collide(Cloth*) compile-error" \
            "read-reference full graded"; do
  read -r name expect verdict <<<"$spec"
  make_submission "$name"
  rm -rf "$root/autograder/submission" "$root/autograder/results"
  cp -r "$work/submissions/$name" "$root/autograder/submission"
  begin=$EPOCHREALTIME
  debian_root_run "$root" "/autograder/run_autograder" >"$work/$name.log" 2>&1
  code=$?
  seconds=$(python3 -c "print(round($EPOCHREALTIME - $begin, 2))")
  if ! python3 - "$root/autograder/results/results.json" "$expect" "$verdict" "$name" "$seconds" <<'EOF'
import json, sys
path, expect, verdict, name, seconds = sys.argv[1:]
raw = open(path, "rb").read()
raw.decode("utf-8")  # Gradescope reads UTF-8
results = json.loads(raw)
assert isinstance(results.get("score"), (int, float)), "score is not a number"
tests = results.get("tests")
assert isinstance(tests, list) and tests, "no tests"
formats = {"text", "html", "simple_format", "md", "ansi"}
for test in tests:
    for key in ("name", "score", "max_score", "output", "visibility"):
        assert key in test, f"a test without {key}: {test.get('name')}"
    assert isinstance(test["score"], (int, float)) and isinstance(test["max_score"], (int, float))
    assert test["visibility"] in {"hidden", "after_due_date", "after_published", "visible"}
    assert test.get("output_format", "text") in formats, test.get("output_format")
# Gradescope shows `score` against the sum of the tests' max_score: they must agree to the
# rounding of the per-test figures, and with the grader's own maximum.
total = sum(results["extra_data"]["stub_max"].values())
assert abs(sum(t["max_score"] for t in tests) - total) < 0.01, "tests' max_score do not sum up"
got = results["extra_data"]["verdict"]
isolation = results["extra_data"]["isolation"]
assert got == verdict, f"verdict {got}, expected {verdict}"
assert not isolation.startswith("bubblewrap"), isolation
if expect == "full":
    assert abs(results["score"] - total) < 1e-9, f"score {results['score']} of {total}"
elif expect == "zero":
    assert results["score"] == 0, f"score {results['score']}, expected 0"
else:
    stub = expect.split(":", 1)[1]
    mine = [t for t in tests if t["name"].startswith(stub)]
    assert mine, f"no test named {stub}"
    assert sum(t["score"] for t in mine) < sum(t["max_score"] for t in mine), f"{stub} full marks"
# No line of our reference reaches the student, whatever the attack (its header line is ours alone:
# the submissions here replace it).
assert "clothref's reference solution" not in raw.decode("utf-8"), "a reference line was quoted"
print(f"{name}: {results['score']:g} / {total:g}, verdict {got}, {seconds} s, isolation: {isolation}")
EOF
  then
    say "FAILED: $name (run_autograder exit $code)"
    tail -n 20 "$work/$name.log"
    # what the grader itself said (run_autograder keeps it beside the results)
    head -c 3000 "$root/autograder/results/grader-stderr.txt" 2>/dev/null
    status=1
  fi
done
exit "$status"
