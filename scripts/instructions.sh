#!/usr/bin/env bash
# Instruction counts of the headline runs (docs/performance.md, "Instruction counts"), by
# callgrind: exact and the same on a loaded machine, so that a regression shows where times are
# noise. Slow (about a minute under valgrind): not run by CI; ctest only checks that it parses.
#   scripts/instructions.sh [BUILD_DIR]      (default build/; needs BUILD_DIR/mo2d, a Release build)
# Prints a Markdown table: per run, the instructions of the whole process, of main(), of
# forward_dynamics() (inclusive), and of one evaluation (ForwardData::accelerations, inclusive
# per call, averaged over the run's calls, the regularized ones at the singular passages included).
# The runs: the IFToMM double four-bar (mechanisms/double_fourbar.yaml), 10 s, two samples, at the
# cheapest settings found for an error of B0(10 s) <= 1e-3, 1e-6 and 1e-10 (bench/peers_bench.cpp
# prints their errors and times: erk6 tol 3e-6, erk8 tol 3e-9, rk4 h 8e-4); the shipped scene as it
# is (101 samples, accuracy 1e-6 with its error estimate); `mo2d info` on the shipped scene.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
mo2d=$build/mo2d
scene=mechanisms/double_fourbar.yaml
command -v valgrind >/dev/null || { echo "instructions.sh: valgrind not found" >&2; exit 2; }
[[ -x $mo2d ]] || { echo "instructions.sh: $mo2d not built" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# inclusive Ir and calls of the functions whose name starts with $2, from callgrind's file $1
calls_of() { python3 scripts/callgrind_inclusive.py "$1" "$2"; }

row() {  # LABEL ARGS...: one run of build/mo2d under callgrind, one row of the table
  local label=$1
  shift
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" "$mo2d" "$@" >"$tmp/log" 2>&1 ||
    { cat "$tmp/log" >&2; echo "instructions.sh: $label failed" >&2; exit 1; }
  local total main fwd fwd_n acc acc_n per
  total=$(sed -n 's/^summary: //p' "$tmp/cg")
  read -r main _ < <(calls_of "$tmp/cg" "main")
  read -r fwd fwd_n < <(calls_of "$tmp/cg" "mo2d::forward_dynamics(")
  read -r acc acc_n < <(calls_of "$tmp/cg" "mo2d::ForwardData::accelerations(")
  per="—"
  ((acc_n > 0)) && per="$((acc / acc_n)) ($acc_n calls)"
  ((fwd_n > 0)) || fwd="—"
  printf '| %s | %s | %s | %s | %s |\n' "$label" "$total" "$main" "$fwd" "$per"
}

echo "| run | process | main | forward_dynamics | one evaluation |"
echo "|---|---|---|---|---|"
row "double four-bar, erk6 tol 3e-6 (error <= 1e-3)" forward "$scene" --integrator erk6 \
  --rtol 3e-6 --atol 3e-6 --samples 2 --out "$tmp/out"
row "double four-bar, erk8 tol 3e-9 (error <= 1e-6)" forward "$scene" --integrator erk8 \
  --rtol 3e-9 --atol 3e-9 --samples 2 --out "$tmp/out"
row "double four-bar, rk4 h 8e-4 (error <= 1e-10)" forward "$scene" --integrator rk4 \
  --step 8e-4 --samples 2 --out "$tmp/out"
row "double_fourbar.yaml as shipped" forward "$scene" --out "$tmp/out"
row "mo2d info double_fourbar.yaml" info "$scene"
