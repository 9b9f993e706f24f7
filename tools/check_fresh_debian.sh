#!/usr/bin/env bash
# The fresh-machine check: builds a minimal Debian 12 root with mmdebstrap, clones this checkout's
# current commit into /root/clothref inside it (where root's clones usually go: mode 700), and runs
# the README's two commands there exactly as the README writes them, timing each. Prints the time
# of each command and the test summary; removes its mounts and folder on success, failure or
# interrupt.
#
# Usage: tools/check_fresh_debian.sh [--keep] [--workdir DIR]
#   --keep      leave the root file system in place (its path is printed)
#   --workdir   a new folder to make the root in (default: a new one under ${TMPDIR:-/tmp})
# Needs: root, mmdebstrap (Debian package), a reachable Debian package source.
# Exit: 0 both commands passed; 1 a command failed; 2 the check could not run (nothing touched).
# Bubblewrap cannot make namespaces inside a chroot, so the grader's bubblewrap tests skip there
# with a message; everything else runs as on a fresh machine.
set -uo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=tools/debian_root.sh
. "$repo/tools/debian_root.sh"
say() { echo "check_fresh_debian: $*" >&2; }

workdir=""
while [ $# -gt 0 ]; do
  case "$1" in
    --keep) export DEBIAN_ROOT_KEEP=1 ;;
    --workdir) workdir=${2:?--workdir needs a folder}; shift ;;
    -h | --help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
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
root="$workdir/root"
# shellcheck disable=SC2317  # reached through the trap
finish() {
  local status=$?
  trap - EXIT
  debian_root_release "$root" "$workdir" || status=2
  exit "$status"
}
trap finish EXIT
trap 'say "interrupted"; exit 130' INT TERM

say "commit $commit; root in $root"
start=$(date +%s)
if ! debian_root_make "$root" "$workdir/mmdebstrap.log" git,sudo; then
  tail -n 20 "$workdir/mmdebstrap.log" >&2
  say "mmdebstrap failed (no package source reachable?)"
  exit 2
fi
say "minimal Debian 12 root made in $(($(date +%s) - start)) s"

# The current commit only (no uncommitted change), in root's home as a user would clone it.
if ! git clone --quiet --no-hardlinks "$repo" "$root/root/clothref" ||
   ! git -C "$root/root/clothref" checkout --quiet --detach "$commit"; then
  say "clone failed"
  exit 2
fi
debian_root_mount "$root" || { say "could not bind /proc, /sys and /dev into $root"; exit 2; }

status=0
summary=()
for index in 0 1; do
  say "command $((index + 1)): ${commands[index]}"
  log="$workdir/command$((index + 1)).log"
  begin=$(date +%s)
  debian_root_run "$root" "cd /root/clothref && ${commands[index]}" >"$log" 2>&1
  code=$?
  seconds=$(($(date +%s) - begin))
  summary+=("command $((index + 1)): exit $code in $((seconds / 60)) min $((seconds % 60)) s")
  if [ "$code" -ne 0 ]; then
    tail -n 40 "$log" >&2
    status=1
  fi
done

# ctest's closing lines: the pass count, then any skipped or failed tests.
sed -n '/tests passed/,$p' "$workdir/command2.log" | grep -v '^\s*$' | head -n 60
printf '%s\n' "${summary[@]}"
echo "commit $commit, $(date -u +%Y-%m-%d), $([ $status -eq 0 ] && echo passed || echo FAILED)"
exit "$status"
