#!/usr/bin/env bash
# CI hook: the collision, incline, mesh-wall and group-motion comparisons, sable against real LIGGGHTS
# when `liggghts` is on PATH, else against the stored LIGGGHTS results in
# reference_runs/reference/; then the yade_* decks against YADE or its stored
# results. Exits non-zero if any judged observable fails, an observable has no
# #@ tolerance or #@ unjudged line, a line decides none, or a stored result was
# made from another deck (compare.py refuses it: sha256 of the deck's commands).
# Usage: bash reference_runs/run_ci_comparisons.sh [SABLE_BINARY]  (default build/sable)
set -u
cd "$(dirname "$0")/.."
sable=${1:-build/sable}
py=/usr/bin/python3; [ -x "$py" ] || py=python3
if command -v liggghts >/dev/null; then ref=liggghts; else
  ref=liggghts-stored
  echo "liggghts not found (apt-get install liggghts); comparing against the stored references"
fi
status=0
for deck in collisions_hertz collisions_hooke incline mesh_ramp mesh_box mesh_rotating_plate mesh_moving_plate mesh_fold mesh_conveyor move_wiggle aveforce_lid rigid_tumble rigid_lid cohesion_sjkr cohesion_sjkr2 hooke_hysteresis multisphere_pour; do
  "$py" -m sable_tools.compare "input_scripts/compare/$deck.in" --codes "sable,$ref" \
    --sable "$sable" --out build-compare > "/tmp/compare_$deck.$$.txt" 2>&1
  rc=$?
  echo "$deck: $([ $rc = 0 ] && echo pass || echo FAIL) ($(grep -h 'observables judged' "/tmp/compare_$deck.$$.txt"); build-compare/$deck/comparison.md)"
  [ $rc = 0 ] || { status=1; grep -E "FAIL|failed|^no |Error|stored reference" "/tmp/compare_$deck.$$.txt" | head -n 30; }
  rm -f "/tmp/compare_$deck.$$.txt"
done
# YADE comparisons (sable --export-yade): against YADE where installed, else its stored results.
if command -v yade >/dev/null; then yref=yade; else
  yref=yade-stored
  echo "yade not found (apt-get install yade); comparing against the stored YADE results"
fi
for deck in yade_collisions_hertz yade_linear_2d yade_wall yade_wall_avetime yade_lid_2d yade_aveforce_lid yade_lid_rigid_2d yade_rigid_tumble yade_mesh_ramp yade_mesh_paddle yade_mesh_pusher yade_periodic yade_periodic_rigid; do
  "$py" -m sable_tools.compare "input_scripts/compare/$deck.in" --codes "sable,$yref" \
    --sable "$sable" --out build-compare > "/tmp/compare_$deck.$$.txt" 2>&1
  rc=$?
  echo "$deck: $([ $rc = 0 ] && echo pass || echo FAIL) ($(grep -h 'observables judged' "/tmp/compare_$deck.$$.txt"); build-compare/$deck/comparison.md)"
  [ $rc = 0 ] || { status=1; grep -E "FAIL|failed|^no |Error|stored reference" "/tmp/compare_$deck.$$.txt" | head -n 30; }
  rm -f "/tmp/compare_$deck.$$.txt"
done
exit $status
