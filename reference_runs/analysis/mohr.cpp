// Mohr circles and their envelope, power-law fits, petit2017 Eq. 9 by quadrature and inverted,
// its Eq. 6 bulk modulus, the offset power law of its Eq. 7, envelopes per cycle, Eq. 10 entropy.
#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "reference_runs/analysis/analysis.h"

namespace sable::analysis {

Circle mohr_circle(double s1, double s3) { return {0.5 * (s1 + s3), 0.5 * std::fabs(s1 - s3)}; }

void principal_2d(double sxx, double syy, double sxy, double& s1, double& s3) {
  const double c = 0.5 * (sxx + syy), r = std::hypot(0.5 * (sxx - syy), sxy);
  s1 = c + r;
  s3 = c - r;
}

// The line |tau| = C + mu sigma is tangent to circle i when the distance from its
// centre, (C + mu c_i) / sqrt(1 + mu^2) = C cos(phi) + sin(phi) c_i, equals r_i: so
// least squares on (distance - radius) is the straight-line fit r = a + b c, with
// b = sin(phi), a = C cos(phi). mu = tan(phi), C = a / cos(phi).
Envelope mohr_envelope(const std::vector<Circle>& circles) {
  const std::size_t n = circles.size();
  if (n < 2) throw Error("mohr-envelope needs at least 2 circles");
  Vec c, r;
  for (auto& k : circles) {
    c.push_back(k.centre);
    r.push_back(k.radius);
  }
  double a, b, c00, c01, c11, ss;
  gsl_fit_linear(c.data(), 1, r.data(), 1, n, &a, &b, &c00, &c01, &c11, &ss);
  if (!(std::fabs(b) < 1)) throw Error("mohr-envelope: radius grows as fast as the centre (sin(phi) >= 1): no tangent line");
  if (n == 2) c00 = c01 = c11 = 0;  // two circles: the line is exact, no scatter to estimate from
  const double q = 1 - b * b, cq = std::sqrt(q);
  Envelope e;
  e.mu = b / cq;
  e.c = a / cq;
  e.phi = std::asin(b);
  const double dmu_db = 1 / (q * cq), dc_da = 1 / cq, dc_db = a * b / (q * cq);  // delta method
  e.mu_err = std::sqrt(dmu_db * dmu_db * c11);
  e.c_err = std::sqrt(dc_da * dc_da * c00 + 2 * dc_da * dc_db * c01 + dc_db * dc_db * c11);
  e.cov = dmu_db * (dc_da * c01 + dc_db * c11);
  e.rms = std::sqrt(ss / double(n));
  return e;
}

namespace {
void check_xy(const Vec& x, const Vec& y, const Vec& yerr) {
  if (x.size() != y.size() || (!yerr.empty() && yerr.size() != x.size()))
    throw Error("power-law: x, y (and y errors) must have the same length");
  if (x.size() < 3) throw Error("power-law: needs at least 3 points");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0)) throw Error("power-law: point " + std::to_string(i + 1) + " is not positive");
    if (!yerr.empty() && !(yerr[i] > 0)) throw Error("power-law: error of point " + std::to_string(i + 1) + " is not positive");
  }
}
}  // namespace

PowerLaw power_law_loglog(const Vec& x, const Vec& y, const Vec& yerr, double x0) {
  check_xy(x, y, yerr);
  const std::size_t n = x.size();
  Vec lx, ly, w;
  for (std::size_t i = 0; i < n; ++i) {
    lx.push_back(std::log(x[i] / x0));
    ly.push_back(std::log(y[i]));
    if (!yerr.empty()) w.push_back((y[i] / yerr[i]) * (y[i] / yerr[i]));  // sd(ln y) = yerr / y
  }
  double c0, c1, c00, c01, c11, chi2;
  if (w.empty())
    gsl_fit_linear(lx.data(), 1, ly.data(), 1, n, &c0, &c1, &c00, &c01, &c11, &chi2);  // cov from the scatter
  else
    gsl_fit_wlinear(lx.data(), 1, w.data(), 1, ly.data(), 1, n, &c0, &c1, &c00, &c01, &c11, &chi2);
  PowerLaw p;
  p.method = w.empty() ? "loglog" : "loglog-weighted";
  p.x0 = x0;
  p.k0 = std::exp(c0);
  p.alpha = c1;
  p.k0_err = p.k0 * std::sqrt(c00);
  p.alpha_err = std::sqrt(c11);
  p.cov = p.k0 * c01;
  p.chi2 = chi2;
  p.dof = n - 2;
  return p;
}

