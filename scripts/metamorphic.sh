#!/usr/bin/env bash
# Nightly-style metamorphic run: scripts/metamorphic.sh [SEED] [COUNT] [BUILD_DIR]
# Runs the metamorphic suite of mo2d_tests (tests/metamorphic/metamorphic_test.cpp) on COUNT generated
# mechanisms with seeds SEED .. SEED+COUNT-1 and prints the summary table (relation, mechanisms,
# checks, failures, worst deviation). A failure names its seed; reproduce it alone with
#   MO2D_META_SEED=<seed> MO2D_META_COUNT=1 build/tests/mo2d_tests --gtest_filter=Metamorphic.*
set -euo pipefail
seed=${1:-1}
count=${2:-3000}
build=${3:-build}
bin="$build/tests/mo2d_tests"
[[ -x "$bin" ]] || { echo "metamorphic.sh: $bin not found (cmake --build $build --target mo2d_tests)" >&2; exit 2; }
MO2D_META_SEED="$seed" MO2D_META_COUNT="$count" exec "$bin" --gtest_filter='Metamorphic.GeneratedMechanisms'
