#!/usr/bin/env bash
# Runs libFuzzer targets one after another, each for a bounded time, from the committed seeds, and
# prints one table row per target from libFuzzer's final statistics (docs/reliability.md).
#
# Usage: tests/fuzz/run_fuzz.sh BUILD_DIR WORK_DIR SECONDS [TARGET...]
#   BUILD_DIR  a build configured with -DCLOTHREF_FUZZ=ON (clang), its fuzz_<target> built
#   WORK_DIR   created if missing; per target: corpus/<target>/ (seeds + what the run grew),
#              crashes/<target>/ (crash-, leak-, timeout-, oom- inputs), logs/<target>.log
#   SECONDS    -max_total_time of each target
#   TARGET     default: every target of tests/fuzz/CMakeLists.txt
# Environment: FUZZ_NICE (default 5), the niceness each run gets on a shared machine.
# Exit status: 0 if no target found anything, 1 if one did (its inputs are in crashes/), 2 on a
# usage error or a missing binary.
set -uo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
if [ $# -lt 3 ]; then
  echo "usage: $0 BUILD_DIR WORK_DIR SECONDS [TARGET...]" >&2
  exit 2
fi
build_dir=$1
work_dir=$2
seconds=$3
shift 3
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  read -r -a targets < <(sed -n 's/^set(CLOTHREF_FUZZ_TARGETS \(.*\))$/\1/p' \
    "$root/tests/fuzz/CMakeLists.txt")
fi

# the value of the last "stat::NAME: V" line, or of the last "NAME: V" on a status line
final_stat() { sed -n "s/^stat::$2: *\([0-9]*\).*/\1/p" "$1" | tail -n 1; }
status_field() { grep -E '^#[0-9]+' "$1" | sed -n "s/.* $2: \([0-9]*\).*/\1/p" | tail -n 1; }

found=0
echo "| target | seconds | executions | exec/s | cov | ft | peak RSS (MB) | findings |"
echo "|---|---|---|---|---|---|---|---|"
for target in "${targets[@]}"; do
  binary=$build_dir/bin/fuzz_$target
  if [ ! -x "$binary" ]; then
    echo "run_fuzz: $binary: not built (cmake --build $build_dir --target fuzz_$target)" >&2
    exit 2
  fi
  corpus=$work_dir/corpus/$target
  crashes=$work_dir/crashes/$target
  log=$work_dir/logs/$target.log
  mkdir -p "$corpus" "$crashes" "$work_dir/logs"
  cp -n "$root/tests/fuzz/corpus/$target/"* "$corpus/"
  start=$(date +%s)
  nice -n "${FUZZ_NICE:-5}" "$binary" "$corpus" -max_total_time="$seconds" -print_final_stats=1 \
    -max_len=65536 -rss_limit_mb=2048 -timeout=20 -artifact_prefix="$crashes/" >"$log" 2>&1
  status=$?
  elapsed=$(($(date +%s) - start))
  findings=$(find "$crashes" -type f | wc -l)
  if [ "$status" -ne 0 ] || [ "$findings" -ne 0 ]; then
    found=1
    findings="$findings input(s), exit $status: see $log"
  else
    findings=none
  fi
  echo "| $target | $elapsed | $(final_stat "$log" number_of_executed_units)" \
    "| $(final_stat "$log" average_exec_per_sec) | $(status_field "$log" cov)" \
    "| $(status_field "$log" ft) | $(final_stat "$log" peak_rss_mb) | $findings |"
done
exit "$found"
