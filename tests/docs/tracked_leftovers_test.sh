#!/usr/bin/env bash
# tools/check_tracked_leftovers.sh catches each kind of leftover and only those: a scratch git
# repository (in its own temporary folder) is given one file of each kind, staged, plus files
# whose names only resemble them; the check must fail and name exactly the leftovers. Then, with
# the leftovers removed from the index, it must pass.
# Usage: tests/docs/tracked_leftovers_test.sh CHECKER
set -euo pipefail

checker=${1:?usage: tracked_leftovers_test.sh CHECKER}
command -v git >/dev/null || { echo "SKIP: git is not installed"; exit 77; }
scratch=$(mktemp -d "${TMPDIR:-/tmp}/clothref-leftovers.XXXXXX")
trap 'rm -rf "$scratch"' EXIT

repo=$scratch/repo
git init --quiet "$repo"
leftovers=(lib/a.cpp.orig lib/a.cpp.rej "notes.md~" "src/.b.h.swp" config.bak)
innocent=(lib/a.cpp docs/origin.md tools/orig.sh rej.txt lib/backup.h "a~b.txt" swp.cpp)
for path in "${leftovers[@]}" "${innocent[@]}"; do
  mkdir -p "$repo/$(dirname "$path")"
  echo x >"$repo/$path"
done
git -C "$repo" add -A

fail() { echo "FAIL: $*"; exit 1; }
set +e
output=$("$checker" "$repo" 2>&1)
code=$?
set -e
[ "$code" -eq 1 ] || fail "exit $code with ${#leftovers[@]} leftovers tracked, expected 1: $output"
named=$(sed -n 's/^check_tracked_leftovers: tracked leftover: //p' <<<"$output" | sort)
wanted=$(printf '%s\n' "${leftovers[@]}" | sort)
[ "$named" = "$wanted" ] || fail "named:
$named
expected:
$wanted"

git -C "$repo" rm --quiet --cached "${leftovers[@]}"
output=$("$checker" "$repo" 2>&1) || fail "exit $? with only innocent names tracked: $output"
grep -q "${#innocent[@]} tracked files, no leftover" <<<"$output" || fail "unexpected: $output"
echo "ok: ${#leftovers[@]} leftovers named, ${#innocent[@]} look-alikes passed"
