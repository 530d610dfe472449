#!/usr/bin/env bash
# Fuzz mo2d with libFuzzer (clang-14, ASan + UBSan) in its own build folder.
#   ./scripts/fuzz.sh [SECONDS]          the scene loader (default 120 s)
#   ./scripts/fuzz.sh run [SECONDS [RUNS]]  loader + tiny inverse/forward runs with budgets (RUNS:
#                                        stop after that many executions, if sooner)
# Seeds: mechanisms/*.yaml (and, for the runs, the reproduction scenes of shared/repro when that
# folder is beside the checkout). New corpus entries go to build-fuzz/corpus[-run]; crash
# reproducers to build-fuzz/crashes[-run]. Not part of the normal build or CI. Exit status:
# libFuzzer's (0 = no crash).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
target=mo2d_scene_fuzz
suffix=""
if [[ "${1:-}" == run ]]; then
  target=mo2d_run_fuzz
  suffix="-run"
  shift
fi
seconds=${1:-120}
runs=${2:--1}
build=build-fuzz

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++-14 -DMO2D_BUILD_FUZZ=ON -DMO2D_BUILD_TESTS=OFF \
  -DMO2D_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j2 --target "$target"

corpus="$build/corpus$suffix" seeds="$build/seeds$suffix" crashes="$build/crashes$suffix"
mkdir -p "$corpus" "$seeds" "$crashes"
cp mechanisms/*.yaml "$seeds/"
if [[ -n "$suffix" && -d ../shared/repro ]]; then
  for f in ../shared/repro/*.yaml; do cp "$f" "$seeds/repro_$(basename "$f")"; done
fi
# -max_len: scene files are small; -timeout: a hang is a bug too (each run has a budget of 200
# steps and 0.05 s, tests/fuzz/run_fuzz.cpp, so 5 s is far beyond any budgeted run); one job (2
# shared cores)
timeout=10
[[ -n "$suffix" ]] && timeout=5
"$build/tests/fuzz/$target" -max_total_time="$seconds" -runs="$runs" -max_len=8192 -timeout="$timeout" \
  -rss_limit_mb=2048 -artifact_prefix="$crashes/" -print_final_stats=1 "$corpus" "$seeds"
