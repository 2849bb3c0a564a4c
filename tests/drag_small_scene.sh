# Sourced by the drag deck's tests: a fresh work folder, the small scene's cylinder and its
# variables (Wd 10, Ld 4, Dd 2, 5 rev/s, 2 turns). Sets sable, src, deck and scene from the
# test's arguments (SABLE SRC WORKDIR).
set -u
sable=$1; src=$2; work=$3
rm -rf "$work"; mkdir -p "$work" && cd "$work" || exit 1
PYTHONPATH="$src" python3 -m sable_tools.drag.make_cylinder_stl 0.003 0.006 cyl.stl > /dev/null || exit 1
scene="-var Wd 10 -var Ld 4 -var Dd 2 -var zcL 1 -var period 0.2 -var turns 2 -var settle 0.05 -var stl cyl.stl -log none -echo none"
deck="$src/input_scripts/drag/drag.in"
