#!/usr/bin/env bash
# ctest `install`: an installed clothref stands alone. Installs the build into a temporary prefix,
# copies that prefix elsewhere (so nothing may point back into the install step's paths), then,
# with the source and build trees out of reach (bubblewrap puts an empty tmpfs over them), runs
# from the copy: trace, plot, golden (the installed golden set against its own data), grade (a
# corpus submission, in the sandbox the install gives) and verify, and reads a man page.
# Skipped (77) only when bubblewrap is missing or cannot create namespaces here.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2

command -v bwrap >/dev/null || { echo "SKIP: bwrap not installed (tools/setup.sh installs bubblewrap)"; exit 77; }
bwrap --dev-bind / / true 2>/dev/null ||
  { echo "SKIP: bubblewrap cannot create a mount namespace here"; exit 77; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/clothref-install-XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cp -a "$tmp/prefix" "$tmp/copy"
rm -rf "$tmp/prefix"
mkdir -p "$tmp/work"
# a student submission from the corpus, copied before the source tree goes out of reach
cp -r "$source/tests/grader/submissions/2022/reference" "$tmp/work/submission"

# Everything as it is, except the source and build trees: empty.
hide=(--tmpfs "$source")
case "$build" in "$source"/*) ;; *) hide+=(--tmpfs "$build") ;; esac
run() {  # what command ...: runs in the sandbox, output to $tmp/work/<what>.log
  local what=$1
  shift
  echo "+ clothref $*"
  if ! bwrap --dev-bind / / "${hide[@]}" --chdir "$tmp/work" \
      env -u PYTHONPATH "$tmp/copy/bin/clothref" "$@" > "$tmp/work/$what.log" 2>&1; then
    cat "$tmp/work/$what.log" >&2
    fail "clothref $* (from the installed copy)"
  fi
}
bwrap --dev-bind / / "${hide[@]}" test ! -e "$source/tools/python" ||
  fail "the source tree is still reachable"

run trace trace --scene spring --steps 200 --stride 20 -o "$tmp/work/spring.jsonl"
run plot plot "$tmp/work/spring.jsonl" -o "$tmp/work/spring" --formats png
[ -s "$tmp/work/spring-energy.png" ] || fail "plot wrote no spring-energy.png"
run golden golden -q
grep -q "golden" "$tmp/work/golden.log" || fail "golden printed no verdict: $(cat "$tmp/work/golden.log")"
run grade grade "$tmp/work/submission" --no-whole-run --results "$tmp/work/results.json"
python3 - "$tmp/work/results.json" <<'PY' || fail "the installed grader did not give the reference full marks"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["score"] == 80, r["score"]
PY
run verify verify
grep -q " checks, 0 failed" "$tmp/work/verify.log" || fail "verify: $(tail -n 3 "$tmp/work/verify.log")"
for page in clothref clothref-trace clothref-grade; do
  [ -s "$tmp/copy/share/man/man1/$page.1" ] || fail "no man page $page.1"
done
echo "the installed copy ran trace, plot, golden, grade and verify without the source tree"
