#!/usr/bin/env bash
# Insertion benchmark: insert_pack.in in sable and LIGGGHTS, each REPEATS times
# (interleaved), wall clock of the whole process; prints the medians and the ratio.
#   bash input_scripts/bench/insert_pack.sh [SABLE] [REPEATS]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
sable="$(realpath "${1:-$here/../../build/sable}")"
repeats="${2:-3}"
work="$(mktemp -d /tmp/sable-bench-insert.XXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
time_of() { local t0 t1; t0=$(date +%s.%N); "$@" > out.txt 2>&1 || { cat out.txt >&2; exit 1; }; t1=$(date +%s.%N); echo "$t1 - $t0" | bc -l; }
s=(); l=()
for r in $(seq "$repeats"); do
  s+=("$(OMP_NUM_THREADS=1 time_of "$sable" -in "$here/insert_pack.in" -log none)")
  grep -q "20000" out.txt || { echo "sable did not place 20000 grains"; cat out.txt; exit 1; }
  if command -v liggghts > /dev/null; then
    l+=("$(time_of liggghts -in "$here/insert_pack.in" -log none)")
    grep -q "20000" out.txt || { echo "LIGGGHTS did not place 20000 grains"; cat out.txt; exit 1; }
  fi
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
ms=$(median "${s[@]}")
printf 'insert/pack 20000 grains + 1 step, %s repeats: sable %.3f s' "$repeats" "$ms"
if [ ${#l[@]} -gt 0 ]; then ml=$(median "${l[@]}"); printf ', LIGGGHTS %.3f s, LIGGGHTS / sable %.2f\n' "$ml" "$(echo "$ml / $ms" | bc -l)"; else echo ' (no liggghts on the PATH)'; fi
