#!/usr/bin/env bash
# The gallery (docs/gallery.md, docs/gallery/): every shipped scene (mechanisms/*.yaml) solved as
# its run: section says and drawn by `mo2d render` (docs/rendering.md): an animation (GIF,
# `mo2d render --animate`), the filmstrip and the main plot (the efforts of an inverse run, the
# energy balance of a forward run). The pictures are the same bytes on every run of the same build
# (tests: gallery.current, which also fails when a scene has no GIF or a GIF is over max_gif_bytes
# below). A mo2d built without FFmpeg cannot write the animations: the committed
# GIFs are then kept as they are (and not compared by --check), with a note saying so.
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

# The animation of each scene: 320 x 240 GIF at 10 frames/s with the loads drawn, real time unless
# the scene says otherwise below (a short run slowed down, a long periodic one cut to its period).
anim_size=(--width 320 --height 240 --fps 10 --loads)
anim_options() {
  case $1 in
    crank_press) echo "--slow 8" ;;
    # one turn of the cam in 63 ms: 50 times slower (3.1 s, the lift-off and the landings seen)
    cam_follower) echo "--slow 50" ;;
    # two crank turns in 0.4 s: 10 times slower
    slider_crank_clearance) echo "--slow 10" ;;
    # an engagement (a quarter of the wheel's turn) in a quarter second: 4 times slower; the first
    # 1.5 s of the 3 s run (the first engagement, the dwell and the next slot's lip hits at 1.37 s):
    # the whole run, its slots hatched, is a 365 kB GIF
    geneva) echo "--duration 1.5 --samples 151 --slow 4" ;;
    chain_drive | fourbar_design | rolling_disc | slider_crank | slider_crank_control | \
      slider_crank_friction | watt_sixbar_lengths) echo "--slow 4" ;;
    fourbar | pendulum | cam_table | gear_train | gearbox | rack_pinion | ring_disc | \
      rocking_block) echo "--slow 2" ;;
    # the crank turns ~16 times a second: a quarter second, 20 times slower
    engine) echo "--duration 0.25 --samples 251 --slow 20" ;;
    # whitworth: one turn of the crank (the run makes four); rrr3: the first half of the 8 s
    # period, a closed loop (x has a 4 s period, y and the angle come back to 0 at 4 s); the whole
    # period would be a 445 kB GIF
    rrr3 | whitworth) echo "--duration 4 --samples 126" ;;
    double_fourbar) echo "--duration 5 --samples 51" ;;
    *) echo "" ;;
  esac
}
# What anim_options says, in words for the page.
anim_words() {
  local o words="" slow=1 duration=""
  read -ra o <<<"$(anim_options "$1")"
  for ((i = 0; i < ${#o[@]}; i += 2)); do
    case ${o[i]} in --slow) slow=${o[i + 1]} ;; --duration) duration=${o[i + 1]} ;; esac
  done
  [[ -n $duration ]] && words="the first $duration s, "
  if [[ $slow == 1 ]]; then words+="real time"; else words+="$slow times slower than real time"; fi
  echo "$words"
}

# "" when this mo2d writes animations; otherwise why not (its error), and the GIFs are kept.
ffmpeg_missing=""
# The most bytes of one animation (--check fails above it): the gallery stays small.
max_gif_bytes=300000

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
    echo "efforts of an inverse-dynamics run, the energy balance of a forward run), and an animation"
    echo "(\`mo2d render --animate NAME.gif --width 320 --height 240 --fps 10 --loads\`: 10 frames/s,"
    echo "the applied loads as arrows, slowed down or cut short where the page says so)."
    echo "Written by one command, \`scripts/gallery.sh build/mo2d\` (or"
    echo "\`cmake --build build --target mo2d_gallery\`); the test \`gallery.current\` fails when"
    echo "these pictures are not the bytes it writes, or a scene has no animation, or an animation"
    echo "is over $((max_gif_bytes / 1000)) kB."
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
      if [[ -z $ffmpeg_missing ]]; then
        # shellcheck disable=SC2046 # anim_options is a list of words
        if ! "$mo2d" render "$scene" --out "$work/$stem" --animate "$work/$stem/$stem.gif" \
          "${anim_size[@]}" $(anim_options "$stem") >"$work/anim.log" 2>&1; then
          if grep -q "built without FFmpeg" "$work/anim.log"; then
            ffmpeg_missing=$(grep -o "mo2d was built without FFmpeg[^)]*)" "$work/anim.log" | head -1)
          else
            cat "$work/anim.log" >&2
            exit 1
          fi
        else
          cp "$work/$stem/$stem.gif" "$dest/gallery/$stem.gif"
        fi
      fi
      cp "$work/$stem/${name}_${plot}.png" "$dest/gallery/${stem}_${plot}.png"
      echo
      echo "## ${stem}"
      echo
      describe "$scene"
      echo
      echo "[\`mechanisms/${stem}.yaml\`](../mechanisms/${stem}.yaml): ${what}," \
        "$(sed -n 's/^mo2d render: [a-z]* dynamics of [^,]*, \(.*\)/\1/p' <<<"$log").$note"
      echo
      echo "![${stem} animation](gallery/${stem}.gif)"
      echo
      # the size of the GIF the page shows (the committed one when this mo2d cannot write it)
      local gif="$dest/gallery/$stem.gif"
      [[ -f $gif ]] || gif="$root/docs/gallery/$stem.gif"
      local kb="missing"
      [[ -f $gif ]] && kb="$((($(stat -c %s "$gif") + 500) / 1000)) kB"
      echo "*Animation: $(anim_words "$stem"), 10 frames/s, $kb.*"
      echo
      echo "![${stem} filmstrip](gallery/${stem}_filmstrip.png)"
      echo
      echo "![${stem} ${plot}](gallery/${stem}_${plot}.png)"
    done
  } >"$dest/gallery.md.tmp"
  mv "$dest/gallery.md.tmp" "$dest/gallery.md"
  rm -rf "$work"
  # an animation of a scene that is gone (kept when this mo2d cannot write animations)
  if [[ -z $ffmpeg_missing ]]; then
    for f in "$dest/gallery/"*.gif; do
      [[ -e "$f" && ! -f "$root/mechanisms/$(basename "$f" .gif).yaml" ]] && rm -f "$f"
    done
  fi
  return 0
}

