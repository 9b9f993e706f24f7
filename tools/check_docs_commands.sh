#!/usr/bin/env bash
# Runs the commands a document shows, so the docs cannot drift from the code.
# Every line of every ```sh block of FILE (except comments) runs in order with bash from the
# repository root; each must exit 0, unless it ends with "# exits N" (then it must exit N).
#
# Usage: tools/check_docs_commands.sh [--cli BIN] FILE...
#   --cli BIN  run only the lines that start with build/bin/clothref (after "tools/setup.sh && "),
#              in a scratch directory where build/bin/clothref is BIN (the ctest docs_commands:
#              fast, writes only there)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cli=""
if [ "${1:-}" = "--cli" ]; then
  cli=$(realpath "$2")
  shift 2
fi
[ $# -gt 0 ] || { echo "usage: $0 [--cli BIN] FILE..." >&2; exit 2; }

files=()
for file in "$@"; do files+=("$(realpath "$file")"); done

workdir=$root
if [ -n "$cli" ]; then
  workdir=$(mktemp -d "${TMPDIR:-/tmp}/clothref-docs.XXXXXX")
  trap 'rm -rf "$workdir"' EXIT
  # the folders the documented commands write into (the README's pictures go to docs/charts)
  mkdir -p "$workdir/build/bin" "$workdir/docs/charts"
  ln -s "$cli" "$workdir/build/bin/clothref"
fi
cd "$workdir"

count=0
failures=0
for file in "${files[@]}"; do
  in_block=0
  line_number=0
  while IFS= read -r line || [ -n "$line" ]; do
    line_number=$((line_number + 1))
    case "$line" in
      '```sh') in_block=1; continue ;;
      '```'*) in_block=0; continue ;;
    esac
    [ $in_block -eq 1 ] || continue
    [[ "$line" =~ ^[[:space:]]*(#|$) ]] && continue
    # CLI mode: the set-up is the build that made BIN, so "tools/setup.sh && X" runs X
    [ -n "$cli" ] && line=${line#tools/setup.sh && }
    if [ -n "$cli" ] && [[ "$line" != build/bin/clothref* ]]; then continue; fi
    expected=0
    if [[ "$line" =~ \#\ exits\ ([0-9]+)[[:space:]]*$ ]]; then expected=${BASH_REMATCH[1]}; fi
    count=$((count + 1))
    set +e
    output=$(bash -c "$line" 2>&1 </dev/null)
    code=$?
    set -e
    if [ "$code" -ne "$expected" ]; then
      failures=$((failures + 1))
      echo "$file:$line_number: exit $code, expected $expected: $line" >&2
      printf '%s\n' "$output" | tail -n 20 | sed 's/^/    /' >&2
    fi
  done <"$file"
done
echo "check_docs_commands: $count commands, $failures failed" >&2
[ "$count" -gt 0 ] || { echo "check_docs_commands: no commands found" >&2; exit 1; }
[ "$failures" -eq 0 ]
