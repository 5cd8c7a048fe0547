#!/usr/bin/env bash
# Side-by-side speed guard: DLA grown by the dla3d of commit BASE and by the working tree's,
# alternating run by run with the same seeds, and whether the two wrote the same files.
# How to use it and read it: docs/dev/performance-notes.md#the-side-by-side-guard.
#
#   bench/compare.sh [--pairs K] [--seeds 5,7] [--dims 3,2] [--threads 1,2] [--work-build build] BASE [COUNT...]
#
# The working tree's dla3d is built in its build folder (the README's, build/, by default); the
# base's beside the working tree, in ../<repo>-compare/<commit>/ (or under $DLA_COMPARE_DIR),
# with the same flags, once, and kept for the next call.
set -euo pipefail
program=compare.sh
# shellcheck source=bench/side_by_side.sh
source "$(dirname "$0")/side_by_side.sh"

pairs=3 seeds=5,7 dims=3,2 threads=1,2 work_build=
while [ $# -gt 0 ]; do
  case $1 in
    --pairs) pairs=${2:?--pairs needs a count}; shift 2 ;;
    --seeds) seeds=${2:?--seeds needs a comma list}; shift 2 ;;
    --dims) dims=${2:?--dims needs a comma list}; shift 2 ;;
    --threads) threads=${2:?--threads needs a comma list}; shift 2 ;;
    --work-build) work_build=${2:?--work-build needs a folder}; shift 2 ;;
    -h|--help) usage ;;
    -*) echo "compare.sh: unknown option $1" >&2; usage ;;
    *) break ;;
  esac
