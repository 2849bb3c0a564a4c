# mohr_yade.py: petit2017's loading-unloading cycles (mohr.in) translated by hand to YADE,
# started from the packing sable's mohr.in wrote (sable --export-yade refuses this protocol).
#
#   yade -n -x input_scripts/mohr/mohr_yade.py --out PREFIX [--mu 0.3] [--rotation 0] [--cycles 15]
#        [--E 95.04e9] [--deps 0.01] [--thr 1e-3] [--cap 200000] [--damp cundall|restitution]
#        [--e default] [--ramp 1e-4] [--piston 15] [--thick 2] [--delta 0.5] [--dtfrac 0.02]
#        [--states FILE] [--threads 1]
#
# Parameters are command-line arguments after the script (same names and defaults as
# mohr.in's -var; run sable's deck first with the same values and the same `out`).
# Reads PREFIX_pack.dump (mohr.in's write_dump: id type radius mass x y z, %.17g; box
# periodic in x) and, when present, the first line of PREFIX_states.txt (sable's states
# header: dt, H_Rav, dy_Rav, nramp are taken from it; without it they are recomputed as
# mohr.in does, from --delta and --dtfrac). Writes PREFIX_yade_states.txt with the columns
# of sable's states file and prints STATE, PEAK and RESULT lines as mohr.in does.
#
# The translation (what sable's mohr.in does -> YADE):
# - pair_style gran model hertz tangential history, E, nu 0.08, restitution e ->
#   FrictMat(E, nu, atan(mu)), Ip2_FrictMat_FrictMat_MindlinPhys(betan = betas =
#   sqrt(5/6) beta, beta = -ln e / sqrt(ln^2 e + pi^2)), Law2_ScGeom_MindlinPhys_Mindlin
#   (sable's tools/export_yade.cpp mapping). YADE's Mindlin law clips the damped normal
#   force at 0 (sable's hertz: limitForce off, the deck's default) - a known difference.
# - dimension 2 grains disks: spheres in the x-y plane, blockedDOFs 'zXY' (+ 'Z' with
#   rotation 0); mass = the dump's mass column (disks of thickness `thick` R_av), inertia
#   1/2 m r^2 set explicitly.
# - boundary p f p: a periodic cell, W (the dump's x bounds) in x, 100 box lengths in y and
#   z (nothing meets through them).
# - pistons: grains with centre y <= piston R_av or >= ytop - piston R_av. sable moves
#   them with fix move (not fix freeze), so its contact damping uses m* = m_i m_j /
#   (m_i + m_j) with piston grains too; YADE's Mindlin law takes the dynamic grain's mass
#   when the other body is not dynamic. The piston grains here therefore stay dynamic, with
#   x, y, z, rotations about x, y blocked (their prescribed velocity is kept) and an inertia
#   of 1e30 about z (blocking every DOF would make YADE mark them non-dynamic): they move
#   at the velocity they are given and turn by nothing measurable.
# - fix move linear at vp = dy / (nramp dt) for nramp steps, then velocity 0: the same.
# - damp cundall: fix damping/cundall 0.7 on the mobile grains -> NewtonIntegrator(damping
#   = 0.7) (the piston grains have no free translation: damping does nothing to them);
#   damp restitution: NewtonIntegrator(damping = 0).
# - the relaxation ends (fix halt 100 v_relaxed > 0) when the unbalanced-force ratio < thr, or no
#   contact of a mobile grain is left, or sigma_yy < smin/100 (mohr.in's let-go rule), else after
#   `cap` steps (capped).
# - compute unbalanced/force over the mobile grains: mean |net force| of the mobile grains
#   over mean |contact force| of the contacts touching a mobile grain, computed here in
#   Python (utils.unbalancedForce() would also count the piston grains, dynamic here, and
#   the piston-piston contacts). fix halt 100: checked at steps that are multiples of 100.
# - sigma_yy, sigma_xx (force/midline), Love-Weber, Z (contacts any, rattlers < 2
#   contacts removed repeatedly), S (36 bins), overlaps, porosity: computed here from
#   O.interactions as compute contact/fabric and force/midline define them.
# Every column of sable's states file is written (none is nan).
import argparse, math, sys, time

