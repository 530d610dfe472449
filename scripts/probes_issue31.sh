#!/usr/bin/env bash
# Re-run the probes that issue 31 names (items 1, 3, 4 and 5 of its "Why"), each with a time
# limit, and print per probe: the exit status, the seconds, and the last error or warning line,
# then the counts. A probe is classed by status alone: "hang" (the limit ran out: status 124),
# "crash" (a signal: status > 128), "exit0" (to be read: a refusal was expected) or "error"
# (status 1 or 2: read the message to judge it clear). Not run by CI (a few minutes: the 2,000-link
# modes probe and the sweeps start processes).
#   scripts/probes_issue31.sh [BUILD_DIR]        (default build/, a Release build with Python)
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
mo2d=$build/mo2d
scenes=mechanisms
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A count=()

probe() {  # probe NAME LIMIT_S COMMAND...
  local name=$1 limit=$2
  shift 2
  local start=$SECONDS out status class
  out=$(timeout "$limit" "$@" 2>&1 </dev/null)
  status=$?
  if ((status == 124)); then
    class=hang
  elif ((status > 128)); then
    class=crash
  elif ((status == 0)); then
    class=exit0
  else
    class=error
  fi
  count[$class]=$((${count[$class]:-0} + 1))
  printf '%-44s %-7s status %3d %3d s  %s\n' "$name" "$class" "$status" $((SECONDS - start)) \
    "$(grep -iE 'error|warning|refus' <<<"$out" | tail -1 | cut -c1-160)"
}

py=(env "PYTHONPATH=$build/python" python3 -c)  # python code run against the build's module

# a chain of n pendulum links (for the modes/linearize budgets)
chain() {
  local n=$1 f=$tmp/chain$1.yaml
  {
    echo "name: chain$n"
    echo "bodies:"
    for ((k = 0; k < n; ++k)); do
      echo "  b$k: {nodes: {A: [$k, 0], B: [$((k + 1)), 0]}, mass: 1, inertia: 0.1, com: {between: [A, B]}}"
    done
    echo "joints:"
    echo "  j0: {type: revolute, node_a: ground.A, node_b: b0.A}"
    for ((k = 1; k < n; ++k)); do
      echo "  j$k: {type: revolute, node_a: b$((k - 1)).B, node_b: b$k.A}"
    done
    echo "ground: {A: [0, 0]}"
    echo "loads: {gravity: [0, -9.81]}"

  } >"$f"
  echo "$f"
}

# item 1: budgets
probe "crosscheck --step 1e-7 --max-seconds 20" 120 \
  "$mo2d" crosscheck $scenes/slider_crank.yaml --step 1e-7 --max-seconds 20 --out "$tmp/cc1"
probe "crosscheck --step 1e-6 --max-seconds 2" 120 \
  "$mo2d" crosscheck $scenes/slider_crank.yaml --step 1e-6 --max-seconds 2 --out "$tmp/cc2"
c2000=$(chain 2000)
c500=$(chain 500)
probe "modes 2000-link chain --max-seconds 20" 120 "$mo2d" modes "$c2000" --max-seconds 20
probe "modes 500-link chain --max-seconds 5" 120 "$mo2d" modes "$c500" --max-seconds 5
probe "linearize 500-link chain --max-seconds 5" 120 "$mo2d" linearize "$c500" --max-seconds 5
# item 2: the 40-loop chain on cvode_bdf (shortened to 1 s, as the issue did)
probe "forward chain40 cvode_bdf 1 s" 300 \
  "$mo2d" forward tests/data/chain40_bdf.yaml --duration 1 --out "$tmp/c40"
# item 4: sweeps
mkdir -p "$tmp/outdir"
probe "sweep -o DIR (a folder)" 120 "$mo2d" sweep $scenes/pendulum.yaml --set m=1,2 -o "$tmp/outdir"
probe "sweep --scheduler unreachable" 120 \
  "$mo2d" sweep $scenes/pendulum.yaml --set m=1,2 --scheduler tcp://127.0.0.1:9 -o "$tmp/s1.csv"
probe "sweep grid of 1e9" 120 "$mo2d" sweep $scenes/pendulum.yaml --set m=1:2:1000000000 -o "$tmp/s2.csv"
# item 5: unclear errors
probe "linearize --at t=abc" 60 "$mo2d" linearize $scenes/double_fourbar.yaml --at t=abc
probe "modes --amplitude nan" 60 "$mo2d" modes $scenes/double_fourbar.yaml --amplitude nan
probe "--set g=1e200" 60 "$mo2d" forward $scenes/pendulum.yaml --set g=1e200 --out "$tmp/g"
probe "linearize --at t=1e300" 60 "$mo2d" linearize $scenes/double_fourbar.yaml --at t=1e300
probe "crosscheck --step nan" 60 "$mo2d" crosscheck $scenes/slider_crank.yaml --step nan --out "$tmp/cc3"
probe "python set={'L': [1, 2]}" 60 "${py[@]}" "import mo2d; mo2d.load_scene('$scenes/pendulum.yaml', set={'L': [1, 2]})"
probe "python add_body(nodes='abc')" 60 "${py[@]}" "import mo2d; mo2d.System('s').add_body('b', nodes='abc', mass=1.0)"
probe "python parse_scene(bytes)" 60 "${py[@]}" "import mo2d; s = mo2d.parse_scene(open('$scenes/pendulum.yaml', 'rb').read()); assert s.name == 'pendulum', s.name"
probe "python samples=10**12" 60 "${py[@]}" "
import mo2d
s = mo2d.System('p'); s.add_ground_node('O', (0, 0))
s.add_body('link', nodes={'O': (0, 0), 'P': (1, 0)}, mass=1.0, com='P')
s.add_revolute('pivot', 'ground.O', 'link.O', actuated=True)
s.add_coordinate('link.angle', rate=[('link.w', 1.0)])
mo2d.inverse_dynamics(mo2d.build_model(s), [('link.angle', 't')], samples=10**12)"
lock=$(find "$tmp" -name '.mo2d.lock' | wc -l)
echo "zero-byte .mo2d.lock files left in the output folders: $lock"
for c in error exit0 hang crash; do echo "$c: ${count[$c]:-0}"; done
