#!/usr/bin/env bash
# The cross-check's convergence study for springs, friction and state-dependent loads
# (docs/crosscheck.md, "Loads: first order too"): mo2d crosscheck of five shipped scenes at Box2D
# steps 1/1000 ... 1/8000 s, the error read from its report, a table (CSV) and its log-log plot by
# mo2d's renderer (mo2d plot --log-x --log-y), with a first-order line for reference.
#   scripts/crosscheck_convergence.sh [BUILD_DIR=build] [OUT_DIR=docs/img]
# Forward scenes: the largest body angle error over the horizon (rad); the inverse friction scene:
# the crank torque's RMS error over its peak. A refused run (the step too coarse for the scene) is
# "nan", a gap in the plot.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
out=${2:-docs/img}
mo2d="${build}/mo2d"
work=$(mktemp -d)
trap 'rm -rf "${work}"' EXIT

# scene, horizon (s), extra flags
scenes=(
  "sprung_double_pendulum 1 --samples 21"
  "door 1 --samples 21"
  "rack_pinion 2 --samples 21"
  "engine 0.15 --samples 16"
  "slider_crank_friction 1"
)
steps=(0.001 0.0005 0.00025 0.000125 0.0000625 0.00003125)

# the error of one run: forward "body angle error: max X rad", inverse the effort's rms/peak
error_of() {
  awk '/body angle error:/ { print $5; found = 1; exit }
       /^  effort / { print $4; found = 1; exit }
       END { if (!found) print "nan" }' "$1"
}

header="h"
for s in "${scenes[@]}"; do header+=",${s%% *}"; done
table="${work}/table.csv"
echo "${header},first_order" >"${table}"
units="s"  # the units row (mo2d plot puts them in the axis label or the legend)
for s in "${scenes[@]}"; do
  [[ "${s}" == slider_crank_friction* ]] && units+=",RMS/peak" || units+=",rad"
done
echo "${units},rad" >>"${table}"
for h in "${steps[@]}"; do
  row="${h}"
  for s in "${scenes[@]}"; do
    read -r name horizon flags <<<"${s}"
    log="${work}/${name}_${h}.txt"
    # shellcheck disable=SC2086
    "${mo2d}" crosscheck "mechanisms/${name}.yaml" --step "${h}" --duration "${horizon}" ${flags} \
      --out "${work}/${name}_${h}" >"${log}" 2>&1 || true
    row+=",$(error_of "${log}")"
  done
  row+=",$(awk -v h="${h}" 'BEGIN { printf "%.3g", 4 * h }')"  # 4 h: slope 1
  echo "${row}" | tee -a /dev/stderr >>"${table}"
done

mkdir -p "${out}"
cp "${table}" "${out}/crosscheck_convergence.csv"
columns=$(head -1 "${table}" | cut -d, -f2- | tr , ' ')
# shellcheck disable=SC2086
"${mo2d}" plot "${table}" ${columns} --x h --log-x --log-y --markers \
  --title "Box2D against mo2d: error against Box2D's step (first order: halves with h)" \
  -o "${out}/crosscheck_convergence.png"
