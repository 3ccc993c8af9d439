#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine: installs dependencies, configures and builds fetic
# into ./build (Release). Extra arguments go to CMake, e.g. -DFETIC_WERROR=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build -j"$(nproc)"
