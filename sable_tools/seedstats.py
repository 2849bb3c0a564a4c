"""Statistics over seeds, one module for every study (drag, cavity, Mohr).

A chaotic flow is compared by means over independent runs (seeds) with the
seed-to-seed standard error; a run's own block error only checks that its noise
is below that scatter and is never added to it. Differences use Welch's
interval; "equal" is a two-one-sided test (TOST) against a stated margin, i.e.
the (1 - 2 alpha) interval inside (-margin, margin); slopes and other linear
combinations of independent means carry Welch-Satterthwaite degrees of freedom.

    from sable_tools.seedstats import summary, welch_diff, tost, slope, ratio, one_sided
    s = summary([24.5, 23.4, 25.2, 22.9])          # mean, sd, n, se, df
    d = welch_diff(sable_values, liggghts_values)  # est, se, df, lo, hi (90 %)
    e = tost(d, margin=0.1 * ref.mean)             # .equivalent, .p
    b = slope([2.2, 3.9, 5.2], [s2, s4, s5])       # OLS slope of the means
    r = ratio(b, b0)                               # delta method
    p = two_sided_p(d)                             # Welch's two-sided p
    g = planned(1.0, 0.03, 4)                      # the Summary 4 seeds of sd 0.03 would give (power)
    m, sd = pointwise(curves)                      # seed mean and sd of curves, point by point
    within(est, se, 0.05), agrees(d, se), differs(d, se), exceeds(d, se)  # fixed-multiplier rules
"""
import math
from dataclasses import dataclass

import numpy as _np
from scipy import stats as _st

LEVEL = 0.90  # two-sided interval level: the TOST at alpha = 0.05 reads the 90 % interval


@dataclass(frozen=True)
class Summary:
    mean: float
    sd: float   # seed-to-seed standard deviation (ddof 1); nan for one seed
    n: int
    se: float   # sd / sqrt(n): the seed-to-seed standard error
    df: float   # n - 1


@dataclass(frozen=True)
class Estimate:
    est: float
    se: float
    df: float
    lo: float   # two-sided interval at `level`
    hi: float
    level: float = LEVEL


@dataclass(frozen=True)
class Equivalence:
    est: float
    lo: float       # the (1 - 2 alpha) interval
    hi: float
    margin_lo: float
    margin_hi: float
    p: float        # the larger of the two one-sided p-values
    equivalent: bool


@dataclass(frozen=True)
class OneSided:
    est: float
    threshold: float
    bound: float    # one-sided (1 - alpha) confidence bound on the side tested
    p: float
    significant: bool


def summary(values):
    """Mean, seed-to-seed sd and standard error of independent runs (nan and None dropped).
    The sums are numpy's (np.mean, np.std(ddof=1): pairwise), so the scripts that used those
    before give the same numbers to the last bit."""
    v = _np.array([float(x) for x in values if x is not None and not math.isnan(float(x))], float)
    n = len(v)
    if n == 0:
        return Summary(math.nan, math.nan, 0, math.nan, math.nan)
    sd = float(v.std(ddof=1)) if n > 1 else math.nan
    return Summary(float(v.mean()), sd, n, sd / math.sqrt(n) if n > 1 else math.nan, n - 1.0)


def planned(mean, sd, n):
    """The Summary that n seeds of this sd would give (power and design calculations: the sd
    assumed, e.g. a coefficient of variation times the mean, not measured)."""
    return Summary(float(mean), float(sd), int(n), sd / math.sqrt(n), n - 1.0)


def pointwise(curves):
    """Seed mean and seed-to-seed sd of equally long curves (one row a seed), point by point
    (numpy's mean and std(ddof=1), as summary's); sd nan for one seed."""
    f = _np.asarray(curves, float)
    return f.mean(0), (f.std(0, ddof=1) if len(f) > 1 else _np.full(f.shape[1:], math.nan))


def _as_summary(x):
    return x if isinstance(x, Summary) else summary(x)


def interval(est, se, df, level=LEVEL):
    """Estimate with its two-sided t interval."""
    if not (se > 0 and df > 0) or math.isnan(se) or math.isnan(df):
        return Estimate(est, se, df, math.nan, math.nan, level)
    t = _st.t.ppf(0.5 + level / 2, df)
    return Estimate(est, se, df, est - t * se, est + t * se, level)


