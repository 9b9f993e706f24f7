#!/usr/bin/env bash
# The fresh-machine check: for each Debian release asked for, builds a minimal root with
# mmdebstrap, clones this checkout's current commit into /root/clothref inside it (where root's
# clones usually go: mode 700), and runs the README's two commands there exactly as the README
# writes them, timing each. Prints, per release, the time of the root and of each command and the
# test summary; removes its mounts and folders on success, failure or interrupt.
#
# Usage: tools/check_fresh_debian.sh [--suite bookworm|trixie|both] [--keep] [--workdir DIR]
#   --suite     bookworm (Debian 12), trixie (Debian 13) or both, one after the other (default)
#   --keep      leave the root file systems in place (their paths are printed)
#   --workdir   a new folder to make the roots in (default: a new one under ${TMPDIR:-/tmp})
# Needs: root, mmdebstrap (Debian package), a reachable Debian package source.
# Exit: 0 both commands passed on every release; 1 a command failed; 2 the check could not run.
# Bubblewrap cannot make namespaces inside a chroot, so the grader's bubblewrap tests skip there
# with a message; everything else runs as on a fresh machine.
set -uo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=tools/debian_root.sh
. "$repo/tools/debian_root.sh"
say() { echo "check_fresh_debian: $*" >&2; }

workdir=""
suites=(bookworm trixie)
while [ $# -gt 0 ]; do
  case "$1" in
    --keep) export DEBIAN_ROOT_KEEP=1 ;;
    --workdir) workdir=${2:?--workdir needs a folder}; shift ;;
    --suite)
      case "${2:-}" in
        bookworm | trixie) suites=("$2") ;;
        both) suites=(bookworm trixie) ;;
        *) say "--suite takes bookworm, trixie or both, not '${2:-}'"; exit 2 ;;
      esac
      shift ;;
    -h | --help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) say "unknown argument '$1' (see --help)"; exit 2 ;;
  esac
  shift
done

# Refuse before touching anything.
if ! why=$(debian_root_usable); then say "$why; nothing done"; exit 2; fi
commit=$(git -C "$repo" rev-parse HEAD 2>/dev/null) ||
  { say "$repo is not a git checkout; nothing done"; exit 2; }
# The README's two commands: the ```sh blocks under "## Two commands".
mapfile -t commands < <(awk '
  /^## / { in_section = index($0, "## Two commands") == 1 }
  in_section && /^```sh$/ { in_block = 1; next }
  in_block && /^```$/ { in_block = 0; next }
  in_block { print }' "$repo/README.md")
if [ ${#commands[@]} -ne 2 ]; then
  say "expected 2 commands under README.md's '## Two commands', found ${#commands[@]}; nothing done"
  exit 2
fi
if [ -n "$workdir" ]; then
  [ ! -e "$workdir" ] || { say "--workdir $workdir exists; give a new path; nothing done"; exit 2; }
  mkdir -p "$workdir" || exit 2
else
  workdir=$(mktemp -d "${TMPDIR:-/tmp}/clothref-fresh.XXXXXX") || exit 2
fi
# The release being checked: its root is $suite_dir/root; released (unmounted, removed) when done.
suite_dir=""
release_current() {
  [ -n "$suite_dir" ] || return 0
  local dir=$suite_dir
  suite_dir=""
  debian_root_release "$dir/root" "$dir"
}
# shellcheck disable=SC2317  # reached through the trap
finish() {
  local status=$?
  trap - EXIT
  release_current || status=2
  [ "${DEBIAN_ROOT_KEEP:-0}" = 1 ] || rmdir "$workdir" 2>/dev/null
  exit "$status"
}
trap finish EXIT
trap 'say "interrupted"; exit 130' INT TERM

# Runs the two commands on a fresh root of one suite; prints its report on stdout.
# Returns 0 both passed, 1 a command failed, 2 the root could not be made.
check_suite() {
  local suite=$1 name root start seconds index log begin code status=0
  name=$(debian_root_release_name "$suite")
  suite_dir="$workdir/$suite"
  root="$suite_dir/root"
  mkdir -p "$suite_dir" || return 2
  say "$name ($suite): commit $commit; root in $root"
  start=$(date +%s)
  if ! debian_root_make "$root" "$suite_dir/mmdebstrap.log" git,sudo "$suite"; then
    tail -n 20 "$suite_dir/mmdebstrap.log" >&2
    say "$name: mmdebstrap failed (no package source reachable?)"
    return 2
  fi
  seconds=$(($(date +%s) - start))
  say "$name: minimal root made in $seconds s"
  local summary=("$name ($suite): minimal root made in $seconds s")

  # The current commit only (no uncommitted change), in root's home as a user would clone it.
  if ! git clone --quiet --no-hardlinks "$repo" "$root/root/clothref" ||
     ! git -C "$root/root/clothref" checkout --quiet --detach "$commit"; then
    say "$name: clone failed"
    return 2
  fi
  debian_root_mount "$root" || { say "$name: could not bind /proc, /sys and /dev into $root"; return 2; }

  for index in 0 1; do
    say "$name: command $((index + 1)): ${commands[index]}"
    log="$suite_dir/command$((index + 1)).log"
    begin=$(date +%s)
    debian_root_run "$root" "cd /root/clothref && ${commands[index]}" >"$log" 2>&1
    code=$?
    seconds=$(($(date +%s) - begin))
    summary+=("$name: command $((index + 1)): exit $code in $((seconds / 60)) min $((seconds % 60)) s")
    if [ "$code" -ne 0 ]; then
      tail -n 40 "$log" >&2
      status=1
    fi
  done
  # shellcheck disable=SC2016  # expanded inside the root
  echo "== $name ($suite): $(debian_root_run "$root" '. /etc/os-release && echo "$PRETTY_NAME"'), $(
    debian_root_run "$root" 'g++ --version 2>/dev/null | head -n 1')"
  # ctest's closing lines: the pass count, then any skipped or failed tests.
  sed -n '/tests passed/,$p' "$suite_dir/command2.log" | grep -v '^\s*$' | head -n 60
  printf '%s\n' "${summary[@]}"
  echo "$name ($suite): commit $commit, $(date -u +%Y-%m-%d), $([ $status -eq 0 ] && echo passed || echo FAILED)"
  return "$status"
}

overall=0
for suite in "${suites[@]}"; do
  check_suite "$suite"
  result=$?
  release_current || result=2
  # the worst outcome wins: could not run (2) over failed (1) over passed (0)
  [ "$result" -gt "$overall" ] && overall=$result
done
exit "$overall"
