#!/usr/bin/env bash
# Side by side with mathsjames/fastDLA, the fastest published exact off-lattice 2D DLA: both
# grow the same count in the plane on one thread, alternating run by run, and the medians of
# wall time and peak memory are compared. fastDLA is built from its own source (GPL, not
# shipped here) with its authors' flags and -march=native.
# How to fetch it and read the result: docs/dev/performance-notes.md#side-by-side-with-fastdla.
#
#   bench/fastdla.sh [--pairs K] [--threads T] [--work-build build] FASTDLA_SOURCE COUNT...
#
# FASTDLA_SOURCE is a folder holding fastDLA.cpp and fastDLA.hpp. dla3d writes only its JSON
# record, fastDLA its binary coordinates, so the times are growth and one small write each.
set -euo pipefail
program=fastdla.sh
# shellcheck source=bench/side_by_side.sh
source "$(dirname "$0")/side_by_side.sh"

pairs=3 threads=1 work_build=
while [ $# -gt 0 ]; do
  case $1 in
    --pairs) pairs=${2:?--pairs needs a count}; shift 2 ;;
    --threads) threads=${2:?--threads needs a count}; shift 2 ;;
    --work-build) work_build=${2:?--work-build needs a folder}; shift 2 ;;
    -h|--help) usage ;;
    -*) echo "fastdla.sh: unknown option $1" >&2; usage ;;
    *) break ;;
  esac
done
[ $# -ge 2 ] || usage
source_dir=$1; shift
counts=("$@")
whole_numbers "$pairs" "$threads" "${counts[@]}"
[ "$pairs" -ge 1 ] || { echo "fastdla.sh: --pairs must be at least 1" >&2; exit 2; }
if [ ! -f "$source_dir/fastDLA.cpp" ] || [ ! -f "$source_dir/fastDLA.hpp" ]; then
  echo "fastdla.sh: $source_dir holds no fastDLA.cpp and fastDLA.hpp (git clone https://github.com/mathsjames/fastDLA)" >&2
  exit 2
fi
[ -x /usr/bin/time ] || { echo "fastdla.sh: peak memory needs /usr/bin/time (apt-get install time)" >&2; exit 2; }

repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
work_build=${work_build:-$repo/build}
runs=$(mktemp -d)
trap 'rm -rf "$runs"' EXIT

echo "building fastDLA from $source_dir (g++ -std=gnu++11 -O3 -march=native)"
g++ -std=gnu++11 -O3 -march=native -o "$runs/fastDLA" "$source_dir/fastDLA.cpp" ||
  { echo "fastdla.sh: building fastDLA failed" >&2; exit 1; }
echo "building dla3d in $work_build"
cmake --build "$work_build" --target dla3d -j"$(nproc)" > /dev/null ||
  { echo "fastdla.sh: building dla3d failed" >&2; exit 1; }

run_once() {  # NAME COMMAND... -> "seconds megabytes" on stdout
  local name=$1; shift
  /usr/bin/time -f '%e %M' -o "$runs/$name.time" "$@" > /dev/null 2> "$runs/$name.err" ||
    { echo "fastdla.sh: $name failed: $(head -c 300 "$runs/$name.err")" >&2; exit 1; }
  awk '{ printf "%.2f %.0f", $1, $2 / 1024 }' "$runs/$name.time"
}
dla3d_once() {  # COUNT SEED
  run_once dla3d "$work_build/dla3d" --dimensions 2 -n "$1" --threads "$threads" --rng-seed "$2" \
    --formats json -q -o "$runs/dla3d"
}
fastdla_once() {  # COUNT SEED
  run_once fastDLA "$runs/fastDLA" "$1" "$runs/fastDLA.bin" "$2"
}

echo "dla3d $(git -C "$repo" rev-parse --short HEAD)$(git -C "$repo" diff --quiet HEAD || echo ', with changes'), $threads thread(s), against fastDLA on one"
echo "speed-up = fastDLA's time / dla3d's; pairs alternate which runs first; seeds 1..$pairs"
summary=()
for count in "${counts[@]}"; do
  dla_times=() fast_times=() dla_mb=() fast_mb=() ratios=()
  for ((seed = 1; seed <= pairs; ++seed)); do
    if ((seed % 2)); then
      read -r td md <<< "$(dla3d_once "$count" "$seed")"
      read -r tf mf <<< "$(fastdla_once "$count" "$seed")"
    else
      read -r tf mf <<< "$(fastdla_once "$count" "$seed")"
      read -r td md <<< "$(dla3d_once "$count" "$seed")"
    fi
    ratio=$(awk -v d="$td" -v f="$tf" 'BEGIN { printf "%.2f", f / d }')
    dla_times+=("$td") fast_times+=("$tf") dla_mb+=("$md") fast_mb+=("$mf") ratios+=("$ratio")
    printf 'n=%s seed=%s: dla3d %7.2f s %6s MB   fastDLA %7.2f s %6s MB   speed-up %s\n' \
      "$count" "$seed" "$td" "$md" "$tf" "$mf" "$ratio"
  done
  summary+=("$(printf 'n=%-10s dla3d %7.2f s %6s MB   fastDLA %7.2f s %6s MB   median speed-up %.2f  (pairs: %s)' \
    "$count" "$(echo "${dla_times[*]}" | median)" "$(echo "${dla_mb[*]}" | median)" \
    "$(echo "${fast_times[*]}" | median)" "$(echo "${fast_mb[*]}" | median)" \
    "$(echo "${ratios[*]}" | median)" "${ratios[*]}")")
done
echo
echo "medians:"
printf '%s\n' "${summary[@]}"
