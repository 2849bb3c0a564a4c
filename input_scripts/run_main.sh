#!/usr/bin/env bash
# The main job: build sable, run the example decks (measured vs analytic), then
# the comparison decks against LIGGGHTS (real when installed, else its stored
# results), printing each comparison table; figures go next to the tables.
# (The three studies join this list as their decks land.)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/.ci/install_deps.sh"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$root/build" -j"$(nproc)"
out="$root/build/main_job"
mkdir -p "$out"
cd "$root/input_scripts/examples"
for deck in collision_hertz incline_roll poured_bed; do
  echo "== $deck"
  "$root/build/sable" -in "$deck.in" -var engine sable -log "$out/$deck.log" > "$out/$deck.screen"
  grep '^RESULT' "$out/$deck.screen"
done

cd "$root"
live=liggghts-stored
command -v liggghts >/dev/null && live=liggghts
status=0
for deck in collisions_hertz collisions_hooke incline poured_bed mesh_ramp mesh_box mesh_rotating_plate mesh_moving_plate mesh_fold mesh_conveyor; do
  ref=$live
  [ "$deck" = poured_bed ] && ref=liggghts-stored  # 10 LIGGGHTS seeds take minutes: use the stored ones
  echo "== compare $deck (sable vs $ref)"
  /usr/bin/python3 reference_runs/compare.py "input_scripts/compare/$deck.in" --codes "sable,$ref" \
    --sable "$root/build/sable" --out "$out/compare" > "$out/compare_$deck.txt" 2>&1 || status=1
  grep -E '^\| |^\*\*' "$out/compare/$deck/comparison.md" || cat "$out/compare_$deck.txt"
done
echo "logs, tables (comparison.md) and figures (comparison.png) in $out"
exit $status
