#!/usr/bin/env bash
# Cavity benchmark (issue 43 item 6): the shear of input_scripts/cavity/cavity.in at H/d 12,
# one core, recording on (10 kHz series, ten slices, every grain-wall contact row; the
# coarse-grained fields off, as YADE has no translation of them), in sable and in YADE from
# the same sable deposit, interleaved REPEATS times. Each code's particle-steps per second
# of the shear run (the deck's PS_per_s: atoms x steps / CPU seconds of the run, $(cpu)
# snapshots in both codes); prints the medians and the ratio sable / YADE.
#   bash input_scripts/bench/cavity_yade.sh [SABLE] [REPEATS] [NU]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
deck="$here/../cavity/cavity.in"
sable="$(realpath "${1:-$here/../../build/sable}")"
repeats="${2:-3}"
nu="${3:-10}"
work="$(mktemp -d /tmp/sable-bench-cavity.XXXX)"
trap 'rm -rf "$work"' EXIT
cd "$work"
vars=(-var Hd 12 -var NU "$nu" -var NP 1 -var seed 5 -var tshear 0.15 -var trec 0.05 -var fields 0 -var contacts 1)
OMP_NUM_THREADS=1 "$sable" -in "$deck" "${vars[@]}" -var phase deposit -var restart dep.restart -log none -echo none > dep.txt
"$sable" --export-yade "$deck" "${vars[@]}" -var phase shear -var restart dep.restart -var out yade -o shear.py > export.txt
ps_of() { sed -n 's/^RESULT F_PLd=.* PS_per_s=\([0-9.eE+-]*\).*/\1/p' "$1"; }
s=(); y=()
for r in $(seq "$repeats"); do
  OMP_NUM_THREADS=1 "$sable" -in "$deck" "${vars[@]}" -var phase shear -var restart dep.restart -var out sable \
    -log none -echo none > sable.txt
  s+=("$(ps_of sable.txt)")
  if command -v yade > /dev/null; then
    OMP_NUM_THREADS=1 yade -j1 -n -x shear.py > yade.txt 2>&1
    y+=("$(ps_of yade.txt)")
  fi
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
steps=$(sed -n 's/^RESULT .* steps=\([0-9]*\).*/\1/p' sable.txt)
atoms=$(sed -n 's/^RESULT .* atoms=\([0-9]*\).*/\1/p' sable.txt)
ms=$(median "${s[@]}")
printf 'cavity shear H/d 12, N_U %s, %s atoms x %s steps, recording on, %s repeats: sable %.3g PS/s' \
  "$nu" "$atoms" "$steps" "$repeats" "$ms"
if [ ${#y[@]} -gt 0 ]; then
  my=$(median "${y[@]}")
  printf ', YADE %.3g PS/s, sable / YADE %.2f\n' "$my" "$(echo "$ms / $my" | bc -l)"
else
  echo ' (no yade on the PATH)'
fi