from yade import *  # noqa: F401,F403  (O, utils, engines, Vector3, Matrix3)
from yade import utils

p = argparse.ArgumentParser(prog='mohr_yade.py')
p.add_argument('--out', default='mohr')
p.add_argument('--mu', type=float, default=0.3)
p.add_argument('--rotation', type=int, default=0, choices=[0, 1])
p.add_argument('--cycles', type=int, default=15)
p.add_argument('--E', type=float, default=95.04e9)
p.add_argument('--deps', type=float, default=0.01)
p.add_argument('--thr', type=float, default=1e-3)
p.add_argument('--cap', type=int, default=200000)
p.add_argument('--damp', default='cundall', choices=['cundall', 'restitution'])
p.add_argument('--e', default='default')
p.add_argument('--ramp', type=float, default=1e-4)
p.add_argument('--piston', type=float, default=15)
p.add_argument('--thick', type=float, default=2)
p.add_argument('--delta', type=float, default=0.5)
p.add_argument('--dtfrac', type=float, default=0.02)
p.add_argument('--states', default=None, help="sable's states file (default PREFIX_states.txt)")
p.add_argument('--threads', type=int, default=1)
args = p.parse_args(sys.argv[1:])

Rav, nu, PI = 1e-3, 0.08, math.pi
ecoef = float(args.e) if args.e != 'default' else (0.9 if args.damp == 'cundall' else 0.3)
t = args.thick * Rav
smin = 5e6 * args.E / 95.04e9

# ---- the packing
with open(args.out + '_pack.dump') as f:
    lines = f.read().splitlines()
k = lines.index('ITEM: BOX BOUNDS pp ff pp')
box = [[float(v) for v in lines[k + 1 + a].split()[:2]] for a in range(3)]
k = next(i for i, l in enumerate(lines) if l.startswith('ITEM: ATOMS'))
cols = lines[k].split()[2:]
grains = []
for l in lines[k + 1:]:
    if l.strip():
        v = dict(zip(cols, l.split()))
        grains.append((int(v['id']), float(v['radius']), float(v['mass']), float(v['x']), float(v['y'])))
# the dump's bounds have 6 digits: W as mohr.in computes it (checked against them), or the states header's
W = math.sqrt(len(grains) * math.pi * Rav ** 2 * (1 + 0.291 * args.delta ** 2) / 1.6)
if abs(W - (box[0][1] - box[0][0])) > 1e-5 * W:
    sys.exit(f'mohr_yade.py: W = {W} for N = {len(grains)}, delta = {args.delta}, the dump says {box[0][1] - box[0][0]}')
Hbox = box[1][1] - box[1][0]

# ---- the derived quantities, as mohr.in
ytop = max(g[4] for g in grains)
Yb0, Yt0 = args.piston * Rav, ytop - args.piston * Rav
H = Yt0 - Yb0
dy = args.deps * H / 2
nramp = math.ceil(dy / (args.ramp * Rav))
Rmin = Rav * (1 - args.delta)
Estar = args.E / (2 * (1 - nu ** 2))
kmin = 2 * Estar * math.sqrt(0.5 * Rmin * 0.04 * Rmin)
mmin = PI * Rmin ** 2 * 2650 * t
dt = args.dtfrac * 2 * PI * math.sqrt(0.5 * mmin / kmin)
states_file = args.states or args.out + '_states.txt'
try:
    head = open(states_file).readline()
except OSError:
    head = ''