def satterthwaite(parts):
    """Degrees of freedom of a sum of independent variance terms [(variance, df), ...]."""
    tot = sum(v for v, _ in parts)
    den = sum(v * v / d for v, d in parts if v > 0)
    return tot * tot / den if den > 0 else math.nan


def linear_contrast(groups, coeffs, level=LEVEL):
    """sum c_i mean_i over independent groups (summaries or value lists), its standard
    error from the seed-to-seed errors and Welch-Satterthwaite degrees of freedom."""
    gs = [_as_summary(g) for g in groups]
    if len(gs) != len(coeffs):
        raise ValueError('one coefficient per group')
    est = sum(c * g.mean for c, g in zip(coeffs, gs))
    parts = [(c * c * g.se * g.se, g.df) for c, g in zip(coeffs, gs) if c != 0]
    var = sum(v for v, _ in parts)
    return interval(est, math.sqrt(var) if var == var else math.nan, satterthwaite(parts), level)


def welch_diff(a, b, level=LEVEL):
    """mean(a) - mean(b) with Welch's interval."""
    return linear_contrast([a, b], [1.0, -1.0], level)


def slope(x, groups, level=LEVEL):
    """Least-squares slope of the group means against x (each mean weighted alike), its
    error from the groups' seed-to-seed errors alone (no lack-of-fit term)."""
    if len(x) < 2:
        raise ValueError('a slope needs two x values')
    xm = sum(x) / len(x)
    sxx = sum((xi - xm) ** 2 for xi in x)
    return linear_contrast(groups, [(xi - xm) / sxx for xi in x], level)


def ratio(num, den, level=LEVEL):
    """num / den of two independent estimates (delta method; Satterthwaite df)."""
    r = num.est / den.est
    v1 = (num.se / den.est) ** 2
    v2 = (r * den.se / den.est) ** 2
    se = math.sqrt(v1 + v2)
    return interval(r, se, satterthwaite([(v1, num.df), (v2, den.df)]), level)


def scale(e, k, level=None):
    """An estimate times a known constant."""
    return interval(e.est * k, abs(k) * e.se, e.df, level or e.level)


def tost(e, margin, alpha=0.05, margin_hi=None):
    """Two one-sided tests: is e.est inside (-margin, margin) (or (margin, margin_hi) when
    margin_hi is given, margin then the lower bound)? Equivalent when both one-sided
    p-values are below alpha, i.e. the (1 - 2 alpha) interval lies inside the margins."""
    lo_m, hi_m = (-abs(margin), abs(margin)) if margin_hi is None else (margin, margin_hi)
    if not (e.se > 0 and e.df > 0):
        return Equivalence(e.est, math.nan, math.nan, lo_m, hi_m, math.nan, False)
    p_lo = _st.t.sf((e.est - lo_m) / e.se, e.df)   # H0: est <= lo_m
    p_hi = _st.t.cdf((e.est - hi_m) / e.se, e.df)  # H0: est >= hi_m
    t = _st.t.ppf(1 - alpha, e.df)
    p = max(p_lo, p_hi)
    return Equivalence(e.est, e.est - t * e.se, e.est + t * e.se, lo_m, hi_m, p, bool(p < alpha))


def two_sided_p(e, value=0.0):
    """p-value of the two-sided t test of est = value (Welch's, for an estimate of welch_diff)."""
    if not (e.se > 0 and e.df > 0):
        return math.nan
    return float(2 * _st.t.sf(abs(e.est - value) / e.se, e.df))


def one_sided(e, threshold=0.0, greater=True, alpha=0.05):
    """Difference test: is the true value above (greater) or below the threshold?"""
    if not (e.se > 0 and e.df > 0):
        return OneSided(e.est, threshold, math.nan, math.nan, False)
    z = (e.est - threshold) / e.se
    t = _st.t.ppf(1 - alpha, e.df)
    if greater:
        return OneSided(e.est, threshold, e.est - t * e.se, _st.t.sf(z, e.df), bool(_st.t.sf(z, e.df) < alpha))
    return OneSided(e.est, threshold, e.est + t * e.se, _st.t.cdf(z, e.df), bool(_st.t.cdf(z, e.df) < alpha))


