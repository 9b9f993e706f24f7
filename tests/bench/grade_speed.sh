#!/usr/bin/env bash
# How long `clothref grade` takes (docs/grading-reference.md, "Speed"): one submission end to end with an
# empty object cache (cold) and again with the cache it left (cached), then a batch of 30
# *distinct* submissions at --jobs 1 and --jobs 2, each batch with its own empty cache. The 30
# are the corpus's (13 of 2024, the first 17 of 2022 in name order, mutants laid over their base)
# with a comment and a blank line added to every file, different per submission, so no two share
# a file and the cache cannot help. Prints medians and where the time of one submission goes
# (compile, link, probes: medians of the results.json "seconds" of the cold runs).
#
# Usage: tests/bench/grade_speed.sh [BUILD_DIR] [SINGLE_RUNS] [BATCH_RUNS]
#   (defaults: build 5 1). Work goes to a temporary folder, removed at the end.
# The machine's load average is printed with the figures: timings of a loaded machine say little.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
single_runs=${2:-5}
batch_runs=${3:-1}
clothref=$build/bin/clothref
[ -x "$clothref" ] || { echo "grade_speed: $clothref not built" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/clothref-grade-speed-XXXXXX")
trap 'rm -rf "$work"' EXIT

# 1. The 30 distinct submissions.
"$root/tests/bench/make_corpus_batch.sh" "$work/subs" --distinct
count=$(find "$work/subs" -mindepth 1 -maxdepth 1 -type d | wc -l)
distinct=$(md5sum "$work"/subs/*/*.cpp | cut -d' ' -f1 | sort -u | wc -l)
files=$(find "$work/subs" -mindepth 2 -maxdepth 2 -name "*.cpp" | wc -l)
echo "submissions: $count, files: $files, distinct files: $distinct"
[ "$distinct" -eq "$files" ] || { echo "grade_speed: two submissions share a file" >&2; exit 1; }

seconds() { python3 -c 'import sys; print(f"{float(sys.argv[1]):.2f}")' "$1"; }
now() { date +%s.%N; }
median() { python3 -c 'import statistics,sys; print(f"{statistics.median(map(float,sys.argv[1:])):.2f}")' "$@"; }

# 2. One submission, cold then cached.
one=$(echo "$work"/subs/*2024-reference)
cold=() cached=()
for r in $(seq "$single_runs"); do
  rm -rf "$work/cache"
  t0=$(now)
  "$clothref" grade "$one" --cache-dir "$work/cache" --results "$work/cold-$r.json" >/dev/null
  t1=$(now)
  "$clothref" grade "$one" --cache-dir "$work/cache" --results "$work/cached-$r.json" >/dev/null
  t2=$(now)
  cold+=("$(python3 -c "print($t1 - $t0)")")
  cached+=("$(python3 -c "print($t2 - $t1)")")
done
echo "load before the batches: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "one submission, cold (empty cache), median of $single_runs: $(median "${cold[@]}") s" \
  "(runs: $(for c in "${cold[@]}"; do seconds "$c"; done | tr '\n' ' '))"
echo "one submission, cached, median of $single_runs: $(median "${cached[@]}") s" \
  "(runs: $(for c in "${cached[@]}"; do seconds "$c"; done | tr '\n' ' '))"
python3 - "$work" "$single_runs" <<'EOF'
import json, statistics, sys
work, runs = sys.argv[1], int(sys.argv[2])
for kind in ("cold", "cached"):
    phases = {}
    for r in range(1, runs + 1):
        for k, v in json.load(open(f"{work}/{kind}-{r}.json"))["extra_data"]["seconds"].items():
            phases.setdefault(k, []).append(v)
    print(f"  {kind}: where the time goes (medians, s): " +
          ", ".join(f"{k} {statistics.median(v):.2f}" for k, v in sorted(phases.items())))
EOF

# 3. The batch of 30 distinct submissions at --jobs 1 and --jobs 2.
for jobs in 1 2; do
  walls=()
  for r in $(seq "$batch_runs"); do
    rm -rf "$work/batch"
    t0=$(now)
    "$clothref" grade "$work"/subs/*/ --out "$work/batch" --jobs "$jobs" --quiet
    t1=$(now)
    walls+=("$(python3 -c "print($t1 - $t0)")")
    rows=$(($(wc -l < "$work/batch/grades.csv") - 1))
    [ "$rows" -eq "$count" ] || { echo "grade_speed: $rows rows, expected $count" >&2; exit 1; }
  done
  echo "batch of $count distinct, --jobs $jobs, median of $batch_runs: $(median "${walls[@]}") s" \
    "(runs: $(for w in "${walls[@]}"; do seconds "$w"; done | tr '\n' ' '); load now" \
    "$(cut -d' ' -f1-3 /proc/loadavg))"
done
