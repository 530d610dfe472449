#!/usr/bin/env bash
# First run of mo2d: install the packages the libraries and the mo2d command need, build them
# (Release, build/), run the demo (inverse dynamics of the Whitworth mechanism: table, CSV,
# filmstrip, torque plot in out/). The test suite, the benchmarks and the Python module are left
# to scripts/test.sh, which installs and builds the rest in the same build/.
#   ./scripts/quickstart.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
jobs=$(nproc 2>/dev/null || echo 2)
start=$SECONDS

echo "== dependencies"
./scripts/install-deps.sh --minimal

echo "== configure (preset 'quickstart', build/)"
cmake --preset quickstart

echo "== build: the libraries and build/mo2d (${jobs} jobs)"
cmake --build --preset quickstart -j "${jobs}"

echo "== demo: build/mo2d demo"
./build/mo2d demo

echo
echo "Done in $((SECONDS - start)) s."
echo "  inverse dynamics of the Whitworth mechanism: $(pwd)/out/whitworth_inverse.csv"
echo "  filmstrip of the motion:                     $(pwd)/out/whitworth_filmstrip.png"
echo "  crank torque plot:                           $(pwd)/out/whitworth_efforts.png"
echo "  command-line tool:                           $(pwd)/build/mo2d --help"
echo "  scene files:                                 $(pwd)/mechanisms/*.yaml (build/mo2d info|inverse|forward|render|crosscheck SCENE)"
echo "  optional parts (Python module, tests...):     $(pwd)/build/mo2d doctor"
echo "  next: ./scripts/test.sh (Release + ASan/UBSan test suites, the Python module)"
