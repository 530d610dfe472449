#!/usr/bin/env bash
# Instructions of `mo2d info` on every shipped scene, split into its parts (docs/performance.md,
# "Issue 33, item 5"), by callgrind: exact and the same on a loaded machine. Slow (about half a
# minute under valgrind): not run by CI; ctest only checks that it parses.
#   scripts/startup_instructions.sh [BUILD_DIR]   (default build/; needs BUILD_DIR/mo2d, Release)
# Prints a Markdown table, one row per scene: its bytes; the instructions of the whole process and
# of main(); of yaml-cpp's YAML::Load (the YAML parse into nodes); of the rest of reading the scene
# (mo2d::load_scene without YAML::Load: the nodes' values, expressions, tables); of building the
# model (mo2d::build_scene_model); and "mo2d's part", the last two together.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
mo2d=$build/mo2d
command -v valgrind >/dev/null || { echo "startup_instructions.sh: valgrind not found" >&2; exit 2; }
[[ -x $mo2d ]] || { echo "startup_instructions.sh: $mo2d not built" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ir() { python3 scripts/callgrind_inclusive.py "$tmp/cg" "$1" | cut -d' ' -f1; }

echo "| scene | bytes | process | main | YAML::Load | rest of load_scene | build_scene_model | mo2d's part |"
echo "|---|---|---|---|---|---|---|---|"
for f in mechanisms/*.yaml; do
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" "$mo2d" info "$f" >"$tmp/log" 2>&1 ||
    { cat "$tmp/log" >&2; echo "startup_instructions.sh: $f failed" >&2; exit 1; }
  total=$(sed -n 's/^summary: //p' "$tmp/cg")
  main=$(ir "main")
  yaml=$(ir "YAML::Load(")
  load=$(ir "mo2d::load_scene(")
  build_ir=$(ir "mo2d::build_scene_model(")
  printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$(basename "$f" .yaml)" "$(wc -c <"$f")" \
    "$total" "$main" "$yaml" "$((load - yaml))" "$build_ir" "$((load - yaml + build_ir))"
done
