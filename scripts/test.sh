#!/usr/bin/env bash
# Installs the tests' dependencies (scripts/install-deps.sh --all), configures ./build
# with the test suite (keeping the options it was configured with), builds everything
# and runs the whole suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --all
if [ -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DFETIC_BUILD_TESTS=ON
else
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DFETIC_BUILD_TESTS=ON
fi
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