namespace {
struct PlData {
  const Vec *x, *y, *e;
  double x0;
};
int pl_f(const gsl_vector* t, void* d, gsl_vector* f) {
  auto* p = static_cast<PlData*>(d);
  const double k0 = gsl_vector_get(t, 0), a = gsl_vector_get(t, 1);
  for (std::size_t i = 0; i < p->x->size(); ++i) {
    const double s = p->e->empty() ? 1.0 : (*p->e)[i];
    gsl_vector_set(f, i, (k0 * std::pow((*p->x)[i] / p->x0, a) - (*p->y)[i]) / s);
  }
  return GSL_SUCCESS;
}
int pl_df(const gsl_vector* t, void* d, gsl_matrix* j) {
  auto* p = static_cast<PlData*>(d);
  const double k0 = gsl_vector_get(t, 0), a = gsl_vector_get(t, 1);
  for (std::size_t i = 0; i < p->x->size(); ++i) {
    const double s = p->e->empty() ? 1.0 : (*p->e)[i], u = (*p->x)[i] / p->x0, pw = std::pow(u, a);
    gsl_matrix_set(j, i, 0, pw / s);
    gsl_matrix_set(j, i, 1, k0 * pw * std::log(u) / s);
  }
  return GSL_SUCCESS;
}
}  // namespace

PowerLaw power_law_nls(const Vec& x, const Vec& y, const Vec& yerr, double x0) {
  const PowerLaw start = power_law_loglog(x, y, yerr, x0);
  const std::size_t n = x.size();
  PlData data{&x, &y, &yerr, x0};
  gsl_multifit_nlinear_fdf fdf{};
  fdf.f = pl_f;
  fdf.df = pl_df;
  fdf.n = n;
  fdf.p = 2;
  fdf.params = &data;
  gsl_multifit_nlinear_parameters prm = gsl_multifit_nlinear_default_parameters();
  gsl_multifit_nlinear_workspace* w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &prm, n, 2);
  double t0[2] = {start.k0, start.alpha};
  gsl_vector_view tv = gsl_vector_view_array(t0, 2);
  gsl_multifit_nlinear_init(&tv.vector, &fdf, w);
  int info = 0;
  const int status = gsl_multifit_nlinear_driver(200, 1e-12, 1e-12, 1e-12, nullptr, nullptr, &info, w);
  gsl_matrix* cov = gsl_matrix_alloc(2, 2);
  gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 0.0, cov);
  double chi2 = 0;
  gsl_blas_ddot(gsl_multifit_nlinear_residual(w), gsl_multifit_nlinear_residual(w), &chi2);
  const double scale = yerr.empty() ? chi2 / double(n - 2) : 1.0;  // no errors given: from the scatter
  PowerLaw p;
  p.method = yerr.empty() ? "nls" : "nls-weighted";
  p.x0 = x0;
  p.k0 = gsl_vector_get(gsl_multifit_nlinear_position(w), 0);
  p.alpha = gsl_vector_get(gsl_multifit_nlinear_position(w), 1);
  p.k0_err = std::sqrt(scale * gsl_matrix_get(cov, 0, 0));
  p.alpha_err = std::sqrt(scale * gsl_matrix_get(cov, 1, 1));
  p.cov = scale * gsl_matrix_get(cov, 0, 1);
  p.chi2 = chi2;
  p.dof = n - 2;
  gsl_matrix_free(cov);
  gsl_multifit_nlinear_free(w);
  if (status != GSL_SUCCESS) throw Error("power-law: nonlinear least squares did not converge");
  return p;
}

namespace {
struct Eq9Data {
  const std::function<double(double)>* p;
  double phi_m;
  bool weight_only;
};
double eq9_integrand(double phi, void* d) {
  auto* e = static_cast<Eq9Data*>(d);
  const double p = (*e->p)(phi);
  return e->weight_only ? p : p * std::tan(2.0 / 3.0 * (e->phi_m - phi + M_PI / 4));
}
}  // namespace

Eq9 quad_eq9(const std::function<double(double)>& p, double mu, double phi_min, Vec breaks) {
  Eq9 r;
  const double phi_m = std::atan(mu);
  r.phi_max = phi_m + M_PI / 4;
  if (!(phi_min < r.phi_max)) throw Error("quad-eq9: phi_min must lie below phi_max = atan(mu) + pi/4");
  if (!(2.0 / 3.0 * (r.phi_max - phi_min) < M_PI / 2))
    throw Error("quad-eq9: phi_min so low that tan(2/3 (phi_m - phi + pi/4)) reaches pi/2 inside the range");
  // qagp: a tabulated P has kinks or steps at its nodes; they become break points.
  Vec pts{phi_min};
  std::sort(breaks.begin(), breaks.end());
  for (double b : breaks)
    if (b > pts.back() && b < r.phi_max) pts.push_back(b);
  pts.push_back(r.phi_max);
  gsl_integration_workspace* ws = gsl_integration_workspace_alloc(4000);
  Eq9Data d{&p, phi_m, false};
  gsl_function f{&eq9_integrand, &d};
  double err2 = 0;
  const int s1 = gsl_integration_qagp(&f, pts.data(), pts.size(), 0, 1e-10, 4000, ws, &r.mu_m, &r.abserr);
  d.weight_only = true;
  const int s2 = gsl_integration_qagp(&f, pts.data(), pts.size(), 0, 1e-10, 4000, ws, &r.weight, &err2);
  gsl_integration_workspace_free(ws);
  if ((s1 != GSL_SUCCESS && s1 != GSL_EROUND) || (s2 != GSL_SUCCESS && s2 != GSL_EROUND)) throw Error("quad-eq9: the quadrature did not converge");
  if (!(r.weight > 0)) throw Error("quad-eq9: P(phi) has no weight in [phi_min, phi_max]");
  r.mu_m_window = r.mu_m / r.weight;
  return r;
}

