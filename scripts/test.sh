#!/usr/bin/env bash
# Build and test mo2d twice: Release (build/) and Debug with AddressSanitizer and
# UndefinedBehaviorSanitizer (build-asan/, benchmarks off). Stops at the first failure, so the
# last lines printed are always the summary of the ctest run that decided the result.
# The style checks (scripts/check-style.sh) run after the release configuration; MO2D_STYLE_CHECK=0
# skips them (a local run).
#   ./scripts/test.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS

stage() { echo; echo "== $* [$((SECONDS - start)) s]"; }

stage "dependencies"
./scripts/install-deps.sh

# Style (scripts/check-style.sh: clang-format, file and function sizes, clang-tidy; a few minutes)
# on the release configuration's compile_commands.json. Off until the issue-11 refactor lands
# (src/ does not pass yet); to make it mandatory, change the default below from 0 to 1.
style=${MO2D_STYLE_CHECK:-1}

for preset in release debug-asan; do
  stage "${preset}: configure"
  cmake --preset "${preset}"
  if [[ "${preset}" == release && "${style}" == 1 ]]; then
    stage "style (clang-tidy on the release configuration's unity batches, each file alone)"
    ./scripts/check-style.sh build
  fi
  stage "${preset}: build (${jobs} jobs)"
  cmake --build --preset "${preset}" -j "${jobs}"
  stage "${preset}: test"
  ctest --preset "${preset}" -j "${jobs}"
done
