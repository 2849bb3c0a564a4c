#!/usr/bin/env bash
# Mohr benchmark (issue 44 item 8): input_scripts/mohr/mohr.in's loading-unloading cycles
# (mu 0.3, delta 0.5, locked rotation, Cundall damping) in sable and in YADE
# (input_scripts/mohr/mohr_yade.py, the hand translation) from the same sable packing, one
# core each, interleaved REPEATS times. Each code's particle-steps per second (its RESULT
# PS_per_s: grains x steps / wall seconds of the run, the set-up included); prints the
# medians, the ratio sable / YADE and each code's wall time for the run.
#   bash input_scripts/bench/mohr_yade.sh [SABLE] [REPEATS] [N] [CYCLES]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
deck="$here/../mohr/mohr.in"
yscript="$here/../mohr/mohr_yade.py"
sable="$(realpath "${1:-$here/../../build/sable}")"
repeats="${2:-3}"
n="${3:-500}"
cycles="${4:-2}"
work="$(mktemp -d /tmp/sable-bench-mohr.XXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
ps_of() { sed -n 's/^RESULT .* PS_per_s=\([0-9.eE+-]*\).*/\1/p' "$1"; }
s=(); y=(); ws=(); wy=()
for r in $(seq "$repeats"); do
  t0=$(date +%s.%N)
  OMP_NUM_THREADS=1 "$sable" -in "$deck" -var N "$n" -var cycles "$cycles" -var out m -log none -echo none > sable.txt
  ws+=("$(echo "$(date +%s.%N) - $t0" | bc -l)")
  s+=("$(ps_of sable.txt)")
  if command -v yade > /dev/null; then
    t0=$(date +%s.%N)
    OMP_NUM_THREADS=1 yade -j1 -n -x "$yscript" --out m --states m_states.txt --cycles "$cycles" > yade.txt 2>&1
    wy+=("$(echo "$(date +%s.%N) - $t0" | bc -l)")
    y+=("$(ps_of yade.txt)")
  fi
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
steps=$(sed -n 's/^RESULT .* steps=\([0-9]*\).*/\1/p' sable.txt)
ms=$(median "${s[@]}")
printf 'mohr N %s, %s cycles, %s steps, %s repeats: sable %.3g PS/s (%.1f s a run)' "$n" "$cycles" "$steps" \
  "$repeats" "$ms" "$(median "${ws[@]}")"
if [ ${#y[@]} -gt 0 ]; then
  my=$(median "${y[@]}")
  printf ', YADE %.3g PS/s (%.1f s a run), sable / YADE %.2f\n' "$my" "$(median "${wy[@]}")" "$(awk -v a="$ms" -v b="$my" 'BEGIN {print a / b}')"
else
  echo ' (no yade on the PATH)'
fi
