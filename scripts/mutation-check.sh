#!/usr/bin/env bash
# Mutation check: apply deliberate bugs to a copy of the sources, rebuild, run the test suite and
# list which tests catch each one. A mutation that no test catches is a hole in the suite.
# Usage: scripts/mutation-check.sh [WORKDIR [FILTER]]   (default /tmp/mo2d-mutations; FILTER: an
# extended regular expression: only the mutations whose name matches it)
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
work=${1:-/tmp/mo2d-mutations}
filter=${2:-}
# a fresh copy and a fresh build every time: tar restores the sources' old mtimes, so a build
# directory kept from an earlier run would reuse objects compiled from mutated sources
rm -rf "$work"
mkdir -p "$work/src-copy"
(cd "$src" && tar --exclude='./build*' --exclude=./out --exclude=./.git -cf - .) | tar -xf - -C "$work/src-copy"
cd "$work/src-copy"
cmake -S . -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DMO2D_BUILD_BENCH=OFF >/dev/null
cmake --build "$work/build" -j"$(nproc)" --target mo2d_tests >/dev/null

# name | file | sed expression
mutations=(
  "actuator sign flipped|src/model/rows.cpp|s/std::pair{body2, 1.0}, std::pair{body1, -1.0}/std::pair{body2, -1.0}, std::pair{body1, 1.0}/"
  "centre of mass moved (gamma + 0.1)|src/model/validate.cpp|s/b.gamma = com.gamma;/b.gamma = com.gamma + 0.1;/"
  "centre of mass at the other node|src/model/validate.cpp|s/b.ci = com_node(d, com.node_i);\$/b.ci = com_node(d, com.node_i); if (n >= 2) b.ci = n - 1 - b.ci;/"
  "inertia +5 %|src/dynamics/dynamics.cpp|s/l\[b.slots() - 1\] = b.inertia \*/l[b.slots() - 1] = 1.05 * b.inertia */"
  "gravity sign flipped|src/dynamics/dynamics.cpp|s/b.mass \* m.gravity/-b.mass * m.gravity/"
  "rigid-body acceleration bias sign|src/constraints/rigid.hpp|s/const Vec2 e = w \* perp(node_velocity/const Vec2 e = -w * perp(node_velocity/"
  "slider acceleration bias dropped|src/constraints/prismatic_slot.hpp|s/const Vec2 e = (2 \* q1\[c.q\]/const Vec2 e = (0 * q1[c.q]/"
  "reaction split sign|src/dynamics/reactions.cpp|s/F\[i\] = -local\[base + i\];/F[i] = local[base + i];/"
  # a body point evaluated with the wrong helper (trust issue, item 1): positions through the
  # velocity helper, which puts a node joined to the ground at the origin
  "spring point position through the velocity helper|src/dynamics/dynamics.cpp|s/return {local_position_of_point(b, q0, bp.ci/return {local_velocity_of_point(b, q0, bp.ci/"
  "centre of mass position through the velocity helper|src/model/model.cpp|s/const Vec2 d = node_position(b.nodes\[b.cj\], q0) - pi;/const Vec2 d = node_velocity(b.nodes[b.cj], q0) - pi;/"
  # a load's work left out of the energy balance (trust issue, item 6)
  "load work left out of the energy balance|src/forward/recorder.cpp|s/rates\[kLoadWork\] = load_power(d.m, q0, q1, t);/rates[kLoadWork] = 0;/"
  "damper dissipation left out of the energy balance|src/forward/recorder.cpp|s/rates\[kDissipated\] = damping_power(d.m, q0, q1);/rates[kDissipated] = 0;/"
  "spring tension sign (on its first point)|src/dynamics/dynamics.cpp|s/s.a.rho, T \* st.e,/s.a.rho, -T * st.e,/"
)
status=0
for entry in "${mutations[@]}"; do
  IFS='|' read -r name file expr <<<"$entry"
  if [[ -n "$filter" ]] && ! grep -Eq -- "$filter" <<<"$name"; then continue; fi
  cp "$file" "$file.orig"
  sed -i "$expr" "$file"
  if cmp -s "$file" "$file.orig"; then
    echo "MUTATION NOT APPLIED: $name ($file)"; status=1; mv "$file.orig" "$file"; touch "$file"; continue
  fi
  if ! cmake --build "$work/build" -j"$(nproc)" --target mo2d_tests >/dev/null 2>&1; then
    echo "[$name] does not compile"; mv "$file.orig" "$file"; touch "$file"; continue
  fi
  # the metamorphic suite on 40 generated mechanisms (as in the sanitizer build), not 300: under a
  # mutation most replays run to their step budgets and 300 mechanisms take over 40 minutes
  failed=$( { MO2D_META_COUNT=${MO2D_META_COUNT:-40} "$work/build/tests/mo2d_tests" --gtest_brief=1 2>&1 || true; } | sed -n 's/^\[  FAILED  \] \([A-Za-z0-9_.]*\).*/\1/p' | sort -u | tr '\n' ' ')
  if [ -z "$failed" ]; then
    echo "[$name] NOT CAUGHT"; status=1
  else
    echo "[$name] caught by: $failed"
  fi
  # restore, and make it newer than its object file so that the next build drops the mutation
  mv "$file.orig" "$file"
  touch "$file"
done
exit $status
