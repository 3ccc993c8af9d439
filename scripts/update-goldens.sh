#!/usr/bin/env bash
# Regenerates the renderer's golden images (tests/golden/*.png) from the current code,
# including the interactive window's screenshots (tests/golden/gui_*.png, taken under Xvfb):
# builds, then runs the golden tests with FETIC_UPDATE_GOLDENS=1, which write the renders
# instead of comparing them. Review the new images (git diff --stat tests/golden, and look
# at them) before committing. Usage: scripts/update-goldens.sh [BUILD_DIR] (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j"$(nproc)" --target test_render_golden test_gui fetic
FETIC_UPDATE_GOLDENS=1 ctest --test-dir "$build" -R "render golden" --output-on-failure
FETIC_UPDATE_GOLDENS=1 ctest --test-dir "$build" -R "gui: (e2e|scripted)" --output-on-failure
git status --short tests/golden
