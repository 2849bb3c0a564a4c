#!/usr/bin/python3
"""Compare a random deck's statistics between sable and LIGGGHTS (or YADE) over seeds.

    /usr/bin/python3 -m sable_tools.compare_seeds DECK [--out DIR] [--sable PATH]
        [--var NAME VALUE ...] [--seeds N] [--seed-values V ...] [--seed-var NAME] [--timeout S]
        [--ref liggghts|yade|liggghts-stored|yade-stored] [--store] [--tolerances FILE]
        [--prepare NAME VALUE ...] [--results]

Insertion places grains differently in each code for the same seed, so a single
run of one code cannot be judged against one run of the other. This runs the
deck in BOTH codes once per value of its `#@ seeds VAR V1 V2 ...` line (the
first N with --seeds), reads the OBSERVABLE lines (as compare.py does) and, per
observable, compares the two means with their combined standard error
SE = sqrt(sd_s^2 / n + sd_l^2 / n). It passes when |mean_s - mean_l| <= K SE,
K from the deck's `#@ tolerance NAME sigma K` (an `abs X` tolerance is an
absolute bound on the difference of the means; `none` is not judged).
Writes DIR/DECKNAME/seeds.md and seeds.json; exit status 0 when all pass.

--ref yade: the reference is YADE on the script sable --export-yade writes from the
deck (reference_runs/README.md, YADE section). --prepare NAME VALUE (repeatable):
before each judged run of either code, sable runs the deck in that run's directory
with these variables (e.g. the cavity's `phase deposit`, which writes the restart its
`phase shear` reads): both codes then start from the same sable state, as YADE must
where the exporter translates a scene once (the cavity: deposit in sable, shear in
both). --results: the key=value pairs of the deck's RESULT lines are observables too
(the last value of a key wins). --seed-var NAME: the seed variable of a deck without
a `#@ seeds` line (give --seed-values).

--ref liggghts-stored|yade-stored: the reference's per-seed results are read from
reference_runs/reference/DECKNAME/CODE/results.json instead of run (sable still runs
every seed); --store with --ref liggghts|yade writes that file (compare.py's store:
the sha256 of the deck's commands and of the files it names, the -var values, seeds,
--prepare and --results). compare.py's load_stored refuses a stored record made from
other deck commands or files, or with other -var values, seeds, --prepare or --results,
before anything runs. --tolerances FILE: more `#@ tolerance` / `#@ unjudged` lines,
after the deck's (compare.py's parse_header), e.g. input_scripts/cavity/compare_smoke.tol;
a line that decides no observable fails the comparison, as in compare.py.
"""
import argparse, datetime, json, math, os, shutil, sys

from sable_tools import compare, runner, seedstats  # the deck conventions; the binaries; statistics over seeds
from sable_tools.readers import screen  # the RESULT lines of a run's screen


def stats(values):
    """(mean, seed-to-seed sd, n) of the seeds' values, nan dropped (seedstats.summary; sd nan for one)."""
    s = seedstats.summary(values)
    return s.mean, s.sd, s.n


def result_values(screen_file):
    """key=value pairs of the RESULT lines of a run's screen (numbers only; the last wins)."""
    if not os.path.exists(screen_file):
        return {}
    with open(screen_file, errors='replace') as f:
        return screen.numeric_keys(f.read(), 'RESULT')


def judge(spec, ms, mlig, se):
    """(pass?, text) for the difference of the means under a tolerance spec."""
    if spec is None:
        return None, 'not judged'
    d = abs(ms - mlig - spec.get('offset', 0.0))
    allowed, parts = 0.0, [f'offset {spec["offset"]:g}, '] if 'offset' in spec else []
    if 'abs' in spec:
        allowed += spec['abs']
        parts.append(f'abs {spec["abs"]:g}')
    if 'rel' in spec:
        allowed += spec['rel'] * abs(mlig)
        parts.append(f'rel {spec["rel"]:g}')
    if 'sigma' in spec:
        if math.isnan(se):
            return False, 'no spread (one seed)'
        allowed += spec['sigma'] * se
        parts.append(f'{spec["sigma"]:g} SE')
    return d <= allowed, ' + '.join(parts).replace(', + ', ', ') + f' = {allowed:.3g}'