if [[ $check == 0 ]]; then
  generate "$out"
  echo "gallery.sh: wrote $out/gallery.md and $(ls "$out/gallery" | wc -l) pictures in $out/gallery/"
  [[ -z $ffmpeg_missing ]] || echo "gallery.sh: note: the animations (*.gif) were not rewritten: $ffmpeg_missing"
  exit 0
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
generate "$tmp"
status=0
for f in "$tmp"/gallery.md "$tmp"/gallery/*.png "$tmp"/gallery/*.gif; do
  [[ -e "$f" ]] || continue
  rel=${f#"$tmp"/}
  if [[ ! -f "$root/docs/$rel" ]]; then echo "gallery: docs/$rel is missing"; status=1
  elif ! cmp -s "$f" "$root/docs/$rel"; then echo "gallery: docs/$rel differs from what gallery.sh writes"; status=1; fi
done
for scene in "$root"/mechanisms/*.yaml; do
  gif="docs/gallery/$(basename "$scene" .yaml).gif"
  [[ -f "$root/$gif" ]] || { echo "gallery: $gif (the animation of $(basename "$scene")) is missing"; status=1; }
done
for f in "$root"/docs/gallery/*.gif; do
  [[ -e "$f" ]] || continue
  size=$(stat -c %s "$f")
  ((size <= max_gif_bytes)) || { echo "gallery: docs/gallery/$(basename "$f") is $size bytes, more than $max_gif_bytes"; status=1; }
done
for f in "$root"/docs/gallery/*; do
  [[ -e "$f" ]] || continue
  [[ -n $ffmpeg_missing && $f == *.gif ]] && continue
  [[ -f "$tmp/gallery/$(basename "$f")" ]] || { echo "gallery: docs/gallery/$(basename "$f") is not written by gallery.sh"; status=1; }
done
if [[ $status != 0 ]]; then
  echo "gallery: regenerate with: cmake --build build --target mo2d_gallery (scripts/gallery.sh build/mo2d)"
else
  echo "gallery: docs/gallery.md and $(ls "$tmp/gallery" | wc -l) pictures are current"
fi
[[ -z $ffmpeg_missing ]] || echo "gallery: note: the animations (*.gif) were not checked: $ffmpeg_missing"

exit $status
