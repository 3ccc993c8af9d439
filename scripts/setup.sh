#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine to run fetic: installs what building and running the
# program needs (not the tests' dependencies), configures ./build (Release) and builds
# the program and its man page only. scripts/test.sh adds the rest and builds the tests.
# Extra arguments go to CMake, e.g. -DFETIC_WERROR=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DFETIC_BUILD_TESTS=OFF "$@"
cmake --build build -j"$(nproc)"