// ---------- petit2017 Eqs. 6, 7, 8 per cycle, 9 inverted, 10 ----------

namespace {
double at_or(const Vec& v, std::size_t i, double def) { return v.empty() ? def : v[i]; }
void same_length(const char* what, std::size_t n, std::initializer_list<const Vec*> cols) {
  for (const Vec* c : cols)
    if (!c->empty() && c->size() != n) throw Error(std::string(what) + ": the columns have different lengths");
}
}  // namespace

std::vector<BulkPoint> bulk_modulus(const Vec& syy, const Vec& sxx, const Vec& eyy, const Vec& cycle, const Vec& loading) {
  const std::size_t n = syy.size();
  if (sxx.size() != n || eyy.size() != n) throw Error("bulk-modulus: syy, sxx, eyy have different lengths");
  same_length("bulk-modulus", n, {&cycle, &loading});
  std::vector<BulkPoint> out;
  for (std::size_t i = 1; i < n; ++i) {
    const bool same = at_or(cycle, i, 0) == at_or(cycle, i - 1, 0);
    if (!same || at_or(loading, i, 1) == 0 || at_or(loading, i - 1, 1) == 0) continue;  // not one loading branch
    const double de = eyy[i] - eyy[i - 1];
    if (de == 0) throw Error("bulk-modulus: rows " + std::to_string(i) + " and " + std::to_string(i + 1) + " have the same strain");
    BulkPoint b;
    b.row = i;
    b.cycle = at_or(cycle, i, 0);
    b.syy = syy[i];
    b.syy_mid = 0.5 * (syy[i] + syy[i - 1]);
    b.eyy = eyy[i];
    b.k = (syy[i] - syy[i - 1] + 2 * (sxx[i] - sxx[i - 1])) / (3 * de);  // Eq. 6
    out.push_back(b);
  }
  if (out.empty()) throw Error("bulk-modulus: no two successive loading states in one cycle");
  return out;
}

double offset_power(double s, double k0, double a, double alpha, double s0) {
  const double u = s / s0 - 1;
  return k0 + (u > 0 ? a * std::pow(u, alpha) : 0.0);
}

LsqFit fit_offset_power(const Vec& s, const Vec& k, const Vec& kerr, double s0) {
  lsq::check("fit-offset-power", s, k, kerr, 3);
  if (!(s0 > 0)) throw Error("fit-offset-power: sigma0 must be positive");
  const std::size_t n = s.size();
  Vec u(n);
  for (std::size_t i = 0; i < n; ++i) {
    u[i] = s[i] / s0 - 1;
    if (u[i] < -1e-12) throw Error("fit-offset-power: point " + std::to_string(i + 1) + " lies below sigma0");
    u[i] = std::max(u[i], 0.0);
  }
  const Vec w = lsq::weights(kerr, n);
  // K is linear in (K0, a) at fixed alpha: scan alpha for the start.
  const auto pw = [](double x, double al) { return x > 0 ? std::pow(x, al) : 0.0; };
  const Vec t0 = lsq::scan_linear(pw, u, k, w, 0.02, 3.0, 300);
  const lsq::Residuals res = [&](const Vec& t, Vec& f, Vec* j) {
    for (std::size_t i = 0; i < n; ++i) {
      const double p = pw(u[i], t[2]), sd = 1 / std::sqrt(w[i]);
      f[i] = (t[0] + t[1] * p - k[i]) / sd;
      if (j) {
        (*j)[3 * i] = 1 / sd;
        (*j)[3 * i + 1] = p / sd;
        (*j)[3 * i + 2] = u[i] > 0 ? t[1] * p * std::log(u[i]) / sd : 0.0;
      }
    }
  };
  const lsq::Nls r = lsq::solve(res, n, t0);
  if (!r.converged) throw Error("fit-offset-power: nonlinear least squares did not converge");
  LsqFit f = lsq::start("offset-power", n, 3, !kerr.empty());
  f.chi2 = r.chi2;
  const double scale = f.weighted ? 1.0 : f.chi2 / double(f.dof);
  f.q = lsq::quantile95(f.weighted, f.dof);
  const char* names[] = {"K0", "a", "alpha"};
  for (int i = 0; i < 3; ++i) f.params.push_back(lsq::symmetric(names[i], r.theta[i], std::sqrt(scale * r.cov[4 * i]), f.q));
  Vec fit;
  for (double v : s) fit.push_back(offset_power(v, r.theta[0], r.theta[1], r.theta[2], s0));
  f.r2 = lsq::r_squared(k, fit, w);
  return f;
}