if head.startswith('# mohr.in states:'):
    h = dict(w.split('=', 1) for w in head.split()[3:] if '=' in w)
    dt, nramp, W = float(h['dt']), int(float(h['nramp'])), float(h['W_Rav']) * Rav
    for name, mine, theirs in (('H', H, float(h['H_Rav']) * Rav), ('dy', dy, float(h['dy_Rav']) * Rav)):
        if abs(mine - theirs) > 1e-9 * abs(theirs):
            sys.exit(f'mohr_yade.py: {name} = {mine} from the dump, {theirs} in {states_file}: another packing or -var')
    H, dy = float(h['H_Rav']) * Rav, float(h['dy_Rav']) * Rav
    if int(h.get('N', len(grains))) != len(grains):
        sys.exit(f'mohr_yade.py: {len(grains)} grains in the dump, N={h["N"]} in {states_file}')
    for name, mine in (('delta', args.delta), ('mu', args.mu), ('rotation', args.rotation), ('thr', args.thr), ('E', args.E),
                       ('e', ecoef), ('thick_Rav', args.thick)):
        if name in h and abs(float(h[name]) - mine) > 1e-12 * max(1.0, abs(mine)):
            sys.exit(f'mohr_yade.py: {name} = {mine} here, {h[name]} in {states_file}')
    if h.get('damp', args.damp) != args.damp:
        sys.exit(f'mohr_yade.py: damp = {args.damp} here, {h["damp"]} in {states_file}')
vp = dy / (nramp * dt)

# ---- the scene
O.reset()
O.periodic = True
O.cell.hSize = Matrix3(W, 0, 0, 0, 100 * Hbox, 0, 0, 0, 100 * (box[2][1] - box[2][0]))
mat = O.materials.append(FrictMat(young=args.E, poisson=nu, frictionAngle=math.atan(args.mu), density=1000))
lne = math.log(ecoef)
beta = -lne / math.sqrt(lne * lne + PI * PI)
bn = MatchMaker(matches=[(0, 0, math.sqrt(5.0 / 6.0) * beta)])
bot, top, mobile = [], [], []
radius, mass = {}, {}
for (gid, r, m, x, y) in grains:
    b = utils.sphere((x, y, 0), r, material=mat)
    is_bot, is_top = y <= Yb0, y >= Yt0
    b.state.mass = m
    if is_bot or is_top:
        b.state.inertia = Vector3(1e30, 1e30, 1e30)
        b.state.blockedDOFs = 'xyzXY'
    else:
        I = 0.5 * m * r * r
        b.state.inertia = Vector3(I, I, I)
        b.state.blockedDOFs = 'zXY' + ('' if args.rotation == 1 else 'Z')
    b.state.vel, b.state.angVel = Vector3(0, 0, 0), Vector3(0, 0, 0)
    i = O.bodies.append(b)
    radius[i], mass[i] = r, m
    (bot if is_bot else top if is_top else mobile).append(i)
mob = set(mobile)
area_mobile = sum(PI * radius[i] ** 2 for i in mobile)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(avoidGranularRatcheting=False)],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(betan=bn, betas=bn)],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0.7 if args.damp == 'cundall' else 0.0, gravity=Vector3(0, 0, 0)),
]
O.dt = dt
try:
    O.numThreads = args.threads
except Exception:
    pass


# ---- measurements (on the forces of the last step)
def contacts(any_=True):
    """(i, j, force on i (x, y), l = x_i - x_j (x, y), delta/(Ri+Rj)) of the real contacts
    with a mobile grain (any_) or two (not any_)."""
    out = []
    for I in O.interactions:
        if not I.isReal:
            continue
        a, b = I.id1, I.id2
        ma, mb = a in mob, b in mob
        if not (ma or mb) or (not any_ and not (ma and mb)):
            continue
        F = I.phys.normalForce + I.phys.shearForce  # on id2; -F on id1
        n = I.geom.normal  # from id1 to id2
        s = radius[a] + radius[b]
        d = s - I.geom.penetrationDepth
        out.append((a, b, (-F[0], -F[1]), (-n[0] * d, -n[1] * d), I.geom.penetrationDepth / s))
    return out


