#!/usr/bin/env bash
# The gallery (docs/gallery.md, docs/gallery/): every shipped scene (mechanisms/*.yaml) solved as
# its run: section says and drawn by `mo2d render` (docs/rendering.md): the filmstrip and the main
# plot (the efforts of an inverse run, the energy balance of a forward run). The pictures are the
# same bytes on every run of the same build (tests: gallery.current).
#   scripts/gallery.sh MO2D [OUT]     write OUT/gallery.md and OUT/gallery/ (OUT: docs)
#   scripts/gallery.sh --check MO2D   regenerate in a temporary folder, compare with docs/ byte for
#                                     byte, name every picture that differs, is missing or is extra
# MO2D is the mo2d executable (build/mo2d). `cmake --build build --target mo2d_gallery` runs the
# first form on the build's mo2d.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

check=0
if [[ "${1:-}" == --check ]]; then check=1; shift; fi
mo2d=$(realpath "${1:?usage: gallery.sh [--check] MO2D [OUT]}")
out=${2:-$root/docs}

# The first sentence of a scene's header comment.
describe() {
  awk '/^#/ { sub(/^# ?/, ""); printf "%s ", $0; next } { exit }' "$1" |
    python3 -c 'import re,sys; t=sys.stdin.read().strip(); m=re.search(r"\.(\s+[A-Z]|$)", t); print(t[:m.start()+1] if m else t)'
}

generate() {
  local dest=$1 work
  work=$(mktemp -d)
  mkdir -p "$dest/gallery"
  rm -f "$dest/gallery/"*.png
  {
    echo "# Gallery"
    echo
    echo "Every scene shipped in \`mechanisms/\`, solved as its \`run:\` section says and drawn by"
    echo "\`mo2d render\` (\`docs/rendering.md\`): a filmstrip of the run and its main plot (the"
    echo "efforts of an inverse-dynamics run, the energy balance of a forward run). Written by one"
    echo "command, \`scripts/gallery.sh build/mo2d\` (or \`cmake --build build --target mo2d_gallery\`);"
    echo "the test \`gallery.current\` fails when these pictures are not the bytes it writes."
    for scene in "$root"/mechanisms/*.yaml; do
      local stem name log
      stem=$(basename "$scene" .yaml)
      mkdir -p "$work/$stem"
      # a fast periodic motion: tiles at evenly spaced crank angles of the last cycle, not at
      # evenly spaced times (which alias: the engine's crank turns ~24 times a second)
      local extra=() note=""
      case $stem in
        engine)
          extra=(--filmstrip-phase crank.angle --filmstrip-cycle 720deg)
          note=" Filmstrip: the last cycle of crank.angle (720°), tiles 120° apart, not evenly spaced in time." ;;
      esac
      log=$("$mo2d" render "$scene" --out "$work/$stem" "${extra[@]}")
      name=$(sed -n 's/^mo2d render: \(inverse\|forward\) dynamics of \([^,]*\),.*/\2/p' <<<"$log")
      local plot=efforts what="inverse dynamics"
      if grep -q "^mo2d render: forward" <<<"$log"; then plot=energies; what="forward dynamics"; fi
      cp "$work/$stem/${name}_filmstrip.png" "$dest/gallery/${stem}_filmstrip.png"
      cp "$work/$stem/${name}_${plot}.png" "$dest/gallery/${stem}_${plot}.png"
      echo
      echo "## ${stem}"
      echo
      describe "$scene"
      echo
      echo "[\`mechanisms/${stem}.yaml\`](../mechanisms/${stem}.yaml): ${what}," \
        "$(sed -n 's/^mo2d render: [a-z]* dynamics of [^,]*, \(.*\)/\1/p' <<<"$log").$note"
      echo
      echo "![${stem} filmstrip](gallery/${stem}_filmstrip.png)"
      echo
      echo "![${stem} ${plot}](gallery/${stem}_${plot}.png)"
    done
  } >"$dest/gallery.md.tmp"
  mv "$dest/gallery.md.tmp" "$dest/gallery.md"
  rm -rf "$work"
}

if [[ $check == 0 ]]; then
  generate "$out"
  echo "gallery.sh: wrote $out/gallery.md and $(ls "$out/gallery" | wc -l) pictures in $out/gallery/"
  exit 0
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
generate "$tmp"
status=0
for f in "$tmp"/gallery.md "$tmp"/gallery/*.png; do
  rel=${f#"$tmp"/}
  if [[ ! -f "$root/docs/$rel" ]]; then echo "gallery: docs/$rel is missing"; status=1
  elif ! cmp -s "$f" "$root/docs/$rel"; then echo "gallery: docs/$rel differs from what gallery.sh writes"; status=1; fi
done
for f in "$root"/docs/gallery/*; do
  [[ -e "$f" ]] || continue
  [[ -f "$tmp/gallery/$(basename "$f")" ]] || { echo "gallery: docs/gallery/$(basename "$f") is not written by gallery.sh"; status=1; }
done
if [[ $status != 0 ]]; then
  echo "gallery: regenerate with: cmake --build build --target mo2d_gallery (scripts/gallery.sh build/mo2d)"
else
  echo "gallery: docs/gallery.md and $(ls "$tmp/gallery" | wc -l) pictures are current"
fi
exit $status
