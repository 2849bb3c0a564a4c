"""The Mohr sweep's reduction: per point mean +- seed SE, PLAN.md's tests, REPORT.md,
points.csv and the figures (called by `mohr.py reduce`)."""
import csv
import datetime
import glob
import json
import math
import os

from sable_tools import seedstats as S  # statistics over seeds, one module for every study (its tests: exceeds, within, differs)
from sable_tools.readers.yade import read_states  # the states files of both codes
from sable_tools.readers import dump  # the peaks' contact rows (dump local)

SE_DIFF = 2.0      # "different": |d| > 2 combined SE
Z_EQ = 1.645       # one-sided 5 % for the equivalence and "consistent" tests


def mean_se(xs):
    """(mean, seed-to-seed SE, n) of the seeds' values, nan dropped: seedstats.summary (SE nan for one seed)."""
    s = S.summary(xs)
    return s.mean, s.se, s.n


def load(root):
    pts = {}
    for f in sorted(glob.glob(os.path.join(root, "runs", "*", "s*", "result.json"))):
        name = os.path.basename(os.path.dirname(os.path.dirname(f)))
        with open(f) as fh:
            pts.setdefault(name, []).append(json.load(fh))
    return pts


KEYS = ["mu_M_first", "mu_M_last", "mu_M_last3", "K_peak", "K0", "alpha", "Z_peak", "porosity_peak", "S_peak",
        "dmax_peak", "Z_end", "porosity_end", "Z_initial", "porosity_initial", "S_initial", "Z_first_peak", "phi_min_c1_deg", "phi_min_last_deg", "capped", "wall_s"]
TABLE2 = {0.1: (22.9, 25.7), 0.3: (31.5, 45.8), 0.5: (39.5, 48.7), 1.0: (39.5, 42.9)}  # petit2017 Table II, -deg


def stats(runs):
    out = {k: mean_se([r.get(k, float("nan")) for r in runs]) for k in KEYS}
    out["n"] = len(runs)
    out["limits"] = sum(1 for r in runs if r["limit_cycle"] != "none")
    return out


def wline(xs, ys, es):
    """Weighted line y = a + b x with known errors; b and its SE."""
    w = [1 / e ** 2 for e in es]
    S, Sx, Sy = sum(w), sum(wi * x for wi, x in zip(w, xs)), sum(wi * y for wi, y in zip(w, ys))
    Sxx = sum(wi * x * x for wi, x in zip(w, xs))
    Sxy = sum(wi * x * y for wi, x, y in zip(w, xs, ys))
    D = S * Sxx - Sx * Sx
    return (S * Sxy - Sx * Sy) / D, math.sqrt(S / D)


def fmt(m, se, scale=1.0, nd=3):
    if m != m:
        return "-"
    return f"{m / scale:.{nd}f} +- {se / scale:.{nd}f}" if se == se else f"{m / scale:.{nd}f}"