done
[ $# -ge 1 ] || usage
base_ref=$1; shift
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(100000 1000000)
# shellcheck disable=SC2086  # the comma lists split into words
whole_numbers "$pairs" ${seeds//,/ } ${dims//,/ } ${threads//,/ } "${counts[@]}"
[ "$pairs" -ge 1 ] || { echo "compare.sh: --pairs must be at least 1" >&2; exit 2; }

repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
base=$(git -C "$repo" rev-parse --verify --quiet "$base_ref^{commit}") ||
  { echo "compare.sh: '$base_ref' is not a commit of $repo" >&2; exit 2; }
work_build=${work_build:-$repo/build}
root=${DLA_COMPARE_DIR:-$(dirname "$repo")/$(basename "$repo")-compare}
mkdir -p "$root"
runs=$(mktemp -d)
trap 'rm -rf "$runs"' EXIT

# The base is built with the flags of the working tree's build (the README's: Release, with the
# Python module's position-independent code), only dla3d, and without the web viewer (npm).
cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$work_build/CMakeCache.txt"; }
if [ ! -f "$work_build/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$work_build" -DCMAKE_BUILD_TYPE=Release > /dev/null ||
    { echo "compare.sh: configuring $work_build failed" >&2; exit 1; }
fi
[ "$(cache_value CMAKE_BUILD_TYPE)" = Release ] && [ "$(cache_value DLA_SANITIZE)" != ON ] &&
  [ "$(cache_value DLA_TSAN)" != ON ] ||
  { echo "compare.sh: $work_build is not a plain Release build; give one with --work-build" >&2; exit 2; }
python_flag=$(cache_value DLA_BUILD_PYTHON)

short=${base:0:7}
if [ ! -x "$root/$short/build/dla3d" ]; then
  echo "building $short in $root/$short (once; kept for the next call)"
  rm -rf "$root/$short"
  mkdir -p "$root/$short/source"
  git -C "$repo" archive "$base" | tar -x -C "$root/$short/source"
  cmake -S "$root/$short/source" -B "$root/$short/build" -DCMAKE_BUILD_TYPE=Release -DDLA_BUILD_TESTS=OFF \
    -DDLA_BUILD_BENCH=OFF -DDLA_BUILD_EXAMPLES=OFF -DDLA_BUILD_PYTHON="${python_flag:-ON}" -DDLA_WEB_VIEWER=OFF \
    > "$root/$short/build.log" 2>&1 &&
    cmake --build "$root/$short/build" --target dla3d -j"$(nproc)" >> "$root/$short/build.log" 2>&1 ||
    { echo "compare.sh: building $short failed; see $root/$short/build.log" >&2; rm -rf "$root/$short/build"; exit 1; }
fi
echo "building the working tree's dla3d in $work_build"
cmake --build "$work_build" --target dla3d -j"$(nproc)" > /dev/null ||
  { echo "compare.sh: building the working tree failed" >&2; exit 1; }
base_bin=$root/$short/build/dla3d
work_bin=$work_build/dla3d

run_once() {  # BINARY PREFIX COUNT DIMS THREADS SEED -> seconds on stdout
  local start=$EPOCHREALTIME
  "$1" -n "$3" --dimensions "$4" --threads "$5" --rng-seed "$6" --formats csv -q -o "$2" > /dev/null 2> "$2.err" ||
    { echo "compare.sh: $1 failed: $(head -c 300 "$2.err")" >&2; exit 1; }
  awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }'
}

# A verdict only where the pairs agree: all but one pair on one side of 1, and the median
# ratio beyond 3%.
verdict() {  # MEDIAN RATIOS...
  local m=$1; shift
  awk -v m="$m" -v list="$*" 'BEGIN {
    n = split(list, r, " "); above = 0; below = 0
    for (i = 1; i <= n; ++i) { if (r[i] > 1) ++above; if (r[i] < 1) ++below }
    if (m > 1.03 && above >= n - 1) print "slower"
    else if (m < 0.97 && below >= n - 1) print "faster"
    else print "level" }'
}

echo "base $short ($base_bin) against the working tree ($(git -C "$repo" rev-parse --short HEAD)$(git -C "$repo" diff --quiet HEAD || echo ', with changes'))"
echo "ratio = working tree / base, whole process wall time; pairs alternate which build runs first"
summary=()
same_files=yes
for count in "${counts[@]}"; do
  for d in ${dims//,/ }; do
    for t in ${threads//,/ }; do
      base_times=() work_times=() ratios=() differ=0
      pair=0
      for s in ${seeds//,/ }; do
        for ((k = 0; k < pairs; ++k)); do
          pair=$((pair + 1))
          if ((pair % 2)); then
            tb=$(run_once "$base_bin" "$runs/base" "$count" "$d" "$t" "$s")
            tw=$(run_once "$work_bin" "$runs/work" "$count" "$d" "$t" "$s")
          else
            tw=$(run_once "$work_bin" "$runs/work" "$count" "$d" "$t" "$s")
            tb=$(run_once "$base_bin" "$runs/base" "$count" "$d" "$t" "$s")
          fi
          cmp -s "$runs/base.csv" "$runs/work.csv" || differ=$((differ + 1))
          ratio=$(awk -v w="$tw" -v b="$tb" 'BEGIN { printf "%.3f", w / b }')
          base_times+=("$tb") work_times+=("$tw") ratios+=("$ratio")
          printf '%sD n=%s threads=%s seed=%s: base %6.2f s  work %6.2f s  ratio %s\n' "$d" "$count" "$t" "$s" "$tb" "$tw" "$ratio"
        done
      done
      files=same
      if ((differ)); then files="DIFFER in $differ of $pair pairs"; same_files=no; fi
      median_ratio=$(echo "${ratios[*]}" | median)
      summary+=("$(printf '%sD n=%-8s threads=%s  base %7.2f s  work %7.2f s  median ratio %.3f  %-6s  pairs: %s  files: %s' \
        "$d" "$count" "$t" "$(echo "${base_times[*]}" | median)" "$(echo "${work_times[*]}" | median)" \
        "$median_ratio" "$(verdict "$median_ratio" "${ratios[@]}")" "${ratios[*]}" "$files")")
    done
  done
done
echo
echo "medians (base $short, working tree), verdict where the pairs agree:"
printf '%s\n' "${summary[@]}"
if [ "$same_files" = yes ]; then echo "the two builds wrote the same CSV files in every pair"
else echo "the two builds wrote DIFFERENT CSV files: the runs do not compare the same walks"; fi
