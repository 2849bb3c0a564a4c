#!/bin/bash
# The drag deck's side-wall friction (-var muside): a frictionless vertical wall can
# only push horizontally, so with muside 0 the side wall carries none of the bed's
# weight (its vertical force is zero in every half-turn of the rotation) and floor +
# cylinder carry it all; with the default (the beads' friction) the
# same scene's side wall carries a share, so the check can fail. Small scene, 5 rev/s:
# the bed's momentum change within a half-turn leaves up to ~1.5 % off the weight (3 % allowed).
source "$(dirname "$0")/drag_small_scene.sh"
scene="$scene -var hL 1.5 -var load 1"
"$sable" -in "$deck" $scene -var out rough > rough.out 2>&1 || { tail -5 rough.out; exit 1; }
"$sable" -in "$deck" $scene -var out smooth -var muside 0 > smooth.out 2>&1 || { tail -5 smooth.out; exit 1; }
grep -h '^RESULT' rough.out smooth.out
python3 - <<'PY'
import math, re, sys
def loads(name):
    grains = int(re.search(r'^RESULT .* grains=(\d+)', open(name + '.out').read(), re.M).group(1))
    W = grains * 2500 * math.pi * 0.0015 ** 3 / 6 * 9.81  # the deck's d and rho
    return W, [list(map(float, l.split()[1:])) for l in open(name + '_load.txt') if not l.startswith('#')]
W, rough = loads('rough')
Ws, smooth = loads('smooth')
side_rough = max(abs(r[1]) for r in rough) / W
side_smooth = max(abs(r[1]) for r in smooth) / Ws
balance = max(abs(-r[0] - r[2] - Ws) for r in smooth) / Ws
print(f'side wall share of the weight, largest half-turn: friction as the beads {side_rough:.3g}, '
      f'muside 0 {side_smooth:.3g}; floor + cylinder against the weight with muside 0: {balance:.3g}')
ok = len(rough) == len(smooth) == 4 and side_rough > 1e-3 and side_smooth < 1e-12 and balance < 0.03
sys.exit(0 if ok else 1)
PY