def report(root, sweeps, base, seeds, point_name):
    pts = load(root)
    st = {k: stats(v) for k, v in pts.items()}

    def P(**kw):
        return point_name(dict(base, **kw))

    def get(name, key):
        s = st.get(name)
        if not s or s["n"] < 3:
            return None
        return s[key]

    tests = []

    def verdict(name, ok, text):
        tests.append((name, "n/a" if ok is None else ("PASS" if ok else "FAIL"), text))

    mus = [0.1, 0.3, 0.5, 1.0]
    # T1, T2, T7, T8: the locked series
    lk = [(m, get(P(mu=m), "mu_M_last")) for m in mus]
    lk = [(m, v) for m, v in lk if v]
    if len(lk) >= 3:
        b, e = wline([m for m, _ in lk], [v[0] for _, v in lk], [v[1] for _, v in lk])
        verdict("T1 locked mu_M(c15) rises with mu", S.exceeds(b, e, SE_DIFF), f"slope {b:.3f} +- {e:.3f}")
    else:
        verdict("T1 locked mu_M(c15) rises with mu", None, f"{len(lk)} points with >= 3 runs")
    for m, v in lk:
        verdict(f"T2 mu_M(c15) > mu at mu {m}", S.exceeds(v[0] - m, v[1], SE_DIFF), f"{fmt(*v[:2])} vs {m}")
    v = get(P(mu=0.3), "mu_M_last")
    verdict("T3 mu_M(c15) at mu 0.3, delta 0.5 ~ 0.5 (+-0.05)",
            None if not v else S.within(v[0] - 0.5, v[1], 0.05, Z_EQ), f"{fmt(*v[:2])}" if v else "missing")
    fr = get(P(mu=1.0, rotation=1), "mu_M_first")
    lc = get(P(mu=1.0), "mu_M_first")
    verdict("T4a free, cycle 1: mu_M < mu at mu 1.0", None if not fr else S.exceeds(1.0 - fr[0], fr[1], SE_DIFF),
            fmt(*fr[:2]) if fr else "missing")
    ok = None if not (fr and lc) else S.exceeds(lc[0] - fr[0], S.combined_se(fr[1], lc[1]), SE_DIFF)
    verdict("T4b cycle 1 at mu 1.0: free < locked", ok,
            f"free {fmt(*fr[:2])}, locked {fmt(*lc[:2])}" if fr and lc else "missing")
    for key in ("mu_M_last", "mu_M_first"):
        a, b2 = get(P(), key), get(P(damp="restitution"), key)
        ok = None if not (a and b2) else S.within(a[0] - b2[0], S.combined_se(a[1], b2[1]), 0.05, Z_EQ)
        verdict(f"T5 damping: {key} cundall ~ restitution (+-0.05)", ok,
                f"{fmt(*a[:2])} vs {fmt(*b2[:2])}" if a and b2 else "missing")
    ref = get(P(), "mu_M_last")
    for d in (0.0, 0.2, 0.7):
        v = get(P(delta=d), "mu_M_last")
        ok = None if not (v and ref) else S.within(v[0] - ref[0], S.combined_se(v[1], ref[1]), 0.05, Z_EQ)
        verdict(f"T6 delta {d} ~ delta 0.5, mu_M(c15) (+-0.05)", ok,
                f"{fmt(*v[:2])} vs {fmt(*ref[:2])}" if v and ref else "missing")
    for key, lab, sign in (("Z_peak", "T7 Z at the peak falls with mu", -1), ("K_peak", "T8 K at the peak falls with mu", -1)):
        pts_ = [(m, get(P(mu=m), key)) for m in mus]
        pts_ = [(m, v) for m, v in pts_ if v]
        if len(pts_) >= 3:
            b, e = wline([m for m, _ in pts_], [v[0] for _, v in pts_], [v[1] for _, v in pts_])
            verdict(lab, S.exceeds(sign * b, e, SE_DIFF), f"slope {b:.4g} +- {e:.2g}")
        else:
            verdict(lab, None, "missing")
    al = [r["alpha"] for k, runs in pts.items() if "_rot0_" in k for r in runs]
    a = mean_se(al)
    verdict("T9 alpha (all locked runs) ~ 0.47 (+-0.05)", None if a[2] < 3 else S.within(a[0] - 0.47, a[1], 0.05, Z_EQ),
            f"{fmt(a[0], a[1])} over {a[2]} runs")

    # points.csv
    with open(os.path.join(root, "points.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["point", "n", "limits"] + [f"{k}{s}" for k in KEYS for s in ("", "_se")])
        for k, s in sorted(st.items()):
            w.writerow([k, s["n"], s["limits"]] + [x for key in KEYS for x in s[key][:2]])

    L = ["# Mohr sweep (petit2017): report", "",
         f"Generated by `python3 -m sable_tools.mohr.mohr reduce` on {datetime.date.today()} from "
         f"{sum(len(v) for v in pts.values())} runs in `runs/` (plan: PLAN.md, committed before them). "
         "Values: mean +- seed-to-seed standard error over the runs of a point (n); tests as PLAN.md.", "",
         "Departures from the plan: mohr.in gained its let-go rule (a relaxation also ends when the pistons "
         "carry < smin/100) after the first 6 runs; those were deleted and every run was made with the final "
         "deck. Two workers ran side by side (`mohr.py sweep` and `--reverse`), beside builds and tests, so "
         "the wall times are those of a loaded host (56-231 s a run; the plan's pilot: 58 s alone). Added, "
         "reported only: Z and porosity at each run's end (unloaded), Eq. 9's phi_min per run.", "",
         "## Tests", "", "| test | verdict | values |", "|---|---|---|"]
    L += [f"| {a} | {b} | {c} |" for a, b, c in tests]
    L += ["", "## Points", "",
          "| point | n | mu_M cycle 1 | mu_M cycle 15 | limit cycles | K peak (GPa) | alpha | Z peak | porosity peak | "
          "S peak | dmax peak | Z end | porosity end | Z first state | porosity first state | capped | wall (s) |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for k, s in sorted(st.items()):
        L.append(f"| {k} | {s['n']} | {fmt(*s['mu_M_first'][:2])} | {fmt(*s['mu_M_last'][:2])} | {s['limits']}/{s['n']} | "
                 f"{fmt(*s['K_peak'][:2], scale=1e9, nd=2)} | {fmt(*s['alpha'][:2])} | {fmt(*s['Z_peak'][:2])} | "
                 f"{fmt(*s['porosity_peak'][:2], nd=4)} | {fmt(*s['S_peak'][:2])} | {fmt(*s['dmax_peak'][:2], nd=4)} | "
                 f"{fmt(*s['Z_end'][:2])} | {fmt(*s['porosity_end'][:2], nd=4)} | "
                 f"{fmt(*s['Z_initial'][:2])} | {fmt(*s['porosity_initial'][:2], nd=4)} | {s['capped'][0]:.1f} | "
                 f"{s['wall_s'][0]:.0f} |")
    L += ["", "## Eq. 9 inverted (Table II)", "",
          "phi_min at which Eq. 9, with P(phi) from the peak's contacts (36 bins), gives the run's mu_M "
          "(sable-analyze phi-min-eq9; nan: no phi_min reaches it), mean +- SE over the runs that have one; "
          "the paper's Table II values are all negative.", "",
          "| mu (locked, delta 0.5) | phi_min cycle 1 (deg) | paper C1 | phi_min cycle 15 (deg) | paper C15 |",
          "|---|---|---|---|---|"]
    for m, (p1, p15) in TABLE2.items():
        s = st.get(P(mu=m))
        if s:
            L.append(f"| {m} | {fmt(*s['phi_min_c1_deg'][:2], nd=1)} ({s['phi_min_c1_deg'][2]}) | -{p1} | "
                     f"{fmt(*s['phi_min_last_deg'][:2], nd=1)} ({s['phi_min_last_deg'][2]}) | -{p15} |")
    L += ["", "Figures: `figures/` (mohr_report.figures)."]
    with open(os.path.join(root, "REPORT.md"), "w") as f:
        f.write("\n".join(L) + "\n")
    figures(root, pts, base, point_name)
    print("\n".join(L))


def save(fig, path, dpi=110):
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    import matplotlib.pyplot as plt
    plt.close(fig)


def read_peak(path):
    """(phi, and the next two values) of each contact row of a peak's dump local (plain or .gz)."""
    return [(float(p[2]), float(p[3]), float(p[4])) for _, _, rows in dump.local_snapshots(path) for p in rows]


def figures(root, pts, base, point_name):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fd = os.path.join(root, "figures")
    os.makedirs(fd, exist_ok=True)
    mus = [0.1, 0.3, 0.5, 1.0]

    def P(**kw):
        return point_name(dict(base, **kw))

    # Figs. 6, 9: mu_M against mu
    fig, ax = plt.subplots(figsize=(5, 4))
    for rot, key, mk, lab in ((0, "mu_M_last", "s", "locked, cycle 15"), (0, "mu_M_first", "o", "locked, cycle 1"),
                              (1, "mu_M_first", "^", "free, cycle 1"), (1, "mu_M_last", "v", "free, cycle 15")):
        xs, ys, es = [], [], []
        for m in mus:
            runs = pts.get(P(mu=m, rotation=rot), [])
            if runs:
                a = mean_se([r[key] for r in runs])
                xs.append(m), ys.append(a[0]), es.append(a[1] if a[1] == a[1] else 0)
        if xs:
            ax.errorbar(xs, ys, es, marker=mk, ls="-", capsize=3, label=lab,
                        mfc="none" if key == "mu_M_first" else None)
    ax.plot([0, 1], [0, 1], "k:", lw=1, label="mu_M = mu")
    ax.plot([0.3], [0.5], "r*", ms=12, label="paper, mu 0.3, limit cycle")
    ax.set_xlabel("grain friction mu")
    ax.set_ylabel("Mohr friction mu_M")
    ax.legend(fontsize=7)
    save(fig, os.path.join(fd, "muM_vs_mu.png"), 110)

    # mu_M against cycle (mean over seeds)
    fig, ax = plt.subplots(figsize=(5, 4))
    for k in sorted(pts):
        runs = pts[k]
        nc = min(len(r["mu_M"]) for r in runs)
        ms = [mean_se([r["mu_M"][c] for r in runs]) for c in range(nc)]
        ax.errorbar(range(1, nc + 1), [m[0] for m in ms], [m[1] if m[1] == m[1] else 0 for m in ms], capsize=2,
                    label=k.split("_N")[0], lw=1)
    ax.set_xlabel("cycle")
    ax.set_ylabel("mu_M (mean over seeds)")
    ax.legend(fontsize=5)
    save(fig, os.path.join(fd, "muM_vs_cycle.png"), 110)

    # one run in detail: Mohr circles (Fig. 5), K against sigma_yy (Figs. 2, 3), S against state (Fig. 8)
    fig5, ax5 = plt.subplots(figsize=(6, 3.5))
    fig3, ax3 = plt.subplots(figsize=(5, 4))
    fig8, ax8 = plt.subplots(figsize=(5, 4))
    fig7, ax7 = plt.subplots(figsize=(5, 4))
    fig14, ax14 = plt.subplots(figsize=(5, 4))
    import numpy as np
    for m in mus:
        runs = pts.get(P(mu=m), [])
        if not runs:
            continue
        d = os.path.join(root, "runs", P(mu=m), os.path.basename(runs[0]["dir"]))
        sp = os.path.join(d, "mohr_states.txt.gz")
        if not os.path.exists(sp):
            sp = sp[:-3]
        if not os.path.exists(sp):
            continue
        _, rows = read_states(sp)
        ax8.plot([r["state"] for r in rows], [r["S"] for r in rows], lw=1, label=f"mu {m}")
        last = max(int(r["cycle"]) for r in rows)
        ld = [r for r in rows if int(r["cycle"]) == last and r["loading"] == 1]
        K = [(b["syy"], (b["syy"] - a["syy"] + 2 * (b["sxx"] - a["sxx"])) / (3 * (b["eps"] - a["eps"])))
             for a, b in zip(ld, ld[1:])]
        ax3.plot([k[0] / 1e6 for k in K], [k[1] / 1e9 for k in K], "o-", ms=3, label=f"mu {m}")
        if m == 0.3:
            th = np.linspace(0, np.pi, 60)
            for cyc, col in ((1, "C0"), ((last + 1) // 2, "C1"), (last, "C2")):
                for r in (r for r in rows if int(r["cycle"]) == cyc and r["loading"] == 1):
                    c, R = (r["syy"] + r["sxx"]) / 2e6, (r["syy"] - r["sxx"]) / 2e6
                    ax5.plot(c + R * np.cos(th), R * np.sin(th), color=col, lw=0.6)
                ax5.plot([], [], color=col, label=f"cycle {cyc}")
            rr = runs[0]
            mu_l, C_l = rr["mu_M"][-1], rr["C"][-1] / 1e6
            xs = np.linspace(0, max(r["syy"] for r in rows) / 1e6, 10)
            ax5.plot(xs, C_l + mu_l * xs, "k--", lw=1, label=f"envelope cycle {last}: mu_M {mu_l:.3f}")
        pk = os.path.join(d, "mohr_peak_last.txt.gz")
        if not os.path.exists(pk):
            pk = pk[:-3]
        if os.path.exists(pk):
            ph = [p[0] for p in read_peak(pk)]
            ax7.hist(np.degrees(ph), bins=36, range=(-90, 90), density=True, histtype="step", label=f"mu {m}, cycle {last}")
            if m == 0.3:
                dl = [p[1] for p in read_peak(pk)]
                ax14.hist(np.array(dl) * 100, bins=50, histtype="step", density=True, label=f"mu 0.3, cycle {last} peak")
                pc = os.path.join(d, "mohr_peak_c1.txt.gz")
                if os.path.exists(pc):
                    ax7.hist(np.degrees([p[0] for p in read_peak(pc)]), bins=36, range=(-90, 90), density=True,
                             histtype="step", ls="--", color="k", label="mu 0.3, cycle 1")
    ax5.set_xlabel("sigma (MPa)"), ax5.set_ylabel("tau (MPa)"), ax5.set_aspect("equal"), ax5.legend(fontsize=7)
    ax5.set_title("loading circles, mu 0.3, delta 0.5, locked (first seed)", fontsize=8)
    ax3.set_xlabel("sigma_yy (MPa)"), ax3.set_ylabel("K, Eq. 6 (GPa)"), ax3.legend(fontsize=7)
    ax3.set_title("last cycle's loading, locked, delta 0.5 (first seed)", fontsize=8)
    ax8.set_xlabel("state"), ax8.set_ylabel("S (Eq. 10, 36 bins)"), ax8.legend(fontsize=7)
    ax7.set_xlabel("contact angle phi (deg, 0 = vertical)"), ax7.set_ylabel("P(phi)"), ax7.legend(fontsize=6)
    ax14.set_xlabel("overlap / (R_i + R_j) (%)"), ax14.set_ylabel("PDF"), ax14.set_yscale("log"), ax14.legend(fontsize=7)
    for f, n in ((fig5, "mohr_circles.png"), (fig3, "K_vs_syy.png"), (fig8, "entropy_vs_state.png"),
                 (fig7, "angles_peak.png"), (fig14, "overlaps_peak.png")):
        save(f, os.path.join(fd, n))

    # Fig. 12: S against state for the delta series (first seed of each point)
    fig, ax = plt.subplots(figsize=(5, 4))
    for dl in (0.0, 0.2, 0.5, 0.7):
        runs = pts.get(P(delta=dl), [])
        if not runs:
            continue
        sp = os.path.join(root, "runs", P(delta=dl), os.path.basename(runs[0]["dir"]), "mohr_states.txt.gz")
        sp = sp if os.path.exists(sp) else sp[:-3]
        if os.path.exists(sp):
            _, rows = read_states(sp)
            ax.plot([r["state"] for r in rows], [r["S"] for r in rows], lw=1, label=f"delta {dl}")
    ax.set_xlabel("state"), ax.set_ylabel("S (Eq. 10, 36 bins)"), ax.legend(fontsize=7)
    ax.set_title("mu 0.3, locked (first seed)", fontsize=8)
    save(fig, os.path.join(fd, "entropy_vs_state_delta.png"), 110)

    # Figs. 10, 11: against delta
    ds = [0.0, 0.2, 0.5, 0.7]
    fig, axs = plt.subplots(1, 4, figsize=(12, 3))
    for ax, key, lab, sc in zip(axs, ("mu_M_last", "alpha", "K_peak", "Z_peak"),
                                ("mu_M cycle 15", "alpha (Eq. 7)", "K at the peak (GPa)", "Z at the peak"), (1, 1, 1e9, 1)):
        xs, ys, es = [], [], []
        for dl in ds:
            runs = pts.get(P(delta=dl), [])
            if runs:
                a = mean_se([r[key] for r in runs])
                xs.append(dl), ys.append(a[0] / sc), es.append((a[1] if a[1] == a[1] else 0) / sc)
        ax.errorbar(xs, ys, es, marker="o", capsize=3)
        ax.set_xlabel("delta"), ax.set_ylabel(lab)
    xs1 = [dl for dl in ds if pts.get(P(delta=dl))]
    axs[0].errorbar(xs1, [mean_se([r["mu_M_first"] for r in pts[P(delta=dl)]])[0] for dl in xs1],
                    [mean_se([r["mu_M_first"] for r in pts[P(delta=dl)]])[1] or 0 for dl in xs1], marker="s",
                    mfc="none", capsize=3, label="cycle 1")
    axs[0].axhline(0.54, color="r", ls=":", label="paper 0.54")
    axs[1].axhline(0.458, color="r", ls=":", label="paper 0.458")
    axs[0].legend(fontsize=7), axs[1].legend(fontsize=7)
    save(fig, os.path.join(fd, "vs_delta.png"), 100)


def report_damping(sweep_root, new_seeds, old_seeds, point_name, base):
    """PLAN_damping.md: paired (same packing) cundall - restitution differences of mu_M."""
    def runs(root, damp, seeds):
        out = {}
        for s in seeds:
            f = os.path.join(root, "runs", point_name(dict(base, damp=damp)), f"s{s}", "result.json")
            if os.path.exists(f):
                with open(f) as fh:
                    out[s] = json.load(fh)
        return out

    d2 = os.path.join(sweep_root, "damping2")
    new = {k: runs(d2, k, new_seeds) for k in ("cundall", "restitution")}
    old = {k: runs(sweep_root, k, old_seeds) for k in ("cundall", "restitution")}
    L = ["# Damping follow-up (PLAN_damping.md): report", "",
         f"Generated by `python3 -m sable_tools.mohr.mohr reduce` on {datetime.date.today()}. mu 0.3, locked, delta 0.5, "
         "N 1000, 15 cycles; d = mu_M(cundall) - mu_M(restitution) on the same packing, mean +- SE over packings.", "",
         "| test | packings | cundall | restitution | d | equivalent within 0.05 | different (2 SE) |",
         "|---|---|---|---|---|---|---|"]
    for key, lab in (("mu_M_last", "D1 cycle 15"), ("mu_M_first", "D2 cycle 1")):
        for tag, sets in (("new (confirmatory)", [new]), ("all (secondary)", [new, old])):
            pairs = [(r["cundall"][s][key], r["restitution"][s][key]) for r in sets for s in r["cundall"]
                     if s in r["restitution"]]
            if len(pairs) < 3:
                L.append(f"| {lab} | {tag}: {len(pairs)} | - | - | - | n/a | n/a |")
                continue
            m, se, n = mean_se([a - b for a, b in pairs])
            ca, cb = mean_se([a for a, _ in pairs]), mean_se([b for _, b in pairs])
            L.append(f"| {lab} | {tag}: {n} | {fmt(ca[0], ca[1])} | {fmt(cb[0], cb[1])} | {m:+.4f} +- {se:.4f} | "
                     f"{'yes' if S.within(m, se, 0.05, Z_EQ) else 'no'} | {'yes' if S.differs(m, se, SE_DIFF) else 'no'} |")
    with open(os.path.join(d2, "REPORT.md"), "w") as f:
        f.write("\n".join(L) + "\n")
    print("\n".join(L))


def report_clumps(sweep_root, point_name, base, betas=(0.25, 0.62, 0.90), mus=(0.1, 0.3, 0.5, 1.0)):
    """PLAN_clumps.md: Fig. 16's mu_M against mu per beta, tests K1-K3 against the disk sweep."""
    croot = os.path.join(sweep_root, "clumps")
    cl = load(croot)
    disks = load(sweep_root)

    def pt(b, m):
        return point_name(dict(base, beta=b, rotation=1, mu=m, N=400))

    def ms(runs, key):
        return mean_se([r[key] for r in runs]) if runs else (float("nan"), float("nan"), 0)

    L = ["# Clumps (petit2017 App. B, Fig. 16): report", "",
         f"Generated by `python3 -m sable_tools.mohr.mohr reduce` on {datetime.date.today()} from "
         f"{sum(len(v) for v in cl.values())} runs in `clumps/runs/` (plan: PLAN_clumps.md, committed before them). "
         "400 rigid 3-disk clumps, rotation free, delta 0.5, 15 cycles; mean +- seed SE (n).", "",
         *(["**Partial: %d of %d runs.** The verdicts below are provisional until every point has its %d seeds "
            "(`mohr.py sweep --only clumps` continues it)." % (sum(len(v) for v in cl.values()),
                                                                 len(betas) * len(mus) * 5, 5), ""]
           if sum(len(v) for v in cl.values()) < len(betas) * len(mus) * 5 else []),
         "| beta | mu | n | mu_M cycle 1 | mu_M cycle 15 | Eq. 7 fits failed | capped |", "|---|---|---|---|---|---|---|"]
    for b in betas:
        for m in mus:
            runs = cl.get(pt(b, m), [])
            a1, a15 = ms(runs, "mu_M_first"), ms(runs, "mu_M_last")
            L.append(f"| {b} | {m} | {len(runs)} | {fmt(a1[0], a1[1])} | {fmt(a15[0], a15[1])} | "
                     f"{sum(1 for r in runs if r.get('eq7_error'))} | {sum(r['capped'] for r in runs)} |")
    tests = []
    pts_ = [(b, ms(cl.get(pt(b, 1.0), []), "mu_M_last")) for b in betas]
    pts_ = [(b, v) for b, v in pts_ if v[2] >= 3]
    if len(pts_) == 3:
        sl, e = wline([b for b, _ in pts_], [v[0] for _, v in pts_], [v[1] for _, v in pts_])
        tests.append(("K1 mu 1.0: mu_M(c15) rises with beta", "PASS" if S.exceeds(sl, e, SE_DIFF) else "FAIL",
                      f"slope {sl:.3f} +- {e:.3f}"))
    else:
        tests.append(("K1 mu 1.0: mu_M(c15) rises with beta", "n/a", f"{len(pts_)} betas with >= 3 runs"))
    lock01 = ms(disks.get(point_name(dict(base, mu=0.1)), []), "mu_M_last")
    free10 = ms(disks.get(point_name(dict(base, mu=1.0, rotation=1)), []), "mu_M_last")
    lock10 = ms(disks.get(point_name(dict(base, mu=1.0)), []), "mu_M_last")
    for b in betas:
        v = ms(cl.get(pt(b, 0.1), []), "mu_M_last")
        ok = "n/a" if v[2] < 3 or lock01[2] < 3 else (
            "PASS" if S.within(v[0] - lock01[0], S.combined_se(v[1], lock01[1]), 0.05, Z_EQ) else "FAIL")
        tests.append((f"K2 mu 0.1, beta {b}: ~ locked disks (+-0.05)", ok,
                      f"{fmt(v[0], v[1])} vs {fmt(lock01[0], lock01[1])}"))
        v = ms(cl.get(pt(b, 1.0), []), "mu_M_last")
        ok = "n/a" if v[2] < 3 else ("PASS" if S.exceeds(v[0] - free10[0], S.combined_se(v[1], free10[1]), SE_DIFF) and
                                      S.exceeds(lock10[0] - v[0], S.combined_se(v[1], lock10[1]), SE_DIFF) else "FAIL")
        tests.append((f"K3 mu 1.0, beta {b}: between free and locked disks", ok,
                      f"{fmt(v[0], v[1])} (free {fmt(free10[0], free10[1])}, locked {fmt(lock10[0], lock10[1])})"))
    L += ["", "## Tests", "", "| test | verdict | values |", "|---|---|---|"] + [f"| {a} | {b} | {c} |" for a, b, c in tests]
    with open(os.path.join(croot, "REPORT.md"), "w") as f:
        f.write("\n".join(L) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 4))
    for b in betas:
        xs = [m for m in mus if cl.get(pt(b, m))]
        if xs:
            v = [ms(cl[pt(b, m)], "mu_M_last") for m in xs]
            ax.errorbar(xs, [x[0] for x in v], [x[1] if x[1] == x[1] else 0 for x in v], marker="o", capsize=3,
                        label=f"clumps beta {b}")
    for rot, lab, mk in ((0, "locked disks", "s"), (1, "free disks", "v")):
        xs = [m for m in mus if disks.get(point_name(dict(base, mu=m, rotation=rot)))]
        v = [ms(disks[point_name(dict(base, mu=m, rotation=rot))], "mu_M_last") for m in xs]
        ax.errorbar(xs, [x[0] for x in v], [x[1] for x in v], marker=mk, ls="--", color="k" if rot == 0 else "gray",
                    capsize=3, label=lab)
    ax.set_xlabel("grain friction mu"), ax.set_ylabel("mu_M, cycle 15"), ax.set_ylim(0, 1.6)
    ax.legend(fontsize=7)
    save(fig, os.path.join(croot, "muM_vs_mu_clumps.png"), 110)
    print("\n".join(L))