def unbalanced():
    """compute unbalanced/force on the mobile grains."""
    net = sum(O.forces.f(i).norm() for i in mobile) / len(mobile)
    cs = contacts(True)
    if not cs:
        return math.inf
    fc = sum(math.hypot(*c[2]) for c in cs) / len(cs)
    return net / fc if fc > 0 else math.inf


def relaxed():
    """mohr.in's v_relaxed: balanced (ub < thr), or the bed has let go of the pistons (no contact of a
    mobile grain left, or sigma_yy < smin/100)."""
    return unbalanced() < args.thr or not contacts(True) or piston_syy()[0] < 0.01 * smin


def coordination(cs):
    """Z of the non-rattlers (contacts any: piston grains count as walls) and the rattler fraction."""
    alive = set(mobile)
    while True:
        deg = {}
        for (a, b, *_r) in cs:
            if (a in alive or a not in mob) and (b in alive or b not in mob):
                deg[a] = deg.get(a, 0) + 1
                deg[b] = deg.get(b, 0) + 1
        dead = [i for i in alive if deg.get(i, 0) < 2]
        if not dead:
            break
        alive.difference_update(dead)
    ends = sum(deg.get(i, 0) for i in alive)
    return (ends / len(alive) if alive else 0.0), (len(mobile) - len(alive)) / len(mobile)


def entropy(cs, nb=36):
    if not cs:
        return 0.0
    p = [0] * nb
    for c in cs:
        phi = math.atan2(c[3][0], c[3][1])
        if phi >= PI / 2:
            phi -= PI
        if phi < -PI / 2:
            phi += PI
        p[int(math.floor((phi + PI / 2) / (PI / nb) + 0.5)) % nb] += 1
    return -sum(q / len(cs) * math.log(q / len(cs)) for q in p if q)


def midline(Yb, Yt):
    """compute force/midline x W/2 ylo Yb yhi Yt on the mobile-mobile contacts (N/m)."""
    x0, s = 0.5 * W, 0.0
    for (a, b, f, l, _r) in contacts(False):
        pa = O.cell.wrap(O.bodies[a].state.pos)
        xi = (pa[0], pa[1])
        xj = (xi[0] - l[0], xi[1] - l[1])
        x = x0 + W * round((0.5 * (xi[0] + xj[0]) - x0) / W)
        iup = xi[0] >= x
        if iup == (xj[0] >= x):
            continue
        tt = (x - xi[0]) / (xj[0] - xi[0])
        y = xi[1] + tt * (xj[1] - xi[1])
        if y < Yb or y > Yt:
            continue
        s += f[0] if iup else -f[0]
    return s / (Yt - Yb)


def piston_syy():
    ft = sum(O.forces.f(i)[1] for i in top)
    fb = sum(O.forces.f(i)[1] for i in bot)
    syyt, syyb = ft / (W * t), -fb / (W * t)
    return 0.5 * (syyt + syyb), syyt, syyb


def set_piston_velocity(v):
    for i in bot:
        O.bodies[i].state.vel = Vector3(0, v, 0)
    for i in top:
        O.bodies[i].state.vel = Vector3(0, -v, 0)


# ---- the protocol (mohr.in's loop)
outname = args.out + '_yade_states.txt'
fo = open(outname, 'w')
fo.write(f'# mohr_yade.py states: N={len(grains)} mobile={len(mobile)} W_Rav={W / Rav:.17g} H_Rav={H / Rav:.17g} '
         f'dt={dt:.17g} dy_Rav={dy / Rav:.17g} nramp={nramp} mu={args.mu:g} rotation={args.rotation} '
         f'delta={args.delta:g} damp={args.damp} e={ecoef:g} thr={args.thr:g} E={args.E:g} thick_Rav={args.thick:g} '
         '\n')
fo.write('cycle state loading eps syy syy_top syy_bot sxx sxx_lw syy_lw sxy_lw Z Z_both rattlers porosity S '
         'dmean dmax ub steps capped\n')
