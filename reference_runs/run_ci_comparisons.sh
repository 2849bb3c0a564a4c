#!/usr/bin/env bash
# CI hook: the collision, incline, mesh-wall and group-motion comparisons, sable against real LIGGGHTS
# when `liggghts` is on PATH, else against the stored LIGGGHTS results in
# reference_runs/reference/; then the yade_* decks against YADE or its stored
# results. Exits non-zero if any judged observable fails, an observable has no
# #@ tolerance or #@ unjudged line, a line decides none, or a stored result was
# made from another deck (compare.py refuses it: sha256 of the deck's commands).
# Usage: bash reference_runs/run_ci_comparisons.sh [SABLE_BINARY [DECK...]]  (default build/sable, every deck)
#        bash reference_runs/run_ci_comparisons.sh --list   the decks, one per line (ctest runs one test each)
set -u
cd "$(dirname "$0")/.."
liggghts_decks="collisions_hertz collisions_hooke incline mesh_ramp mesh_box mesh_rotating_plate mesh_moving_plate
  mesh_fold mesh_conveyor move_wiggle aveforce_lid rigid_tumble rigid_lid cohesion_sjkr cohesion_sjkr2 hooke_hysteresis
  multisphere_pour"
yade_decks="yade_collisions_hertz yade_linear_2d yade_wall yade_wall_avetime yade_lid_2d yade_aveforce_lid
  yade_lid_rigid_2d yade_rigid_tumble yade_mesh_ramp yade_mesh_paddle yade_mesh_pusher yade_periodic yade_periodic_rigid"
if [ "${1:-}" = --list ]; then printf '%s\n' $liggghts_decks $yade_decks; exit 0; fi
sable=${1:-build/sable}
shift $(($# > 0 ? 1 : 0))
wanted=" $(echo ${*:-$liggghts_decks $yade_decks}) "
py=/usr/bin/python3; [ -x "$py" ] || py=python3
# Real LIGGGHTS and YADE where installed (the yade_* decks through sable --export-yade), else their stored results.
ref=liggghts; command -v liggghts > /dev/null || ref=liggghts-stored
yref=yade; command -v yade > /dev/null || yref=yade-stored

status=0 ran=0
compare() {  # compare DECK REF
  local deck=$1 out="/tmp/compare_$1.$$.txt" rc
  ran=$((ran + 1))
  "$py" -m sable_tools.compare "input_scripts/compare/$deck.in" --codes "sable,$2" \
    --sable "$sable" --out build-compare > "$out" 2>&1
  rc=$?
  echo "$deck ($2): $([ $rc = 0 ] && echo pass || echo FAIL) ($(grep -h 'observables judged' "$out"); build-compare/$deck/comparison.md)"
  [ $rc = 0 ] || { status=1; grep -E "FAIL|failed|^no |Error|stored reference" "$out" | head -n 30; }
  rm -f "$out"
}
for deck in $liggghts_decks; do [[ $wanted == *" $deck "* ]] && compare "$deck" "$ref"; done
for deck in $yade_decks; do [[ $wanted == *" $deck "* ]] && compare "$deck" "$yref"; done
[ $ran -gt 0 ] || { echo "no comparison deck named:$wanted(see --list)"; exit 2; }
exit $status
