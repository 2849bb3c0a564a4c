#!/bin/bash
# Does a restructured exporter write the same YADE scripts? Exports every deck
# with two sable binaries and compares, per deck, the script byte for byte (or,
# where the export is refused, the error text).
#   tests/export_yade_same_script.sh OLD_SABLE NEW_SABLE [DECK_OR_DIR...]
# Default decks: tests/decks/*.in and input_scripts/**/*.in. A directory argument
# adds its *.in (e.g. decks the unit tests wrote with SABLE_KEEP_YADE_DECKS=DIR).
# Each deck is exported from its own directory (its files are relative to it).
# Files the exports write next to the decks are removed. Exit status 1 if any deck differs.
set -u
old=$(realpath "$1") new=$(realpath "$2")
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
decks=()
if [ $# -eq 0 ]; then set -- "$root"/tests/decks "$root"/input_scripts; fi
for a in "$@"; do
  if [ -d "$a" ]; then
    while IFS= read -r d; do decks+=("$d"); done < <(find "$a" -name '*.in' | sort)
  else
    decks+=("$(realpath "$a")")
  fi
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
same_script=0 same_error=0 differ=0
for deck in "${decks[@]}"; do
  dir=$(dirname "$deck") name=$(basename "$deck")
  find "$dir" -type f | sort >"$work/files.before"
  for v in old new; do
    bin=$old; [ $v = new ] && bin=$new
    # timeout: a deck that runs a long set-up (insertion) is skipped the same for both
    (cd "$dir" && timeout 60 "$bin" --export-yade "$name" -o "$work/$v.py" >"$work/$v.out" 2>"$work/$v.err")
    echo $? >"$work/$v.rc"
    [ -f "$work/$v.py" ] || : >"$work/$v.py"
  done
  if cmp -s "$work/old.rc" "$work/new.rc" && cmp -s "$work/old.py" "$work/new.py" &&
     cmp -s "$work/old.err" "$work/new.err"; then
    if [ "$(cat "$work/old.rc")" = 0 ]; then same_script=$((same_script + 1)); else same_error=$((same_error + 1)); fi
  else
    differ=$((differ + 1))
    echo "DIFFERS: $deck (rc $(cat "$work/old.rc") -> $(cat "$work/new.rc"))"
    diff "$work/old.err" "$work/new.err" | head -5
    diff "$work/old.py" "$work/new.py" | head -10
  fi
  rm -f "$work"/old.* "$work"/new.*
  # what the decks' set-up wrote next to them (restart, averages, dumps) goes
  find "$dir" -type f | sort | comm -13 "$work/files.before" - | while IFS= read -r f; do rm -f "$f"; done
done
echo "export-yade same script: ${#decks[@]} decks: $same_script scripts identical, $same_error refusals identical, $differ differ"
[ $differ -eq 0 ]