fo.flush()
t0 = time.time()
Yb, Yt, eps = Yb0, Yt0, 0.0
states = capped = steps = 0
muM1 = muM = C = K0 = Zpk = porpk = Spk = math.nan
for cyc in range(1, args.cycles + 1):
    n = Sc = Sr = Scc = Scr = 0.0
    sgn, ld = 1, 1
    syyp = sxxp = 0.0
    epsp = -1.0
    while True:
        set_piston_velocity(sgn * vp)
        O.run(nramp, True)
        set_piston_velocity(0.0)
        Yb += sgn * dy
        Yt -= sgn * dy
        eps += sgn * 2 * dy / H
        s0 = O.iter
        ub = math.inf
        while O.iter - s0 < args.cap:  # fix halt 100 v_ub < thr: checked at steps divisible by 100
            nxt = min((O.iter // 100 + 1) * 100, s0 + args.cap)
            O.run(nxt - O.iter, True)
            if O.iter % 100 == 0 and relaxed():
                break
        ds = O.iter - s0
        ub = unbalanced()
        cp = 0 if relaxed() else 1
        capped += cp
        steps += ds + nramp
        states += 1
        syy, syyt, syyb = piston_syy()
        sxx = midline(Yb, Yt) / t
        Hc = Yt - Yb
        A = W * Hc
        cs = contacts(True)
        lw = [sum(c[2][a] * c[3][b] for c in cs) / A / t for (a, b) in ((0, 0), (1, 1), (0, 1))]
        Z, ratt = coordination(cs)
        Zb, _ = coordination(contacts(False))
        S = entropy(cs)
        dmean = sum(c[4] for c in cs) / len(cs) if cs else 0.0
        dmax = max((c[4] for c in cs), default=0.0)
        por = 1 - area_mobile / A
        fo.write(f'{cyc} {states} {ld} {eps:.10g} {syy:.10g} {syyt:.10g} {syyb:.10g} {sxx:.10g} {lw[0]:.10g} '
                 f'{lw[1]:.10g} {lw[2]:.10g} {Z:.6g} {Zb:.6g} {ratt:.6g} {por:.8g} {S:.8g} {dmean:.6g} {dmax:.6g} '
                 f'{ub:.4g} {ds} {cp}\n')
        fo.flush()
        print(f'STATE cycle {cyc} state {states} eps {eps:.4f} syy {syy / 1e6:.3f} MPa sxx {sxx / 1e6:.3f} MPa '
              f'steps {ds} ub {ub:.3g}', flush=True)
        if ld == 0:
            if syy >= smin and eps > 1e-9:
                continue
            break
        c, r = 0.5 * (syy + sxx), 0.5 * (syy - sxx)
        n += 1
        Sc, Sr, Scc, Scr = Sc + c, Sr + r, Scc + c * c, Scr + c * r
        if n >= 2:
            K = (syy - syyp + 2 * (sxx - sxxp)) / (3 * (eps - epsp))
            if n == 2:
                K0 = K
        syyp, sxxp, epsp = syy, sxx, eps
        if eps < 0.15 - 1e-9:
            continue
        b = (n * Scr - Sc * Sr) / (n * Scc - Sc * Sc)
        muM = b / math.sqrt(1 - b * b)
        C = (Sr - b * Sc) / n / math.sqrt(1 - b * b)
        if cyc == 1:
            muM1 = muM
        Zpk, porpk, Spk = Z, por, S
        print(f'PEAK cycle {cyc} muM {muM:.4f} C {C / 1e6:.3f} MPa Z {Zpk:.3f} porosity {porpk:.4f} S {Spk:.4f}',
              flush=True)
        sgn, ld = -1, 0
fo.close()
wall = time.time() - t0
print(f'RESULT muM={muM1:.6g} muM_last={muM:.6g} C={C:.6g} K0={K0:.6g} Z={Zpk:.5g} porosity={porpk:.6g} '
      f'S={Spk:.6g} cycles={args.cycles} states={states} capped={capped} steps={steps} '
      f'PS_per_s={len(grains) * steps / wall:.4g}', flush=True)
print(f'wrote {outname}')
