#!/usr/bin/env bash
# Fails when git tracks a leftover of a patch or an editor: *.orig and *.rej (patch, merge), *~
# (Emacs and others), *.swp (Vim), *.bak. Such a file is in every clone, in the Gradescope
# archive's sources and in reviews, and is never what the project means.
#
# Usage: tools/check_tracked_leftovers.sh [DIR]   (default: this checkout)
# Exit: 0 none tracked; 1 some tracked (each named on stderr); 77 DIR is not a git checkout or git
# is missing (ctest counts it as skipped).
set -uo pipefail

dir=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
if ! command -v git >/dev/null; then
  echo "check_tracked_leftovers: git is not installed; nothing checked" >&2
  exit 77
fi
if ! git -C "$dir" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  echo "check_tracked_leftovers: $dir is not a git checkout; nothing checked" >&2
  exit 77
fi
# Every tracked path, the index included (a leftover added but not yet committed counts too).
mapfile -d '' tracked < <(git -C "$dir" ls-files -z)
leftovers=()
for path in "${tracked[@]}"; do
  case "$path" in
    *.orig | *.rej | *~ | *.swp | *.bak) leftovers+=("$path") ;;
  esac
done
if [ ${#leftovers[@]} -gt 0 ]; then
  printf 'check_tracked_leftovers: tracked leftover: %s\n' "${leftovers[@]}" >&2
  echo "check_tracked_leftovers: ${#leftovers[@]} of ${#tracked[@]} tracked files are leftovers (git rm them)" >&2
  exit 1
fi
echo "check_tracked_leftovers: ${#tracked[@]} tracked files, no leftover"
