#!/usr/bin/env bash
# Installs the tests' dependencies (scripts/install-deps.sh --all), configures ./build
# with the test suite (keeping the options it was configured with), builds everything
# and runs the whole suite. With FETIC_REQUIRE_ALL=1 (CI) a test that ctest reports
# skipped fails the run: every check must have run (tests/support/skip.hpp).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --all
if [ -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DFETIC_BUILD_TESTS=ON
else
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DFETIC_BUILD_TESTS=ON
fi
cmake --build build -j"$(nproc)"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
ctest --test-dir build --output-on-failure -j"$(nproc)" | tee "$log"
if [ "${FETIC_REQUIRE_ALL:-0}" = 1 ] && grep -q '\*\*\*Skipped' "$log"; then
  echo "FETIC_REQUIRE_ALL=1: these tests were skipped:" >&2
  grep '\*\*\*Skipped' "$log" >&2
  exit 1
fi