# Rules with a fixed multiplier of the standard error (normal quantiles, no degrees of freedom),
# as the Mohr and cavity reports state their tests; tost(), one_sided() and welch_diff() are the
# t-based forms. Each takes an estimate and its standard error (combined_se for a difference).

def combined_se(*ses):
    """Standard error of a sum or difference of independent estimates: sqrt(sum se^2)."""
    return math.sqrt(sum(float(x) ** 2 for x in ses))


def agrees(est, se, k=2.0):
    """|est| <= k se: a difference consistent with zero (k = 2: about 95 %); None where se is not finite."""
    return bool(abs(est) <= k * se) if math.isfinite(se) else None


def differs(est, se, k=2.0):
    """|est| > k se: a difference (two-sided, k standard errors)."""
    return bool(abs(est) > k * se)


def exceeds(est, se, k=2.0):
    """est > k se: a positive difference (one-sided, k standard errors)."""
    return bool(est > k * se)


def within(est, se, margin, z=1.645):
    """|est| + z se < margin: equivalence inside (-margin, margin) with a normal quantile (z = 1.645:
    each side at 5 %, the (1 - 2 alpha) interval inside the margins; tost() uses the t quantile)."""
    return bool(abs(est) + z * se < margin)


def _chi2_mean(g, df, q_hi=math.inf):
    """E[g(q) ; q < q_hi] for q ~ chi^2(df), integrated over the probability (smooth in it)."""
    from scipy.integrate import quad
    u_hi = _st.chi2.cdf(q_hi, df) if q_hi < math.inf else 1.0
    if not u_hi > 0:
        return 0.0
    return quad(lambda u: g(_st.chi2.ppf(u, df)), 0.0, u_hi, limit=200, epsabs=1e-10)[0]


def tost_power(se, df, margin, true=0.0, alpha=0.05):
    """Chance that tost() finds equivalence when the true value is `true`, the estimate is
    normal with standard error `se` and its estimated standard error is se * sqrt(q / df),
    q ~ chi^2(df), independent of it: exact for a one-sample or pooled t, and for Welch's
    difference of two groups of equal n and sd; near for other Welch cases. (Holding the
    estimated error at `se` instead overstates the chance at a few seeds, and gives 0 where
    t se > margin although a run with a small scatter can still pass.)"""
    m = abs(margin)
    if not se > 0:
        return float(abs(true) < m)
    t = _st.t.ppf(1 - alpha, df)

    def given(s):  # the chance for an estimated standard error s
        lo, hi = -m + t * s, m - t * s
        return float(_st.norm.cdf((hi - true) / se) - _st.norm.cdf((lo - true) / se)) if hi > lo else 0.0
    if math.isinf(df):
        return given(se)
    # equivalence needs t s < margin, i.e. q < df (margin / (t se))^2
    return _chi2_mean(lambda q: given(se * math.sqrt(q / df)), df, df * (m / (t * se)) ** 2)


def one_sided_power(se, df, effect, alpha=0.05):
    """Chance that one_sided() finds est > 0 when the true value is `effect` > 0, with the
    estimated standard error sampled as in tost_power (the noncentral t's P(T'(df, effect/se)
    > t_{1-alpha, df}), integrated here as scipy 1.10's nct warns spuriously at small df)."""
    t = _st.t.ppf(1 - alpha, df)
    if math.isinf(df):
        return float(_st.norm.sf(t - effect / se))
    return _chi2_mean(lambda q: float(_st.norm.sf(t * math.sqrt(q / df) - effect / se)), df)


def block_check(run_block_errors, seeds):
    """One run's noise against the seed scatter: the rms block error over the seed sd
    (should be below 1; it is never added to the seed error)."""
    s = _as_summary(seeds)
    errs = [e for e in run_block_errors if e == e]
    if not errs or not (s.sd > 0):
        return math.nan
    return math.sqrt(sum(e * e for e in errs) / len(errs)) / s.sd
