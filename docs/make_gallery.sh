#!/usr/bin/env bash
# Makes the gallery's own pictures (docs/gallery.md): each by the commands the gallery shows,
# then POV-Ray. The pictures other pages made are linked from the gallery, not made here.
#
#   docs/make_gallery.sh               # full size, into docs/images/gallery_NAME.png
#   docs/make_gallery.sh --small DIR   # 96x72, a tenth of the particles, into DIR: CI's check
#                                      # that every command still runs, renders, and is the
#                                      # one docs/gallery.md shows
#
# After the README's setup: dla3d and open_can from $DLA_BUILD (default: build/), and the bust
# made from the build's copy of CGAL's mesh ($DLA_BUST_OFF).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
build=$(realpath "${DLA_BUILD:-build}")
small=0
out=$repo/docs/images
if [ "${1:-}" = --small ]; then
  small=1
  out=$(realpath -m "${2:?--small needs the folder to write to}")
fi
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
size=(+W480 +H360 +A0.3)
[ $small = 1 ] && size=(+W96 +H72)

export PATH="$build:$PATH"
cd "$work"
dla3d convert "${DLA_BUST_OFF:-$build/data/meshes/mannequin-devil.off}" bust.stl > /dev/null

# picture NAME COMMAND...: runs the commands (a tenth of every particle count with --small),
# then renders NAME.pov into gallery_NAME.png.
picture() {
  local name=$1 command
  shift
  for command in "$@"; do
    if [ $small = 1 ]; then
      grep -qF -- "$command" "$repo/docs/gallery.md" || { echo "docs/gallery.md does not show: $command" >&2; exit 1; }
      command=$(echo "$command" | perl -pe 's/(-n |open_can )(\d+)/$1 . int($2 \/ 10)/ge')
      # A run in a mesh without -n grows 30,000.
      case $command in "dla3d --stl"*) [[ $command == *" -n "* ]] || command="$command -n 3000" ;; esac
    fi
    case $command in dla3d*) command="$command -q" ;; esac
    echo "+ $command"
    bash -euo pipefail -c "$command"
  done
  povray "${size[@]}" -D -V "$name.pov" "+O$out/gallery_$name.png" 2> "$name.log" || { cat "$name.log" >&2; exit 1; }
}

# Bourke
picture bourke_2d "dla3d -n 30000 --dimensions 2 -o bourke_2d"
picture bourke_directed "dla3d -n 20000 --spawn disk --spawn-axis x --disk-radius 0.25 -o bourke_directed"
picture bourke_can "open_can 30000 bourke_can"
picture bourke_bust "dla3d --stl bust.stl --seeds 2 --spawn radial -o bourke_bust"
picture bourke_gravity "dla3d -n 20000 --drift 0,-0.6,0 -o bourke_gravity"
picture bourke_wind "dla3d -n 20000 --drift 0.4,-0.4,0 -o bourke_wind"

# The Houdini thesis
picture wire_uniform "dla3d --stl bust.stl --seeds 2 --radius uniform --base-radius 0.4 -o wire_uniform"
picture wire_boundary "dla3d --stl bust.stl --seeds 2 --radius boundary -o wire_boundary"
# Object fill: a copy at every particle (the `sed` lines switch the copies on and make each a
# sphere). The commands are as the gallery shows them, with $objects.
export objects="--instances all --formats pov,tips --radius uniform --base-radius 0.1"
picture fill_uniform 'dla3d --stl bust.stl --seeds 2 -n 8000 $objects -o fill_uniform' \
  "sed -i 's/^#declare DLA_ShowTips = off;/#declare DLA_ShowTips = on;/; s/^  sphere { Position, min(Scale, 1.5 \\* DLA_TipRadius) }/  sphere { Position, 0.3 }/' fill_uniform.pov"
picture fill_distance "dla3d --stl bust.stl --seeds 2 -n 8000 --look blob --radius boundary --base-radius 1 --tip-radius 0.1 -o fill_distance" \
  "sed -i 's/^#declare DLA_BlobThreshold = 0.5;/#declare DLA_BlobThreshold = 0.01;/; s/^#declare DLA_BlobRadius = function(R) { .* }/#declare DLA_BlobRadius = function(R) { R }/' fill_distance.pov"
picture fill_no_overlap 'dla3d --stl bust.stl --seeds 2 -n 8000 $objects -o fill_no_overlap' \
  "sed -i 's/^#declare DLA_ShowTips = off;/#declare DLA_ShowTips = on;/; s/^  sphere { Position, min(Scale, 1.5 \\* DLA_TipRadius) }/  sphere { Position, Scale }/' fill_no_overlap.pov"
picture fill_complete 'dla3d --stl bust.stl --fill 0.9 -n 60000 $objects -o fill_complete' \
  "sed -i 's/^#declare DLA_ShowTips = off;/#declare DLA_ShowTips = on;/; s/^  sphere { Position, min(Scale, 1.5 \\* DLA_TipRadius) }/  sphere { Position, Scale }/' fill_complete.pov"

# Hyphae
picture hyphae_test4 "dla3d colonize --attractors 5000 --attractor-radius 20 --attractor-falloff 1 --roots 40 --roots-scale 1.5 --noise 0.3,4 --spacing 0.5 --radius pipe --base-radius 0.8 --tip-radius 0.2 -o hyphae_test4"

echo "made $(ls "$out"/gallery_*.png | wc -l) pictures in $out"
