// Maximum-likelihood fits: Nelder-Mead (GSL nmsimplex2) from several starts,
// profile-likelihood intervals, kneib2017 Eq. 7 with its Gaussian limit, Eqs. 8-10.
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_sf_erf.h>
#include <gsl/gsl_sf_gamma.h>

#include <algorithm>
#include <cmath>

#include "reference_runs/analysis/analysis.h"

namespace sable::analysis {

namespace {
constexpr double kHuge = 1e300;  // outside the domain: nmsimplex2 refuses non-finite values
constexpr double kLn2Pi = 1.8378770664093453;

struct Ctx {
  const Objective* f;
  Vec buf;
};
double call(const gsl_vector* v, void* p) {
  auto* c = static_cast<Ctx*>(p);
  for (std::size_t i = 0; i < c->buf.size(); ++i) c->buf[i] = gsl_vector_get(v, i);
  const double r = (*c->f)(c->buf);
  return std::isfinite(r) ? std::min(r, kHuge) : kHuge;
}
}  // namespace

Minimum nelder_mead(const Objective& f, const Vec& start, const Vec& step, double tol, int max_iter) {
  const std::size_t n = start.size();
  if (n == 0) return {start, f(start)};
  gsl_set_error_handler_off();
  Ctx ctx{&f, Vec(n)};
  gsl_multimin_function F{&call, n, &ctx};
  gsl_vector* x = gsl_vector_alloc(n);
  gsl_vector* ss = gsl_vector_alloc(n);
  for (std::size_t i = 0; i < n; ++i) {
    gsl_vector_set(x, i, start[i]);
    gsl_vector_set(ss, i, step[i]);
  }
  gsl_multimin_fminimizer* s = gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, n);
  Minimum m;
  m.theta = start;
  if (gsl_multimin_fminimizer_set(s, &F, x, ss) == GSL_SUCCESS) {
    for (int it = 0; it < max_iter; ++it) {
      if (gsl_multimin_fminimizer_iterate(s) != GSL_SUCCESS) break;
      if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(s), tol) == GSL_SUCCESS) break;
    }
    for (std::size_t i = 0; i < n; ++i) m.theta[i] = gsl_vector_get(s->x, i);
    m.value = s->fval;
  } else {
    m.value = f(start);
  }
  gsl_multimin_fminimizer_free(s);
  gsl_vector_free(ss);
  gsl_vector_free(x);
  return m;
}

Minimum best_of_starts(const Objective& f, const std::vector<Vec>& starts, const Vec& step) {
  Minimum best;
  for (const Vec& s0 : starts) {
    Minimum m = nelder_mead(f, s0, step);
    if (m.value < best.value) best = m;
  }
  for (int r = 0; r < 5 && best.value < kHuge; ++r) {  // restart: a simplex can collapse early
    Minimum m = nelder_mead(f, best.theta, step);
    const bool better = m.value < best.value - 1e-10;
    if (m.value < best.value) best = m;
    if (!better) break;
  }
  return best;
}

Interval profile_interval(const Profile& prof, double t_hat, const Vec& free_hat, double nll_hat, double scale,
                          double t_min, double t_max, double delta) {
  Interval iv;
  for (int dir : {-1, +1}) {
    double inner = t_hat, step = scale, outer = 0;
    Vec free_inner = free_hat;
    bool found = false;
    for (int it = 0; it < 80 && !found; ++it) {
      const double t = std::clamp(inner + dir * step, t_min, t_max);
      Vec fr = free_inner;
      if (prof(t, fr) - nll_hat >= delta) {
        outer = t;
        found = true;
      } else {
        inner = t;
        free_inner = fr;
        if (t == t_min || t == t_max) break;
        step *= 1.6;
      }
    }
    if (!found) continue;  // open on this side: the profile stays within delta up to the search bound
    double a = inner, b = outer;
    for (int it = 0; it < 60 && std::fabs(b - a) > 1e-5 * scale; ++it) {
      const double mid = 0.5 * (a + b);
      Vec fr = free_inner;
      if (prof(mid, fr) - nll_hat >= delta) {
        b = mid;
      } else {
        a = mid;
        free_inner = fr;
      }
    }
    (dir < 0 ? iv.lo : iv.hi) = 0.5 * (a + b);
    (dir < 0 ? iv.lo_open : iv.hi_open) = false;
  }
  return iv;
}

