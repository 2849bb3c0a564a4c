#!/bin/bash
# Issue 21's long runs in pieces: the drag deck turned in pieces (halves / resume,
# a restart file between them) gives the half-turn drags of the whole run, bit for
# bit (sable's restarts and split runs continue exactly): HALF 1 is F_first and the
# last `turns` HALF lines are the BLOCK lines. Small scene, 5 rev/s, 2 turns.
# The whole run also writes the walls' vertical loads (-var load 1, which must not
# change the run): floor + side wall + cylinder balance the weight (Newton) over the
# whole run to 1 %, where the bed's vertical momentum change is negligible; each
# half-turn within 5 %, where it is not (the stirred bed: up to 2.4 % measured).
source "$(dirname "$0")/drag_small_scene.sh"
scene="$scene -var hL 1"
"$sable" -in "$deck" $scene -var out whole -var load 1 > whole.out 2>&1 || { tail -5 whole.out; exit 1; }
"$sable" -in "$deck" $scene -var out part -var halves 1 > p0.out 2>&1 || { tail -5 p0.out; exit 1; }
"$sable" -in "$deck" $scene -var out part -var halves 3 -var resume 1 > p1.out 2>&1 || { tail -5 p1.out; exit 1; }
grep -h -E '^(RESULT|BLOCK|HALF|PIECE)' whole.out p0.out p1.out
python3 - <<'PY'
import math, re, sys
whole, parts = open('whole.out').read(), open('p0.out').read() + open('p1.out').read()
first = float(re.search(r'^RESULT F_first=(\S+)', whole, re.M).group(1))
blocks = [float(x) for x in re.findall(r'^BLOCK \d+ F=(\S+)', whole, re.M)]
halves = {int(k): float(v) for k, v in re.findall(r'^HALF (\d+) F=(\S+)', parts, re.M)}
done = [int(x) for x in re.findall(r'^PIECE done=(\d+)', parts, re.M)]
# the deck prints F_first and BLOCK with 15 significant digits, HALF with more
same = lambda a, b: abs(a - b) <= 1e-13 * abs(b)
ok = done == [1, 4] and sorted(halves) == [1, 2, 3, 4] and len(blocks) == 2 and first > 0
ok = ok and same(halves[1], first) and same(halves[3], blocks[0]) and same(halves[4], blocks[1])
print('pieces equal the whole run' if ok else 'pieces differ from the whole run')
# weight of the grains: d 1.5 mm, rho 2500 (the deck's defaults)
grains = int(re.search(r'^RESULT .* grains=(\d+)', whole, re.M).group(1))
W = grains * 2500 * math.pi * 0.0015 ** 3 / 6 * 9.81
rows = [list(map(float, l.split()[1:])) for l in open('whole_load.txt') if not l.startswith('#')]
# forces on the walls: the grains push the floor and side wall down, the cylinder up
carried = [-r[0] - r[1] - r[2] for r in rows]
bad = [c for c in carried if abs(c - W) > 0.05 * W]
mean = sum(carried) / max(len(carried), 1)
print(f'{len(rows)} half-turns of wall loads, weight {W:.5g} N; carried over the run {mean:.5g} N '
      f'({100 * (mean / W - 1):+.2f} %); half-turns off by more than 5 %: {bad}')
sys.exit(0 if ok and len(rows) == 4 and not bad and abs(mean - W) <= 0.01 * W else 1)
PY