def table(values, ref, h):
    """The rows of the comparison (per observable: each code's seed mean and sd, n, the Welch SE of
    the difference, diff / SE, the tolerance's text and result) and whether none failed.
    values: {code: {observable: [one value per seed]}}; h: compare.parse_header's."""
    names = list(dict.fromkeys(list(values['sable']) + list(values[ref])))
    rows, ok = [], True
    for n in names:
        ms, ss, ns = stats(values['sable'].get(n, []))
        ml, sl, nl = stats(values[ref].get(n, []))
        se = seedstats.welch_diff(values['sable'].get(n, []), values[ref].get(n, [])).se  # nan below two seeds each
        k = compare.rule(h, n)
        if k is None:  # compare.py's rule: every observable is judged or explicitly unjudged
            passed, text = False, 'no #@ tolerance or #@ unjudged line matches'
        elif h['rules'][k][1] is None:
            passed, text = None, 'unjudged: ' + h['rules'][k][2]
        else:
            passed, text = judge(h['rules'][k][1], ms, ml, se)
        ok = ok and passed is not False
        z = abs(ms - ml) / se if se > 0 else (0.0 if ms == ml else math.inf)
        rows.append({'observable': n, 'sable_mean': ms, 'sable_sd': ss, f'{ref}_mean': ml, f'{ref}_sd': sl,
                     'n': min(ns, nl), 'se': se, 'diff_over_se': z, 'tolerance': text,
                     'result': 'not judged' if passed is None else 'pass' if passed else 'FAIL'})
    return rows, ok


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('deck')
    p.add_argument('--out', default=os.path.join(compare.REPO, 'build-compare'))
    p.add_argument('--sable', default=runner.built('sable'))
    p.add_argument('--var', nargs=2, action='append', default=[], metavar=('NAME', 'VALUE'))
    p.add_argument('--seeds', type=int, default=0, help='use only the first N seeds')
    p.add_argument('--seed-values', nargs='+', default=None, metavar='V',
                   help="these seed values instead of the deck's (primes > 10000 for LIGGGHTS)")
    p.add_argument('--timeout', type=float, default=1800)
    p.add_argument('--ref', choices=['liggghts', 'yade', 'liggghts-stored', 'yade-stored'], default='liggghts',
                   help='the reference code (-stored: its stored per-seed results)')
    p.add_argument('--store', action='store_true',
                   help='store the reference (--ref liggghts|yade) under reference_runs/reference/')
    p.add_argument('--tolerances', default=None, metavar='FILE',
                   help="#@ tolerance / #@ unjudged lines read after the deck's")
    p.add_argument('--prepare', nargs=2, action='append', default=[], metavar=('NAME', 'VALUE'),
                   help='variables of a sable run of the deck before each judged run, in its directory')
    p.add_argument('--results', action='store_true', help="the RESULT lines' key=value pairs are observables")
    p.add_argument('--seed-var', default=None, help='the seed variable (decks without "#@ seeds")')
    args = p.parse_args()
    args.sable = os.path.abspath(args.sable)
    ref, stored = args.ref.removesuffix('-stored'), args.ref.endswith('-stored')
    if args.store and stored:
        sys.exit('--store writes the reference from a run of it: use --ref liggghts or --ref yade')
    if not stored and not shutil.which(ref):
        sys.exit(f'{ref} is not on PATH (apt-get install {ref}): this comparison runs both codes '
                 f'(or use --ref {ref}-stored)')
    h = compare.parse_header(args.deck, args.tolerances)
    if h['seeds']:
        var, seeds = h['seeds'][0], (args.seed_values or h['seeds'][1])[:args.seeds or None]
    elif args.seed_var and args.seed_values:
        var, seeds = args.seed_var, args.seed_values[:args.seeds or None]
    else:
        sys.exit(f'{args.deck}: no "#@ seeds VAR V1 V2 ..." line (or give --seed-var and --seed-values)')
    name = os.path.splitext(os.path.basename(args.deck))[0]
    outdir = os.path.join(args.out, name)
    made_with = {'seeds': {var: seeds}, 'prepare': dict(args.prepare), 'results': args.results}
    hashes = compare.deck_hashes(args.deck)  # what runs now, for --store
    if stored:  # before anything runs: a record of another deck or other settings stops here
        rec, note = compare.load_stored(args.deck, name, dict(args.var), ref, made_with)
        refnote = (f'{REFNAME[ref]}: results stored in reference_runs/reference/{name}/{ref}/ '
                   f'({ref} run of {rec.get("date", "?")}; {note}), not run now')
    codes = ['sable'] + ([] if stored else [ref])
    values, errors, tails = {}, [], []
    for code in codes:
        runs = []  # one dict of observables per seed
        for s in seeds:
            rundir = os.path.join(outdir, code, f'{var}_{s}')
            variables = {**dict(args.var), var: s}
            if args.prepare:
                _, _, err, _ = compare.run_once('sable', args.deck, rundir, {**variables, **dict(args.prepare)}, h, args)
                os.replace(os.path.join(rundir, 'screen.txt'), os.path.join(rundir, 'prepare.txt'))
                if err:
                    errors.append(f'{code} {var}={s}: the sable run before it (--prepare): {err}')
                    runs.append({})
                    continue
            obs, _, err, tail = compare.run_once(code, args.deck, rundir, variables, h, args)
            if err:
                errors.append(f'{code} {var}={s}: {err}')
            if args.results:
                obs.update(result_values(os.path.join(rundir, 'screen.txt')))
            runs.append(obs)
            if code == ref:
                tails.append(f'== {var} {s}\n' + '\n'.join(tail.splitlines()[-12:]))
        names = list(dict.fromkeys(k for r in runs for k in r))
        values[code] = {k: [r.get(k, math.nan) for r in runs] for k in names}
    if stored:
        values[ref] = rec['values']
    else:
        # the reference's record, as compare.py's run_code writes one for a seeded LIGGGHTS run
        rec = {'code': ref, 'deck': os.path.basename(args.deck), 'vars': dict(args.var), **made_with,
               'date': datetime.date.today().isoformat(),
               'errors': [e for e in errors if e.startswith(ref + ' ')],
               'observables': {k: stats(v)[0] for k, v in values[ref].items()},
               'std': {k: stats(v)[1] for k, v in values[ref].items()},
               'values': values[ref], 'log_tail': '\n'.join(tails)}
        refnote = f'{REFNAME[ref]}: ran `{shutil.which(ref)}` now' + \
            (' on the script written by sable --export-yade' if ref == 'yade' else '')
        if args.store:
            if rec['errors']:
                sys.exit(f'{ref} failed, reference not stored: ' + '; '.join(rec['errors']))
            compare.store(rec, args.deck, name, ref, hashes)
    names = list(dict.fromkeys(list(values['sable']) + list(values[ref])))
    rows, judged_ok = table(values, ref, h)
    ok = not errors and judged_ok
    dead = [f'{where} `#@ {"unjudged" if spec is None else "tolerance"} {pat}` decides no observable '
            '(its pattern matches none, or later lines override every match)'
            for pat, spec, _, where in compare.dead_rules(h, names)]
    ok = ok and not dead
    REF = REFNAME[ref] + (' (stored)' if stored else '')
    lines = [f'# {name}: sable vs {REF} over {len(seeds)} seeds ({datetime.date.today().isoformat()})', '',
             f'Deck `{compare.show(args.deck)}`' + ''.join(f' -var {k} {v}' for k, v in args.var) +
             ''.join(f' (after a sable run with -var {k} {v})' for k, v in args.prepare) +
             f', {var} = {" ".join(seeds)}; each code ran once per seed' + (' (the reference before, stored)'
             if stored else '') + '. SE = sqrt(sd_s^2/n + sd_l^2/n), the standard error of the difference of '
             'the means.' + (f' Tolerances: {compare.show(args.tolerances)}.' if args.tolerances else ''),
             '', f'- {refnote}', '',
             f'| observable | sable mean ± sd | {REFNAME[ref]} mean ± sd | n | diff / SE | tolerance | result |',
             '|---|---|---|---|---|---|---|']
    for r in rows:
        lines.append(f'| {r["observable"]} | {r["sable_mean"]:.6g} ± {r["sable_sd"]:.3g} | '
                     f'{r[ref + "_mean"]:.6g} ± {r[ref + "_sd"]:.3g} | {r["n"]} | {r["diff_over_se"]:.2f} | '
                     f'{r["tolerance"]} | {r["result"]} |')
    lines += [''] + [f'- error: {e}' for e in errors] + [f'- **FAIL: {d}**' for d in dead]
    lines.append(f'\n**{"PASS" if ok else "FAIL"}**')
    os.makedirs(outdir, exist_ok=True)
    open(os.path.join(outdir, 'seeds.md'), 'w').write('\n'.join(lines) + '\n')
    with open(os.path.join(outdir, 'seeds.json'), 'w') as f:
        json.dump({'deck': name, 'ref': args.ref, 'vars': dict(args.var), 'prepare': dict(args.prepare), 'seeds': seeds,
                   'values': values, 'rows': rows, 'errors': errors, 'dead_rules': dead}, f, indent=1, allow_nan=True)
    print('\n'.join(lines))
    print(f'written: {compare.show(os.path.join(outdir, "seeds.md"))}')
    sys.exit(0 if ok else 1)


REFNAME = {'liggghts': 'LIGGGHTS', 'yade': 'YADE'}


if __name__ == '__main__':
    main()