namespace {

// A reported parameter: exp(t) when log, else t. Plain coordinates are the search
// coordinates themselves; a mapped one says how to read t from a search point and
// which other coordinates stay free while t is profiled (well conditioned ones).
struct Coord {
  std::string name;
  double lo, hi, step;  // t's range and first profile step
  bool log;
  std::function<double(const Vec&)> of = nullptr;           // t at a search point
  std::function<Vec(double, const Vec&)> full = nullptr;    // search point from t and the free ones
  std::function<Vec(const Vec&)> free_of = nullptr;         // the free ones at a search point
  Vec free_step = {};
};

double shown(const Coord& c, double v) { return c.log ? std::exp(v) : v; }

bool inside(const std::vector<Coord>& cs, const Vec& t) {
  for (std::size_t i = 0; i < cs.size(); ++i)
    if (!(t[i] >= cs[i].lo && t[i] <= cs[i].hi)) return false;
  return true;
}

// Plain coordinates: t_i = theta_i, the others free.
void make_plain(std::vector<Coord>& cs) {
  const std::size_t n = cs.size();
  for (std::size_t i = 0; i < n; ++i) {
    Coord& c = cs[i];
    c.of = [i](const Vec& th) { return th[i]; };
    c.full = [i, n](double t, const Vec& fr) {
      Vec th(n);
      for (std::size_t j = 0, k = 0; j < n; ++j) th[j] = j == i ? t : fr[k++];
      return th;
    };
    c.free_of = [i](const Vec& th) {
      Vec fr;
      for (std::size_t j = 0; j < th.size(); ++j)
        if (j != i) fr.push_back(th[j]);
      return fr;
    };
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) c.free_step.push_back(cs[j].step);
  }
}

// Minimise from the starts (search coordinates), then profile every reported parameter.
Fit fit_coords(const std::string& model, std::vector<Coord> cs, const Objective& nll_raw, const std::vector<Vec>& starts,
               const Vec& step, double delta) {
  const bool plain = !cs.front().of;
  if (plain) make_plain(cs);
  const Objective nll = [&](const Vec& t) { return !plain || inside(cs, t) ? nll_raw(t) : kHuge; };
  const Minimum best = best_of_starts(nll, starts, step);
  if (!(best.value < kHuge)) throw Error(model + ": no start gives a finite likelihood");
  Fit fit;
  fit.model = model;
  fit.loglik = -best.value;
  fit.aic = 2.0 * double(cs.size()) + 2.0 * best.value;
  for (const Coord& c : cs) {
    const Profile prof = [&](double t, Vec& free) {
      const Objective g = [&](const Vec& fr) { return nll(c.full(t, fr)); };
      const Minimum m = best_of_starts(g, {free}, c.free_step);
      free = m.theta;
      return m.value;
    };
    const double t_hat = c.of(best.theta);
    const Interval iv = profile_interval(prof, t_hat, c.free_of(best.theta), best.value, c.step, c.lo, c.hi, delta);
    Param p{c.name, shown(c, t_hat), iv};
    p.ci.lo = iv.lo_open ? (c.log ? 0.0 : -kInf) : shown(c, iv.lo);
    p.ci.hi = iv.hi_open ? kInf : shown(c, iv.hi);
    fit.params.push_back(p);
  }
  return fit;
}

Fit fit_plain(const std::string& model, const std::vector<Coord>& cs, const Objective& nll, const std::vector<Vec>& starts,
              double delta) {
  Vec step;
  for (auto& c : cs) step.push_back(c.step);
  return fit_coords(model, cs, nll, starts, step, delta);
}

void check_positive(const Vec& x, const char* what) {
  if (x.size() < 3) throw Error(std::string(what) + ": needs at least 3 values");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!(x[i] > 0))
      throw Error(std::string(what) + " is defined for x > 0: value " + std::to_string(i + 1) + " is " +
                  std::to_string(x[i]) + " (select positive values)");
}

double sd_of(const Vec& x) {
  const double m = mean_of(x);
  double v = 0;
  for (double a : x) v += (a - m) * (a - m);
  return std::sqrt(v / double(x.size() - 1));
}

