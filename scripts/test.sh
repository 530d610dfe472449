#!/usr/bin/env bash
# Build and test mo2d twice: Release (build/) and Debug with AddressSanitizer and
# UndefinedBehaviorSanitizer (build-asan/, benchmarks off). Stops at the first failure, so the
# last lines printed are always the summary of the ctest run that decided the result.
#   ./scripts/test.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS

stage() { echo; echo "== $* [$((SECONDS - start)) s]"; }

stage "dependencies"
./scripts/install-deps.sh

for preset in release debug-asan; do
  stage "${preset}: configure"
  cmake --preset "${preset}"
  stage "${preset}: build (${jobs} jobs)"
  cmake --build --preset "${preset}" -j "${jobs}"
  stage "${preset}: test"
  ctest --preset "${preset}" -j "${jobs}"
done
