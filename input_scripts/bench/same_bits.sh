#!/usr/bin/env bash
# Same physics before and after a change: runs every deck of tests/decks and
# input_scripts/compare, the bench decks at their quick sizes and the cavity and
# Mohr decks at small sizes with two sable binaries, at 1 and 2 threads, and
# compares the final states (write_dump appended to each deck, every column at
# full precision) byte for byte, and the RESULT lines but their timings.
#
#   input_scripts/bench/same_bits.sh OLD_SABLE NEW_SABLE [WORK]   one line per run; exit 1 if any differ
#   SAME_BITS_ONLY=REGEX ...                                      only the decks whose name matches
set -uo pipefail
old=$(readlink -f "$1") new=$(readlink -f "$2") work=${3:-/tmp/sable_same_bits}
repo=$(cd "$(dirname "$0")/../.." && pwd)
bench=$repo/input_scripts/bench
decks=("$repo"/tests/decks/*.in "$repo"/input_scripts/compare/*.in
  "$bench/bed.in|-var nxy 5 -var nz 3 -var prep 300 -var steps 200"
  "$bench/shear_2d.in|-var nx 30 -var ny 5 -var prep 1000 -var shear0 200 -var steps 200"
  "$bench/drum.in|-var R 0.015 -var nzc 2 -var prep 500 -var steps 200"
  "$bench/drag.in|-var nl 6 -var prep 200 -var steps 100 -var stl $bench/drag_cylinder.stl"
  "$bench/box.in|-var n 8 -var nz 8 -var prep 500 -var steps 200"
  "$bench/poly.in|-var pd 0.7 -var n 3 -var nz 3 -var prep 1500 -var steps 200"
  "$repo/input_scripts/cavity/cavity.in|-var Hd 8 -var NU 1 -var NP 1 -var tshear 0.3 -var trec 0.1 -var seed 7 -var nblk 10"
  "$repo/input_scripts/mohr/mohr.in|-var N 300 -var piston 8 -var cycles 2 -var out m")
# A deck that continues another's files ("# runs-after: OTHER") runs after all the others.
later=($(grep -l '^# runs-after:' "$repo"/tests/decks/*.in))
for d in "${later[@]}"; do decks=("${decks[@]/$d/}"); done
decks=("${decks[@]}" "${later[@]}")
timing='s/ (wall_s|PS_per_s)=[^ ]*//g'

# run EXE DECK VARS DIR THREADS: the deck in DIR (its folder's data files linked in), final state to DIR/final.dump.
run() {
  local exe=$1 deck=$2 vars=$3 dir=$4 th=$5 f
  mkdir -p "$dir"
  for f in "$(dirname "$deck")"/*; do
    case $f in *.in | *.md | *.py | *.json) ;; *) [ -f "$f" ] && ln -sf "$f" "$dir/" ;; esac
  done
  { cat "$deck"; echo; echo "write_dump all custom $dir/final.dump id type x y z vx vy vz omegax omegay omegaz fx fy fz"; } > "$dir/$(basename "$deck")"
  # shellcheck disable=SC2086
  (cd "$dir" && OMP_NUM_THREADS=$th timeout 900 "$exe" -in "$(basename "$deck")" $vars > stdout 2>&1)
}

status=0
for th in 1 2; do
  rm -rf "$work/t$th"
  for spec in "${decks[@]}"; do
    [ -z "$spec" ] && continue
    deck=${spec%%|*} vars="" name=$(basename "${spec%%|*}" .in)
    [[ $spec == *"|"* ]] && vars=${spec#*|}
    [[ -n ${SAME_BITS_ONLY:-} && ! $name =~ $SAME_BITS_ONLY ]] && continue
    after=$(sed -n 's/^# runs-after: *\([A-Za-z0-9_]*\).*/\1/p' "$deck")  # continues another deck's files
    for side in old new; do
      exe=$old; [ $side = new ] && exe=$new
      run "$exe" "$deck" "$vars" "$work/t$th/${after:-$name}/$side" "$th"
      cp "$work/t$th/${after:-$name}/$side/stdout" "$work/t$th/${after:-$name}/$side/$name.stdout"
    done
    a=$work/t$th/${after:-$name}/old b=$work/t$th/${after:-$name}/new
    if ! grep -q . "$a/final.dump" 2>/dev/null; then
      echo "$name, $th thread(s): no final state ($(tail -n 1 "$a/$name.stdout" | cut -c1-200))"; status=1
    elif cmp -s "$a/final.dump" "$b/final.dump" &&
      diff -q <(grep RESULT "$a/$name.stdout" | sed -E "$timing") <(grep RESULT "$b/$name.stdout" | sed -E "$timing") > /dev/null; then
      echo "$name, $th thread(s): same bits ($(($(wc -l < "$a/final.dump") - 9)) grains, $(grep -c RESULT "$a/$name.stdout") RESULT lines)"
    else
      echo "$name, $th thread(s): DIFFERENT (see $a and $b)"; status=1
    fi
    rm -f "$a/final.dump" "$b/final.dump"
  done
done
exit $status