// Eq. 7 in (m, s, x0): m = e^mu - x0 (median of the untruncated law), s = sigma e^mu.
// These stay finite as x0 -> inf (the Gaussian limit N(m, s)), so no cancellation.
double z_ms(double x, double m, double s, double x0) {
  const double l = m + x0;
  return std::log1p((x - m) / l) * l / s;
}
double log_surv(double z) { return std::log(0.5) + gsl_sf_log_erfc(z / M_SQRT2); }  // ln P(Z > z)

double eq7_nll_ms(const Vec& x, double m, double s, double x0) {
  const double l = m + x0, sigma = s / l;
  if (!(s > 0) || !(x0 > 0) || !(l > 0)) return kHuge;
  const double ls0 = log_surv(z_ms(0, m, s, x0));
  double sum = 0;
  for (double v : x) {
    const double z = z_ms(v, m, s, x0);
    sum += std::log(sigma * (v + x0)) + 0.5 * kLn2Pi + 0.5 * z * z;
  }
  return sum + double(x.size()) * ls0;
}

double log_softplus(double y) { return y > 0 ? y + std::log1p(std::exp(-y)) : std::log1p(std::exp(y)); }

std::function<double(double)> ks_cdf_guard(std::function<double(double)> f) {
  return [f](double v) { return std::clamp(f(v), 0.0, 1.0); };
}

void finish_ks(Fit& f, const Vec& x) { f.ks = ks_one_sample(x, f.cdf); }

}  // namespace

double eq7_pdf(double x, double mu, double sigma, double x0) {
  if (!(x > 0)) return 0;
  const double l = std::exp(mu), m = l - x0, s = sigma * l;
  const double z = z_ms(x, m, s, x0);
  return std::exp(-0.5 * z * z - 0.5 * kLn2Pi - std::log(sigma * (x + x0)) - log_surv(z_ms(0, m, s, x0)));
}

double eq7_cdf(double x, double mu, double sigma, double x0) {
  if (!(x > 0)) return 0;
  const double l = std::exp(mu), m = l - x0, s = sigma * l;
  return 1 - std::exp(log_surv(z_ms(x, m, s, x0)) - log_surv(z_ms(0, m, s, x0)));
}

Fit fit_truncated_normal(const Vec& x, double delta) {
  check_positive(x, "the truncated normal");
  const double mean = mean_of(x), sd = sd_of(x);
  const auto nll = [&x](const Vec& t) {
    const double m = t[0], s = std::exp(t[1]);
    double sum = 0;
    for (double v : x) sum += 0.5 * ((v - m) / s) * ((v - m) / s);
    return sum + double(x.size()) * (std::log(s) + 0.5 * kLn2Pi + log_surv(-m / s));
  };
  const std::vector<Coord> cs{{"m", mean - 1e3 * sd, mean + 1e3 * sd, 0.1 * sd, false},
                              {"s", std::log(sd) - 15, std::log(sd) + 10, 0.1, true}};
  Fit f = fit_plain("normal", cs, nll, {{mean, std::log(sd)}, {0.5 * mean, std::log(2 * sd)}}, delta);
  const double m = f.params[0].value, s = f.params[1].value;
  f.pdf = [m, s](double v) { return v > 0 ? std::exp(-0.5 * ((v - m) / s) * ((v - m) / s) - std::log(s) - 0.5 * kLn2Pi - log_surv(-m / s)) : 0.0; };
  f.cdf = ks_cdf_guard([m, s](double v) { return v > 0 ? 1 - std::exp(log_surv((v - m) / s) - log_surv(-m / s)) : 0.0; });
  finish_ks(f, x);
  return f;
}