std::vector<CycleEnvelope> cycle_envelopes(const std::vector<Circle>& circles, const Vec& cycle, const Vec& loading) {
  same_length("mohr-cycles", circles.size(), {&cycle, &loading});
  if (cycle.size() != circles.size()) throw Error("mohr-cycles: one cycle number per circle");
  std::vector<double> order;
  std::map<double, std::vector<Circle>> by;
  for (std::size_t i = 0; i < circles.size(); ++i) {
    if (at_or(loading, i, 1) == 0) continue;
    if (!by.count(cycle[i])) order.push_back(cycle[i]);
    by[cycle[i]].push_back(circles[i]);
  }
  std::vector<CycleEnvelope> out;
  for (double c : order) {
    const auto& v = by[c];
    if (v.size() < 2) throw Error("mohr-cycles: cycle " + std::to_string(c) + " has fewer than 2 loading circles");
    out.push_back({c, v.size(), mohr_envelope(v)});
  }
  return out;
}

long limit_cycle(const Vec& mu, double tol) {
  for (std::size_t k = 0; k + 1 < mu.size(); ++k) {
    bool settled = true;
    for (std::size_t j = k + 1; j < mu.size() && settled; ++j) settled = std::fabs(mu[j] - mu[k]) <= tol * std::fabs(mu[k]);
    if (settled) return static_cast<long>(k);
  }
  return -1;
}

namespace {
struct Eq9Root {
  const std::function<double(double)>* p;
  const Vec* breaks;
  double mu, target;
  bool window;
};
double eq9_miss(double phi_min, void* d) {
  auto* r = static_cast<Eq9Root*>(d);
  const Eq9 q = quad_eq9(*r->p, r->mu, phi_min, *r->breaks);
  return (r->window ? q.mu_m_window : q.mu_m) - r->target;
}
}  // namespace

double phi_min_eq9(const std::function<double(double)>& p, double mu, double mu_m, bool window, const Vec& breaks) {
  const double phi_max = std::atan(mu) + M_PI / 4, span = 0.75 * M_PI;
  double lo = phi_max - span * (1 - 1e-6), hi = phi_max - 1e-9;  // inside, where quad_eq9 is finite
  Eq9Root d{&p, &breaks, mu, mu_m, window};
  const double flo = eq9_miss(lo, &d), fhi = eq9_miss(hi, &d);
  if (!(flo >= 0 && fhi <= 0))
    throw Error("phi-min-eq9: mu_M = " + std::to_string(mu_m) + " is not reached: Eq. 9 gives " + std::to_string(fhi + mu_m) +
                " near phi_max and " + std::to_string(flo + mu_m) + " near phi_max - 3 pi/4");
  gsl_set_error_handler_off();
  gsl_function f{&eq9_miss, &d};
  gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_root_fsolver_set(s, &f, lo, hi);
  int status = GSL_CONTINUE;
  for (int it = 0; it < 200 && status == GSL_CONTINUE; ++it) {
    gsl_root_fsolver_iterate(s);
    lo = gsl_root_fsolver_x_lower(s);
    hi = gsl_root_fsolver_x_upper(s);
    status = gsl_root_test_interval(lo, hi, 1e-12, 0);
  }
  const double root = gsl_root_fsolver_root(s);
  gsl_root_fsolver_free(s);
  if (status != GSL_SUCCESS) throw Error("phi-min-eq9: Brent's method did not converge");
  return root;
}

double fold_angle(double phi) {
  constexpr double half = M_PI / 2, slack = 1e-12;  // +-pi/2 themselves (and round-off about them) stay where they are
  while (phi > half + slack) phi -= M_PI;
  while (phi < -half - slack) phi += M_PI;
  return std::clamp(phi, -half, half);
}

Entropy contact_entropy(const Vec& phi, int nbins) {
  if (phi.empty()) throw Error("entropy: no angles");
  Vec f;
  for (double v : phi) f.push_back(fold_angle(v));
  Entropy e;
  e.h = histogram(f, nbins, false, false, -M_PI / 2, M_PI / 2);
  for (double c : e.h.counts) {
    e.p.push_back(c / double(f.size()));
    if (c > 0) e.s -= e.p.back() * std::log(e.p.back());  // 0 ln 0 = 0
  }
  return e;
}

}  // namespace sable::analysis
