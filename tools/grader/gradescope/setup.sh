#!/usr/bin/env bash
# Gradescope runs this once when it builds the autograder image (Ubuntu 22.04 or 24.04, or
# Debian 12, as root): it installs the Debian packages the grader needs and builds only the CLI
# and the grader (no tests, no benchmarks) in /autograder/source/clothref/build.
# Written by `clothref gradescope`; see clothref/docs/grading-reference.md, "Gradescope".
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/clothref"
packages=(cmake ninja-build g++ pkg-config libeigen3-dev libfmt-dev nlohmann-json3-dev
          libcli11-dev libxxhash-dev zlib1g-dev libboost-dev)
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLOTHREF_BUILD_TESTS=OFF \
  -DCLOTHREF_INSTALL=OFF >/dev/null
cmake --build build -j "$(nproc)" --target clothref-cli
# Student code runs as uids of its own; none may read our reference, sources or build, and
# Gradescope's containers allow no private mount namespace to cover them: the whole archive is
# root's alone. The grader copies the course headers its compiles need into a folder of their own.
chmod -R go-rwx "$(cd .. && pwd)"
build/bin/clothref --version