LogNormalFit fit_truncated_lognormal(const Vec& x, double delta) {
  check_positive(x, "Eq. 7 (truncated log-normal)");
  const double mean = mean_of(x), sd = sd_of(x);
  const double lx_lo = std::log(1e-8 * mean), lx_hi = std::log(1e6 * mean);  // x0 past 1e6 means: the Gaussian limit
  // Search in (m, ln s, ln x0) (see z_ms): well conditioned up to the Gaussian limit.
  const auto nll = [&x, lx_lo, lx_hi](const Vec& t) {
    const double m = t[0], s = std::exp(t[1]), x0 = std::exp(t[2]);
    if (!(t[2] >= lx_lo && t[2] <= lx_hi) || !(m + x0 > 0) || !(s > 0) || !std::isfinite(s)) return kHuge;
    return eq7_nll_ms(x, m, s, x0);
  };
  // Starts: mu, sigma from the moments of ln(x + x0) for x0 over four decades of the mean.
  std::vector<Vec> starts;
  for (double f0 : {0.02, 0.1, 0.5, 2.0, 10.0, 100.0}) {
    Vec y;
    for (double v : x) y.push_back(std::log(v + f0 * mean));
    const double l = std::exp(mean_of(y));
    starts.push_back({l - f0 * mean, std::log(sd_of(y) * l), std::log(f0 * mean)});
  }
  const double sm = 0.1 * sd;
  // The reported mu, sigma, x0 (kneib2017's), each profiled with well-conditioned free coordinates.
  const auto bad = [](const Vec& t) { return Vec{t[0], std::nan(""), std::nan("")}; };
  const std::vector<Coord> cs{
      {"mu", -50, lx_hi + 5, 0.1, false, [](const Vec& t) { return std::log(t[0] + std::exp(t[2])); },
       [bad](double mu, const Vec& f) {  // free m, ln s: x0 = e^mu - m
         const double x0 = std::exp(mu) - f[0];
         return x0 > 0 ? Vec{f[0], f[1], std::log(x0)} : bad(f);
       },
       [](const Vec& t) { return Vec{t[0], t[1]}; }, {sm, 0.1}},
      {"sigma", -30, 5, 0.1, true, [](const Vec& t) { return t[1] - std::log(t[0] + std::exp(t[2])); },
       [bad](double ls, const Vec& f) {  // free m, ln x0: s = sigma (m + x0)
         const double l = f[0] + std::exp(f[1]);
         return l > 0 ? Vec{f[0], ls + std::log(l), f[1]} : bad(f);
       },
       [](const Vec& t) { return Vec{t[0], t[2]}; }, {sm, 0.2}},
      {"x0", lx_lo, lx_hi, 0.2, true, [](const Vec& t) { return t[2]; },
       [](double lx, const Vec& f) { return Vec{f[0], f[1], lx}; },  // free m, ln s
       [](const Vec& t) { return Vec{t[0], t[1]}; }, {sm, 0.1}}};
  LogNormalFit r;
  r.starts = static_cast<int>(starts.size());
  r.eq7 = fit_coords("eq7", cs, nll, starts, {sm, 0.1, 0.2}, delta);
  if (r.eq7.params[2].ci.hi_open) {  // x0 -> inf drags mu -> inf and sigma -> 0 with it
    r.eq7.params[0].ci.hi = kInf;
    r.eq7.params[0].ci.hi_open = true;
    r.eq7.params[1].ci.lo = 0;
    r.eq7.params[1].ci.lo_open = true;
  }
  const double mu = r.eq7.params[0].value, sg = r.eq7.params[1].value, x0 = r.eq7.params[2].value;
  r.eq7.pdf = [=](double v) { return eq7_pdf(v, mu, sg, x0); };
  r.eq7.cdf = ks_cdf_guard([=](double v) { return eq7_cdf(v, mu, sg, x0); });
  finish_ks(r.eq7, x);
  r.normal = fit_truncated_normal(x, delta);
  // Eq. 7 tends to the truncated normal as x0 -> inf (nested, at the boundary): when the
  // likelihood gains less than delta over that limit, x0 = inf lies inside the 95 % region.
  r.gaussian_limit = r.eq7.loglik - r.normal.loglik < delta || r.eq7.params[2].ci.hi_open;
  return r;
}

Fit fit_eq8(const Vec& x, double delta) {
  check_positive(x, "Eq. 8 (q-model)");
  double sl = 0, sx = 0;
  for (double v : x) {
    sl += std::log(v);
    sx += v;
  }
  const double n = double(x.size());
  const auto nll = [=](const Vec& t) {
    const double k = std::exp(t[0]);
    return -(n * (k * std::log(k) - gsl_sf_lngamma(k)) + (k - 1) * sl - k * sx);
  };
  const double sd = sd_of(x);
  const std::vector<Coord> cs{{"k", -10, 10, 0.1, true}};
  Fit f = fit_plain("eq8", cs, nll, {{std::log(1 / (sd * sd))}, {0.0}}, delta);
  const double k = f.params[0].value;
  f.pdf = [k](double v) { return v > 0 ? gsl_ran_gamma_pdf(v, k, 1 / k) : 0.0; };
  f.cdf = [k](double v) { return v > 0 ? gsl_cdf_gamma_P(v, k, 1 / k) : 0.0; };
  finish_ks(f, x);
  return f;
}

