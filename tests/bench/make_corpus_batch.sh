#!/usr/bin/env bash
# Lays out 30 submissions of the grader's corpus as a batch (13 of 2024, the first 17 of 2022 in
# name order; a mutant laid over its base, as grade_test does) in DIR/NN-<edition>-<name>/.
# With --distinct, a comment and a blank line, different per submission, end every file, so no
# two submissions share a file and an object cache cannot help (tests/bench/grade_speed.sh).
# Used by the speed bench and the Slurm test (tests/cluster).
# Usage: tests/bench/make_corpus_batch.sh DIR [--distinct]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
corpus=$root/tests/grader/submissions
out=$1
distinct=${2:-}
n=0
names=$(cd "$corpus" && { printf '%s\n' 2024/*/ | head -13; printf '%s\n' 2022/*/ | head -17; } |
  sed 's:/$::')
for name in $names; do
  n=$((n + 1))
  target=$out/$(printf '%02d' "$n")-${name//\//-}
  mkdir -p "$target"
  base=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get("base",""))' \
    "$corpus/$name/expected.json")
  [ -z "$base" ] || find "$corpus/$base" -name '*.cpp' -exec cp {} "$target/" \;
  find "$corpus/$name" -name '*.cpp' -exec cp {} "$target/" \;
  if [ "$distinct" = --distinct ]; then
    for f in "$target"/*.cpp; do printf '\n// variant %s of %s\n\n' "$n" "$name" >> "$f"; done
  fi
done
