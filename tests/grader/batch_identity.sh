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
# for the refactors of issue 37 (docs/grading-reference.md, "Adding a probe"): "byte-identical" in a
# commit message means `compare` printed nothing.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)

usage() {
  echo "usage: $0 grade CLOTHREF OUT | compare A B" >&2
  exit 2
}

# Copies BATCH to OUT with what varies from run to run replaced: in JSON (results.json, row.json,
# the class page's embedded rows) every "seconds" and "execution_time" value, in any text the
# batch's own path and the folder it is in (OUT, where the mutants are laid out), scratch paths,
# sanitizer addresses and pids; grades.csv's seconds column.
normalise() {
  python3 - "$1" "$2" <<'PYTHON'
import json, os, re, shutil, sys
batch, out = sys.argv[1], sys.argv[2]
shutil.rmtree(out, ignore_errors=True)
def text(s):
    s = s.replace(batch, 'BATCH').replace(os.path.dirname(batch), 'OUT')
    s = re.sub(r'/tmp/[A-Za-z0-9._-]*clothref[A-Za-z0-9._/-]*', 'SCRATCH', s)
    s = re.sub(r'0x[0-9a-f]{6,16}', '0xADDR', s)
    s = re.sub(r'==[0-9]+==', '==PID==', s)
    return re.sub(r'"(seconds|execution_time)": ?(\{[^{}]*\}|[-0-9.eE+]+)', r'"\1":"T"', s)
def walk(v):
    if isinstance(v, dict):
        return {k: ('T' if k in ('seconds', 'execution_time') else walk(x)) for k, x in v.items()}
    if isinstance(v, list):
        return [walk(x) for x in v]
    return text(v) if isinstance(v, str) else v
for root, _, files in os.walk(batch):
    for name in files:
        src = os.path.join(root, name)
        dst = os.path.join(out, os.path.relpath(src, batch))
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        data = open(src, 'rb').read().decode('utf-8', 'surrogateescape')
        if name.endswith('.json'):
            data = json.dumps(walk(json.loads(data)), indent=1, ensure_ascii=False) + '\n'
        elif name.endswith('.csv'):
            data = '\n'.join(re.sub(r',[0-9]+\.[0-9]+$', ',T', l) for l in data.split('\n'))
        else:
            data = text(data)
        open(dst, 'wb').write(data.encode('utf-8', 'surrogateescape'))
PYTHON
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
