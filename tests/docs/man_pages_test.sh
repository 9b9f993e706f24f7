#!/usr/bin/env bash
# A man page for clothref and for every subcommand `clothref --help` lists, each rendered with
# `man -l` as a reader would see it: it renders without error, has a NAME section, an EXAMPLES
# section whose first example runs the page's own command, and an EXIT STATUS section that gives
# 0 and 2 (every command's "done" and "bad input"), and its footer shows its three fields apart
# ("clothref-grade 0.1.0   November 2026   CLOTHREF-GRADE(1)"): the source (program and version,
# nothing else), the month, and the title.
# Usage: tests/docs/man_pages_test.sh CLI MANDIR VERSION
# Exit: 0 all good; 1 a page missing or wrong (each named); 77 `man` is not installed.
set -uo pipefail

cli=${1:?usage: man_pages_test.sh CLI MANDIR VERSION}
man_dir=${2:?usage: man_pages_test.sh CLI MANDIR VERSION}
version=${3:?usage: man_pages_test.sh CLI MANDIR VERSION}
if ! command -v man >/dev/null; then
  echo "SKIP: man is not installed (Debian package man-db; tools/setup.sh installs it)"
  exit 77
fi
# man-db filters pages in a seccomp sandbox, which some containers and chroots refuse.
export MAN_DISABLE_SECCOMP=1 MANWIDTH=100 MANPAGER=cat PAGER=cat LC_ALL=C.UTF-8

# The subcommands: the words indented under "Subcommands:" in the top-level help.
mapfile -t commands < <("$cli" --help | awk '
  /^Subcommands:/ { in_list = 1; next }
  in_list && /^[^ ]/ { in_list = 0 }
  in_list && /^  [a-z]/ { print $1 }')
if [ ${#commands[@]} -lt 10 ]; then
  echo "FAIL: found ${#commands[@]} subcommands in '$cli --help', expected at least 10"
  exit 1
fi

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
check_page() {
  local name=$1 page="$man_dir/$1.1" text footer title
  title=$(tr '[:lower:]' '[:upper:]' <<<"$name")
  if [ ! -f "$page" ]; then
    fail "$name: no man page $page"
    return
  fi
  if ! text=$(man -l "$page" 2>&1); then
    fail "$name: man -l $page failed: $text"
    return
  fi
  grep -q '^NAME' <<<"$text" || fail "$name: no NAME section"
  # the lines of a section: from its heading to the next heading (a line that starts with a
  # capital)
  section() { awk -v s="$1" '$0 == s { on = 1; next } on && /^[A-Z]/ { on = 0 } on' <<<"$text"; }
  local examples status command=${name/-/ }
  examples=$(section EXAMPLES)
  status=$(section 'EXIT STATUS')
  [ -n "$examples" ] || fail "$name: no EXAMPLES section (cmake/man/$name.h2m)"
  [ -n "$examples" ] && ! grep -m1 '[a-z]' <<<"$examples" | grep -q "^ *$command\b" &&
    fail "$name: the first example does not run '$command'"
  [ -n "$status" ] || fail "$name: no EXIT STATUS section (cmake/man/$name.h2m)"
  for code in 0 2; do
    grep -q "^ *$code\b" <<<"$status" || fail "$name: EXIT STATUS does not give $code"
  done
  grep -q "^ *$name " <<<"$text" || fail "$name: no line of the page starts with '$name '"
  footer=$(grep -v '^[[:space:]]*$' <<<"$text" | tail -n 1)
  # three fields, at least two spaces apart: source, "Month YYYY", TITLE(1)
  if [[ ! "$footer" =~ ^(.*[^ ])\ {2,}([A-Z][a-z]+\ [0-9]{4})\ {2,}([A-Z-]+\(1\))$ ]]; then
    fail "$name: footer does not show three separate fields: '$footer'"
    return
  fi
  [ "${BASH_REMATCH[1]}" = "$name $version" ] ||
    fail "$name: footer source '${BASH_REMATCH[1]}', expected '$name $version'"
  [ "${BASH_REMATCH[3]}" = "$title(1)" ] ||
    fail "$name: footer title '${BASH_REMATCH[3]}', expected '$title(1)'"
}

check_page clothref
for command in "${commands[@]}"; do check_page "clothref-$command"; done
# Every page made belongs to a command (a removed command leaves no page behind).
declare -A listed=()
for command in "${commands[@]}"; do listed[$command]=1; done
for page in "$man_dir"/*.1; do
  name=$(basename "$page" .1)
  [ "$name" = clothref ] && continue
  [ -n "${listed[${name#clothref-}]:-}" ] ||
    fail "$name: a man page for a command '$cli --help' does not list"
done
if [ "$failures" -gt 0 ]; then
  echo "$failures problem(s) in the man pages of ${#commands[@]} commands"
  exit 1
fi
echo "ok: clothref(1) and ${#commands[@]} command pages render with their footers"
