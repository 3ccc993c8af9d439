#!/usr/bin/env bash
# Fuzzes with libFuzzer (clang-14) for SECONDS seconds in all (default 60, the CI run; a
# long run: scripts/fuzz.sh 3600): two thirds on the scene loader and validation
# (fuzz_scene), one third on the window's view files and scripts (fuzz_view_script, seeded
# from fuzz/seeds_view_script, corpus build-fuzz/corpus_view_script).
#
# Builds build-fuzz/fuzz/fuzz_scene (ASan + UBSan + libFuzzer), seeds the corpus
# build-fuzz/corpus with every bundled scene, every invalid-scene fixture and every fuzz
# regression input, and uses fuzz/toml.dict. Prints the executions and the coverage
# (libFuzzer's cov = code edges, ft = features). Exits non-zero on any crash, leak,
# timeout (an input taking over 10 s counts as a hang) or out-of-memory; the input is
# saved as build-fuzz/crashes/crash-* (also printed in base64 for CI logs). Make it a
# regression fixture: copy it to tests/scenes/fuzz_regressions/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
cxx="${FUZZ_CXX:-clang++-14}"
command -v "$cxx" >/dev/null || { echo "fuzz: $cxx not found (scripts/install-deps.sh)" >&2; exit 1; }

cmake -S . -B build-fuzz -G Ninja -DFETIC_FUZZ=ON -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" >/dev/null
cmake --build build-fuzz

rm -rf build-fuzz/crashes  # only this run's findings
mkdir -p build-fuzz/corpus build-fuzz/crashes
cp -n scenes/*.toml tests/scenes/invalid/*.toml build-fuzz/corpus/ 2>/dev/null || true
for f in tests/scenes/fuzz_regressions/*.toml; do
  [ -e "$f" ] && cp -n "$f" build-fuzz/corpus/
done

log=build-fuzz/fuzz.log
symbolizer=/usr/lib/llvm-14/bin/llvm-symbolizer
[ -x "$symbolizer" ] && export ASAN_SYMBOLIZER_PATH="${ASAN_SYMBOLIZER_PATH:-$symbolizer}"
export ASAN_OPTIONS="detect_leaks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
scene_seconds=$(( (seconds * 2 + 2) / 3 ))
view_seconds=$(( seconds - scene_seconds > 0 ? seconds - scene_seconds : 1 ))
status=0
build-fuzz/fuzz/fuzz_scene build-fuzz/corpus \
  -dict=fuzz/toml.dict -max_total_time="$scene_seconds" -max_len=4096 -timeout=10 \
  -rss_limit_mb=2048 -artifact_prefix=build-fuzz/crashes/ -print_final_stats=1 \
  >"$log" 2>&1 || status=$?
mkdir -p build-fuzz/corpus_view_script
cp -n fuzz/seeds_view_script/* build-fuzz/corpus_view_script/
view_log=build-fuzz/fuzz_view_script.log
if [ "$status" -eq 0 ]; then
  build-fuzz/fuzz/fuzz_view_script build-fuzz/corpus_view_script \
    -max_total_time="$view_seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix=build-fuzz/crashes/ -print_final_stats=1 >"$view_log" 2>&1 || status=$?
  [ "$status" -eq 0 ] || log=$view_log
  view_execs=$(grep -E '^stat::number_of_executed_units' "$view_log" | awk '{print $2}' || true)
  echo "fuzz: view files and scripts: ${view_seconds} s, ${view_execs:-?} executions; log $view_log"
fi

last=$(grep -E '^#[0-9]+' build-fuzz/fuzz.log | tail -1 || true)
execs=$(grep -E '^stat::number_of_executed_units' build-fuzz/fuzz.log | awk '{print $2}' || true)
echo "fuzz: scenes: ${scene_seconds} s, ${execs:-?} executions; last status: ${last:-none}"
echo "fuzz: corpus $(find build-fuzz/corpus -type f | wc -l) inputs in build-fuzz/corpus; log $log"
if [ "$status" -ne 0 ]; then
  echo "fuzz: FAILED (exit $status); the end of the log:" >&2
  tail -60 "$log" >&2
  for f in build-fuzz/crashes/*; do
    [ -e "$f" ] || continue
    echo "fuzz: saved input $f (base64):" >&2
    base64 "$f" >&2
  done
  exit 1
fi
