#!/usr/bin/env bash
# Fuzz the scene loader with libFuzzer (clang-14, ASan + UBSan) in its own build folder.
#   ./scripts/fuzz.sh [SECONDS]        (default 120)
# Seeds: mechanisms/*.yaml. New corpus entries go to build-fuzz/corpus; crash reproducers to
# build-fuzz/crashes. Not part of the normal build or CI. Exit status: libFuzzer's (0 = no crash).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
seconds=${1:-120}
build=build-fuzz

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++-14 -DMO2D_BUILD_FUZZ=ON -DMO2D_BUILD_TESTS=OFF \
  -DMO2D_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j2 --target mo2d_scene_fuzz

mkdir -p "$build/corpus" "$build/seeds" "$build/crashes"
cp mechanisms/*.yaml "$build/seeds/"
# -max_len: scene files are small; -timeout: a hang is a bug too; one job (2 shared cores)
"$build/tests/fuzz/mo2d_scene_fuzz" -max_total_time="$seconds" -max_len=8192 -timeout=10 \
  -rss_limit_mb=2048 -artifact_prefix="$build/crashes/" -print_final_stats=1 \
  "$build/corpus" "$build/seeds"
