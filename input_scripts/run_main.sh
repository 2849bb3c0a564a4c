#!/usr/bin/env bash
# The main job: build sable, run the example decks, print what they measured.
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
echo "logs in $out"