namespace {
// Eq. 9 pieces: integral_0^x e^{-beta t}(1 - b e^{-t^2}) dt, with
// integral_0^x e^{-t^2 - beta t} dt = (sqrt(pi)/2) e^{beta^2/4} [erfc(beta/2) - erfc(x + beta/2)].
double eq9_partial(double x, double b, double beta) {
  const double e1 = (x == kInf) ? 1 / beta : -std::expm1(-beta * x) / beta;
  const double q = beta * beta / 4;
  const double g0 = std::exp(q + gsl_sf_log_erfc(beta / 2));
  const double gx = (x == kInf) ? 0.0 : std::exp(q + gsl_sf_log_erfc(x + beta / 2));
  return e1 - b * 0.5 * std::sqrt(M_PI) * (g0 - gx);
}
}  // namespace

Fit fit_eq9(const Vec& x, double delta) {
  check_positive(x, "Eq. 9");
  const auto nll = [&x](const Vec& t) {
    const double b = t[0], beta = std::exp(t[1]);
    const double norm = eq9_partial(kInf, b, beta);
    if (!(norm > 0) || b > 1) return kHuge;
    double sum = 0;
    for (double v : x) sum += std::log1p(-b * std::exp(-v * v)) - beta * v;
    return -(sum - double(x.size()) * std::log(norm));
  };
  const double lb = std::log(1 / mean_of(x));
  const std::vector<Coord> cs{{"b", -50, 1, 0.1, false}, {"beta", -10, 10, 0.1, true}};
  Fit f = fit_plain("eq9", cs, nll, {{-0.5, lb}, {0.0, lb}, {0.5, lb}, {0.9, lb + 0.3}}, delta);
  const double b = f.params[0].value, beta = f.params[1].value, a = 1 / eq9_partial(kInf, b, beta);
  Param pa{"a", a, Interval{}};
  pa.ci.lo = pa.ci.hi = std::nan("");  // fixed by the normalisation
  f.params.insert(f.params.begin(), pa);
  f.pdf = [=](double v) { return v >= 0 ? a * (1 - b * std::exp(-v * v)) * std::exp(-beta * v) : 0.0; };
  f.cdf = ks_cdf_guard([=](double v) { return v > 0 ? a * eq9_partial(v, b, beta) : 0.0; });
  finish_ks(f, x);
  return f;
}

Fit fit_eq10(const Vec& x, double delta) {
  check_positive(x, "Eq. 10");
  const auto beta_of = [](double g) { return (1 + g) * std::log1p(1 / g); };  // mean 1
  const auto nll = [&x, beta_of](const Vec& t) {
    const double lg = t[0], g = std::exp(lg), beta = beta_of(g);
    double sum = 0;
    for (double v : x) sum += beta * v - 2 * log_softplus(lg + beta * v);
    return -(sum + double(x.size()) * (std::log(beta) + std::log1p(g) + lg));
  };
  const std::vector<Coord> cs{{"gamma0", -30, 30, 0.2, true}};
  Fit f = fit_plain("eq10", cs, nll, {{-3}, {-1}, {0}, {1}, {3}}, delta);
  const double g = f.params[0].value, beta = beta_of(g);
  Param pb{"beta0", beta, Interval{}};
  pb.ci.lo = pb.ci.hi = std::nan("");  // tied to gamma0 by the unit mean
  f.params.push_back(pb);
  f.pdf = [=](double v) {
    return v >= 0 ? std::exp(std::log(beta) + std::log1p(g) + std::log(g) + beta * v - 2 * log_softplus(std::log(g) + beta * v)) : 0.0;
  };
  f.cdf = ks_cdf_guard([=](double v) { return v > 0 ? 1 - (1 + g) * std::exp(-log_softplus(std::log(g) + beta * v)) : 0.0; });
  finish_ks(f, x);
  return f;
}

}  // namespace sable::analysis
