#!/usr/bin/env bash
# The grader's outputs before and after a refactor: grades the labelled sets (tests/grader/corpus,
# tests/grader/handwritten) and the mutants of tests/grader/submissions (each laid over its base,
# as grade_test does) as ONE batch (without the whole run: information only, never scored, and
# the slowest part), then copies every output with what varies from run to run
# normalised: seconds and timings, the scratch and batch paths, and the addresses in a
# sanitizer's report. Two such folders of one grader must be byte-identical (`diff -r`).
#
#   tests/grader/batch_identity.sh grade CLOTHREF OUT   grade with a copy of the CLOTHREF binary
#                                          (OUT/clothref: a rebuild during the batch cannot change
#                                          it) into OUT/batch, normalised copy in OUT/normalised
#   tests/grader/batch_identity.sh compare A B       diff -r A/normalised B/normalised (exit 1
#                                                    when they differ)
#
# OUT must be outside the repository (e.g. /tmp/house-before); --jobs 2. BATCH_IDENTITY_CACHE:
# a compile cache the runs share (the student objects do not depend on the grader's code). Used
# for the refactors of issue 37 (docs/grading.md, "Adding a probe"): "byte-identical" in a
# commit message means `compare` printed nothing.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

usage() {
  echo "usage: $0 grade CLOTHREF OUT | compare A B" >&2
  exit 2
}

normalise() {
  local batch=$1 out=$2
  rm -rf "$out"
  mkdir -p "$out"
  (cd "$batch" && find . -type f ! -name '*.tmp*' -print0) | while IFS= read -r -d '' f; do
    mkdir -p "$out/$(dirname "$f")"
    # seconds: "seconds":{...} objects, execution_time, the CSV's last column, the page's "s"
    # cells; the batch's own path; 0x... addresses and pids of sanitizer reports.
    sed -E \
      -e 's/"(total|build|probes|[a-z_-]+_seconds|seconds)": ?[0-9.eE+-]+/"\1":T/g' \
      -e 's/"execution_time": ?[0-9.eE+-]+/"execution_time":T/g' \
      -e 's/"seconds": ?\{[^}]*\}/"seconds":{T}/g' \
      -e "s#$batch#BATCH#g" \
      -e 's#/tmp/[A-Za-z0-9._-]*clothref[A-Za-z0-9._/-]*#SCRATCH#g' \
      -e 's/0x[0-9a-f]{6,16}/0xADDR/g' \
      -e 's/==[0-9]+==/==PID==/g' \
      -e 's/[0-9]+\.[0-9] s\b/N s/g' \
      "$batch/$f" >"$out/$f"
  done
  if [ -f "$out/grades.csv" ]; then
    # the CSV's last column is the seconds of the submission
    sed -E -i 's/,[0-9]+\.[0-9]$/,T/' "$out/grades.csv"
  fi
}

case "${1:-}" in
grade)
  [ $# -eq 3 ] || usage
  clothref=$2
  out=$3
  case "$(realpath -m "$out")" in "$root"/*) echo "$0: OUT must be outside $root" >&2; exit 2 ;; esac
  rm -rf "$out"
  mkdir -p "$out/submissions"
  out=$(cd "$out" && pwd)
  chmod 0700 "$out"
  cp "$clothref" "$out/clothref"
  dirs=()
  for d in "$root"/tests/grader/corpus/20*/* "$root"/tests/grader/handwritten/20*/*; do
    [ -d "$d" ] && dirs+=("$d")
  done
  # the mutants, each over its base (expected.json "base"), named <edition>-<name>
  for expected in "$root"/tests/grader/submissions/20*/*/expected.json; do
    src=$(dirname "$expected")
    name=$(basename "$(dirname "$src")")-$(basename "$src")
    target=$out/submissions/$name
    mkdir -p "$target"
    base=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get("base",""))' "$expected")
    [ -z "$base" ] || find "$root/tests/grader/submissions/$base" -name '*.cpp' -exec cp {} "$target/" \;
    find "$src" -name '*.cpp' -exec cp {} "$target/" \;
    dirs+=("$target")
  done
  "$out/clothref" grade "${dirs[@]}" --out "$out/batch" --jobs 2 --quiet --no-whole-run \
    --cache-dir "${BATCH_IDENTITY_CACHE:-$out/cache}" || echo "$0: clothref grade exited $?" >&2
  normalise "$out/batch" "$out/normalised"
  echo "$out/normalised: $(find "$out/normalised" -type f | wc -l) files"
  ;;
compare)
  [ $# -eq 3 ] || usage
  diff -r "$2/normalised" "$3/normalised"
  ;;
*) usage ;;
esac
