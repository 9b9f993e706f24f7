#!/usr/bin/env bash
# Installs the Debian/Ubuntu packages clothref needs (only those missing), then configures with
# the `release` preset (CMakePresets.json: Ninja, Release, build/) and builds.
# Usage: tools/setup.sh [extra cmake arguments]
# Environment: BUILD_DIR (default build), CXX (compiler, default the system's), CMAKE_BUILD_TYPE
# (default the preset's Release). Debian 12 and 13 (run here, on fresh roots too:
# tools/check_fresh_debian.sh); Ubuntu 22.04 and 24.04 (the CI matrix, not run here).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}

# Each group's purpose is in README.md ("What tools/setup.sh installs"); keep the two in step.
build=(cmake ninja-build g++ pkg-config libeigen3-dev libfmt-dev nlohmann-json3-dev libcli11-dev
       libxxhash-dev zlib1g-dev libboost-dev)
tests=(libgtest-dev libgmock-dev libbenchmark-dev)
charts=(python3 python3-numpy python3-matplotlib)
pages=(chromium chromium-driver python3-selenium python3-pil python3-markdown)  # the browser tests of the pages
grader=(bubblewrap)
manpages=(help2man man-db)  # a man page per command, made from --help at build time; man renders them
cluster=(slurm-wlm munge)  # the single-node Slurm of the cluster test (ctest -L cluster)
machines=(mmdebstrap)  # the Gradescope test's fresh Debian 12 root (and tools/check_fresh_debian.sh's)
packages=("${build[@]}" "${tests[@]}" "${charts[@]}" "${pages[@]}" "${grader[@]}" "${manpages[@]}"
          "${cluster[@]}" "${machines[@]}")
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo=()
  [ "$(id -u)" -eq 0 ] || sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

# the same preset as `cmake --preset release`, so either may configure build/ first
cd "$root"
cmake --preset release -B "$build_dir" -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" "$@" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
