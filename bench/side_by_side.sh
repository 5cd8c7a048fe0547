# shellcheck shell=bash
# What the side-by-side scripts (bench/compare.sh, bench/fastdla.sh) share. Sourced by them
# after they set `program` to their own name.
: "${program:?set program to the name of the script that sources this}"

# The usage line from the script's header comment, then exit 2.
usage() {
  sed -n "s/^#   \(bench\/$program .*\)/usage: \1/p" "$0" >&2
  exit 2
}

# Exits 2 with one line unless every argument is a whole number.
whole_numbers() {
  local word
  for word; do
    [[ $word =~ ^[0-9]+$ ]] || { echo "$program: '$word' is not a whole number" >&2; exit 2; }
  done
}

# The median of the numbers on standard input, separated by spaces.
median() { tr ' ' '\n' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
