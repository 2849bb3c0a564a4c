// The lid-driven cavity study (kneib2017, issue 43): the Eq. 4 / Eq. 20 sigmoid and the
// Eq. 5 line by least squares, the vortex centre from the mean velocity field, and the
// local rheology (Eqs. 16-19) from mean velocity and stress fields on a grid.
#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_multifit_nlinear.h>

#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <map>

#include "reference_runs/analysis/analysis.h"

namespace sable::analysis {

// ---------- least squares (shared with mohr.cpp's petit2017 Eq. 7 fit) ----------

namespace lsq {

void check(const char* what, const Vec& x, const Vec& y, const Vec& yerr, std::size_t np) {
  if (x.size() != y.size() || (!yerr.empty() && yerr.size() != x.size()))
    throw Error(std::string(what) + ": x, y (and y errors) must have the same length");
  if (x.size() <= np) throw Error(std::string(what) + ": needs more than " + std::to_string(np) + " points");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) throw Error(std::string(what) + ": point " + std::to_string(i + 1) + " is not finite");
    if (!yerr.empty() && !(yerr[i] > 0)) throw Error(std::string(what) + ": error of point " + std::to_string(i + 1) + " is not positive");
  }
}

Vec weights(const Vec& yerr, std::size_t n) {
  Vec w(n, 1.0);
  for (std::size_t i = 0; i < yerr.size(); ++i) w[i] = 1 / (yerr[i] * yerr[i]);
  return w;
}

// R^2 = 1 - SS_res/SS_tot about the (weighted) mean.
double r_squared(const Vec& y, const Vec& fit, const Vec& w) {
  double sw = 0, swy = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    sw += w[i];
    swy += w[i] * y[i];
  }
  const double m = swy / sw;
  double res = 0, tot = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    res += w[i] * (y[i] - fit[i]) * (y[i] - fit[i]);
    tot += w[i] * (y[i] - m) * (y[i] - m);
  }
  return tot > 0 ? 1 - res / tot : std::nan("");
}

// Known errors: the normal quantile; errors from the scatter: Student t with dof.
LsqFit start(const std::string& model, std::size_t n, std::size_t np, bool weighted) {
  LsqFit f;
  f.model = model;
  f.n = n;
  f.dof = n - np;
  f.weighted = weighted;
  return f;
}

double quantile95(bool weighted, std::size_t dof) {
  return weighted ? gsl_cdf_ugaussian_Pinv(0.975) : gsl_cdf_tdist_Pinv(0.975, double(dof));
}

LsqParam symmetric(const std::string& name, double v, double err, double q) { return {name, v, err, v - q * err, v + q * err}; }

Vec scan_linear(const std::function<double(double, double)>& s, const Vec& x, const Vec& y, const Vec& w, double t0, double t1,
                int steps) {
  Vec best{y.front(), 0.0, 0.5 * (t0 + t1)}, sx(x.size());
  double best_chi2 = kInf;
  for (int k = 0; k <= steps; ++k) {
    const double t = t0 + (t1 - t0) * k / double(steps);
    for (std::size_t i = 0; i < x.size(); ++i) sx[i] = s(x[i], t);
    double c0, c1, c00, c01, c11, chi2;
    if (gsl_fit_wlinear(sx.data(), 1, w.data(), 1, y.data(), 1, x.size(), &c0, &c1, &c00, &c01, &c11, &chi2) != GSL_SUCCESS) continue;
    if (std::isfinite(chi2) && chi2 < best_chi2) {
      best_chi2 = chi2;
      best = {c0, c1, t};
    }
  }
  return best;
}

namespace {
struct Problem {
  const Residuals* r;
  std::size_t n, p;
};
int trampoline_f(const gsl_vector* t, void* d, gsl_vector* f) {
  auto* q = static_cast<Problem*>(d);
  Vec th(t->data, t->data + q->p), fv(q->n), jac;
  (*q->r)(th, fv, nullptr);
  for (std::size_t i = 0; i < q->n; ++i) gsl_vector_set(f, i, fv[i]);
  return GSL_SUCCESS;
}
int trampoline_df(const gsl_vector* t, void* d, gsl_matrix* j) {
  auto* q = static_cast<Problem*>(d);
  Vec th(t->data, t->data + q->p), fv(q->n), jac(q->n * q->p);
  (*q->r)(th, fv, &jac);
  for (std::size_t i = 0; i < q->n; ++i)
    for (std::size_t k = 0; k < q->p; ++k) gsl_matrix_set(j, i, k, jac[i * q->p + k]);
  return GSL_SUCCESS;
}
}  // namespace

Nls solve(const Residuals& r, std::size_t n, Vec t0, int max_iter) {
  gsl_set_error_handler_off();
  const std::size_t p = t0.size();
  Problem prob{&r, n, p};
  gsl_multifit_nlinear_fdf fdf{};
  fdf.f = trampoline_f;
  fdf.df = trampoline_df;
  fdf.n = n;
  fdf.p = p;
  fdf.params = &prob;
  gsl_multifit_nlinear_parameters prm = gsl_multifit_nlinear_default_parameters();
  gsl_multifit_nlinear_workspace* ws = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &prm, n, p);
  gsl_vector_view tv = gsl_vector_view_array(t0.data(), p);
  gsl_multifit_nlinear_init(&tv.vector, &fdf, ws);
  int info = 0;
  Nls out;
  out.status = gsl_multifit_nlinear_driver(max_iter, 1e-12, 1e-12, 1e-12, nullptr, nullptr, &info, ws);
  gsl_matrix* cov = gsl_matrix_alloc(p, p);
  gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(ws), 0.0, cov);
  gsl_blas_ddot(gsl_multifit_nlinear_residual(ws), gsl_multifit_nlinear_residual(ws), &out.chi2);
  const gsl_vector* th = gsl_multifit_nlinear_position(ws);
  out.theta.assign(th->data, th->data + p);
  out.cov.assign(cov->data, cov->data + p * p);  // (J^T J)^-1, p x p row-major (tda = p)
  gsl_matrix_free(cov);
  gsl_multifit_nlinear_free(ws);
  // GSL_ENOPROG: no step lowers chi2 any further (exact data reach it at the minimum).
  out.converged = out.status == GSL_SUCCESS || out.status == GSL_ENOPROG;
  return out;
}

}  // namespace lsq

namespace {

using namespace lsq;

double sig_s(double x, double lx0) { return 1 / (1 + std::exp(lx0) / x); }  // the weight of b

// For fixed ln x0 the model is linear in (a, b - a): scan ln x0, keep the best chi2.
Vec sigmoid_start(const Vec& x, const Vec& y, const Vec& w) {
  const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
  const Vec s = scan_linear(sig_s, x, y, w, std::log(*xmin) - 3, std::log(*xmax) + 3, 240);
  return {s[0], s[0] + s[1], s[2]};
}

}  // namespace

double sigmoid(double x, double a, double b, double x0) { return a + (b - a) / (1 + x0 / x); }

LsqFit fit_sigmoid(const Vec& x, const Vec& y, const Vec& yerr) {
  check("fit-sigmoid", x, y, yerr, 3);
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!(x[i] > 0)) throw Error("fit-sigmoid: x of point " + std::to_string(i + 1) + " is not positive");
  const std::size_t n = x.size();
  const Vec w = weights(yerr, n);
  const Residuals res = [&](const Vec& t, Vec& f, Vec* j) {  // in (a, b, ln x0)
    for (std::size_t i = 0; i < n; ++i) {
      const double s = sig_s(x[i], t[2]), sd = 1 / std::sqrt(w[i]);
      f[i] = (t[0] + (t[1] - t[0]) * s - y[i]) / sd;
      if (j) {
        (*j)[3 * i] = (1 - s) / sd;
        (*j)[3 * i + 1] = s / sd;
        (*j)[3 * i + 2] = -(t[1] - t[0]) * s * (1 - s) / sd;  // ds/d ln x0 = -s (1 - s)
      }
    }
  };
  const Nls r = solve(res, n, sigmoid_start(x, y, w));
  if (!r.converged) throw Error("fit-sigmoid: nonlinear least squares did not converge");
  LsqFit f = start("sigmoid", n, 3, !yerr.empty());
  f.chi2 = r.chi2;
  const double scale = f.weighted ? 1.0 : f.chi2 / double(f.dof);  // no errors given: from the scatter
  f.q = quantile95(f.weighted, f.dof);
  const double a = r.theta[0], b = r.theta[1], lx = r.theta[2];
  const double ea = std::sqrt(scale * r.cov[0]), eb = std::sqrt(scale * r.cov[4]), elx = std::sqrt(scale * r.cov[8]);
  const double x0 = std::exp(lx);
  f.params = {symmetric("a", a, ea, f.q), symmetric("b", b, eb, f.q),
              {"x0", x0, x0 * elx, std::exp(lx - f.q * elx), std::exp(lx + f.q * elx)}};  // err: delta method
  Vec fit;
  for (double v : x) fit.push_back(sigmoid(v, a, b, x0));
  f.r2 = r_squared(y, fit, w);
  return f;
}

LsqFit fit_linear_down(const Vec& x, const Vec& y, const Vec& yerr) {
  check("fit-linear", x, y, yerr, 2);
  const std::size_t n = x.size();
  const Vec w = weights(yerr, n);
  LsqFit f = start("linear", n, 2, !yerr.empty());
  double c0, c1, c00, c01, c11;
  // gsl_fit_linear scales its covariance by the residual variance; gsl_fit_wlinear takes the errors as known.
  const int st = f.weighted ? gsl_fit_wlinear(x.data(), 1, w.data(), 1, y.data(), 1, n, &c0, &c1, &c00, &c01, &c11, &f.chi2)
                            : gsl_fit_linear(x.data(), 1, y.data(), 1, n, &c0, &c1, &c00, &c01, &c11, &f.chi2);
  if (st != GSL_SUCCESS || !std::isfinite(c1)) throw Error("fit-linear: the x values do not spread (no slope)");
  f.q = quantile95(f.weighted, f.dof);
  f.params = {symmetric("c1", c0, std::sqrt(c00), f.q), symmetric("c2", -c1, std::sqrt(c11), f.q)};
  Vec fit;
  for (double v : x) fit.push_back(c0 + c1 * v);
  f.r2 = r_squared(y, fit, w);
  return f;
}

// ---------- grids ----------

namespace {

// Distinct coordinates (equal within 1e-9 of the span), evenly spaced within 1e-6 of a spacing.
Vec distinct(Vec v, const char* axis) {
  std::sort(v.begin(), v.end());
  const double span = v.back() - v.front();
  Vec u{v.front()};
  for (double a : v)
    if (a - u.back() > 1e-9 * std::max(span, 1e-300)) u.push_back(a);
  if (u.size() < 2) throw Error(std::string("grid: a single ") + axis + " coordinate");
  const double h = (u.back() - u.front()) / double(u.size() - 1);
  for (std::size_t i = 0; i < u.size(); ++i)
    if (std::fabs(u[i] - (u.front() + double(i) * h)) > 1e-6 * h)
      throw Error(std::string("grid: the ") + axis + " coordinates are not evenly spaced (node " + std::to_string(i + 1) + ")");
  return u;
}

std::size_t node_of(const Vec& u, double a) {
  const double h = u[1] - u[0];
  return static_cast<std::size_t>(std::llround((a - u.front()) / h));
}

double spacing(const Vec& u) { return u[1] - u[0]; }

}  // namespace

Grid2D grid_from_rows(const Vec& x, const Vec& y, const std::vector<std::pair<const Vec*, Vec Grid2D::*>>& fields) {
  if (x.size() != y.size() || x.empty()) throw Error("grid: x and y columns of different lengths (or empty)");
  for (auto& [col, dst] : fields)
    if (col->size() != x.size()) throw Error("grid: a field column's length differs from the coordinates'");
  Grid2D g;
  g.xs = distinct(x, "x");
  g.ys = distinct(y, "y");
  const std::size_t nodes = g.nx() * g.ny();
  std::vector<std::size_t> count(nodes, 0);
  for (auto& [col, dst] : fields) (g.*dst).assign(nodes, 0.0);
  for (std::size_t r = 0; r < x.size(); ++r) {
    const std::size_t k = g.at(node_of(g.xs, x[r]), node_of(g.ys, y[r]));
    ++count[k];
    for (auto& [col, dst] : fields) (g.*dst)[k] += (*col)[r];
  }
  for (std::size_t k = 0; k < nodes; ++k)
    if (count[k] != count[0])
      throw Error("grid: node (" + std::to_string(g.xs[k / g.ny()]) + ", " + std::to_string(g.ys[k % g.ny()]) + ") appears " +
                  std::to_string(count[k]) + " times, node 1 " + std::to_string(count[0]) + " (not a complete grid)");
  for (auto& [col, dst] : fields)
    for (double& v : g.*dst) v /= double(count[0]);  // several windows: their mean
  // Walls at the outer faces of the nodes' cells (fix ave/cg puts nodes at cell centres).
  g.xlo = g.xs.front() - spacing(g.xs) / 2;
  g.xhi = g.xs.back() + spacing(g.xs) / 2;
  g.ylo = g.ys.front() - spacing(g.ys) / 2;
  g.yhi = g.ys.back() + spacing(g.ys) / 2;
  return g;
}

namespace {
int axis_of(char c) { return c == 'x' ? 0 : c == 'y' ? 1 : 2; }
int component(int a, int b) {  // xx yy zz xy xz yz
  if (a == b) return a;
  return a + b == 1 ? 3 : a + b == 2 ? 4 : 5;
}
}  // namespace

Grid2D read_cg_grid(const std::string& path, const std::string& plane, const std::string& stress, std::size_t skip) {
  if (plane != "xy" && plane != "xz" && plane != "yz") throw Error("--plane: xy, xz or yz, not '" + plane + "'");
  const int h = axis_of(plane[0]), v = axis_of(plane[1]), o = 3 - h - v;
  std::vector<std::size_t> dims, d2;
  const Vec shape = read_h5_array(path, "shape", d2), bounds = read_h5_array(path, "bounds", d2);
  const std::size_t n[3] = {std::size_t(shape.at(0)), std::size_t(shape.at(1)), std::size_t(shape.at(2))};
  const std::size_t nodes = n[0] * n[1] * n[2];
  const Vec u = read_h5_array(path, "u", dims);
  const std::size_t windows = dims.empty() ? 0 : dims[0];
  if (dims.size() != 5 || dims[4] != 3 || u.size() != windows * nodes * 3) throw Error("file '" + path + "': 'u' is not [windows][nx][ny][nz][3]");
  if (skip >= windows)
    throw Error("file '" + path + "': --skip " + std::to_string(skip) + " leaves none of " + std::to_string(windows) + " windows");
  Vec s;
  if (!stress.empty()) {
    s = read_h5_array(path, stress, dims);
    if (s.size() != windows * nodes * 6) throw Error("file '" + path + "': '" + stress + "' is not [windows][nx][ny][nz][6]");
  }
  Vec samples(windows, 1.0);
  if (h5_has_dataset(path, "samples")) {
    const Vec sm = read_h5_array(path, "samples", d2);
    for (std::size_t w = 0; w < windows && w < sm.size(); ++w) samples[w] = sm[w];
  }
  Grid2D g;
  const std::string names = "xyz";
  g.xs = read_h5_array(path, std::string(1, names[h]), d2);
  g.ys = read_h5_array(path, std::string(1, names[v]), d2);
  if (g.nx() != n[h] || g.ny() != n[v] || g.nx() < 2 || g.ny() < 2) throw Error("file '" + path + "': node coordinates do not match 'shape'");
  g.xlo = bounds.at(2 * h);
  g.xhi = bounds.at(2 * h + 1);
  g.ylo = bounds.at(2 * v);
  g.yhi = bounds.at(2 * v + 1);
  const std::size_t N = g.nx() * g.ny();
  for (Vec* f : {&g.vx, &g.vy}) f->assign(N, 0.0);
  if (!s.empty())
    for (Vec* f : {&g.sxx, &g.syy, &g.szz, &g.sxy}) f->assign(N, 0.0);
  double wsum = 0;
  for (std::size_t w = skip; w < windows; ++w) wsum += samples[w];
  // Time mean over windows (weighted by their samples), plain mean over the out-of-plane nodes.
  for (std::size_t w = skip; w < windows; ++w)
    for (std::size_t k = 0; k < nodes; ++k) {
      const std::size_t idx[3] = {k / (n[1] * n[2]), (k / n[2]) % n[1], k % n[2]};
      const std::size_t m = g.at(idx[h], idx[v]);
      const double c = samples[w] / wsum / double(n[o]);
      const double* uu = &u[(w * nodes + k) * 3];
      g.vx[m] += c * uu[h];
      g.vy[m] += c * uu[v];
      if (s.empty()) continue;
      const double* ss = &s[(w * nodes + k) * 6];
      g.sxx[m] += c * ss[component(h, h)];
      g.syy[m] += c * ss[component(v, v)];
      g.szz[m] += c * ss[component(o, o)];
      g.sxy[m] += c * ss[component(h, v)];
    }
  return g;
}

// ---------- the vortex ----------

Vec stream_function(const Grid2D& g) {
  const std::size_t nx = g.nx(), ny = g.ny();
  const double hx = spacing(g.xs), hy = spacing(g.ys);
  Vec a(nx * ny), b(nx * ny);
  // a: along the bottom row (dpsi = -vy dx), then up each column (dpsi = vx dy).
  for (std::size_t i = 1; i < nx; ++i) a[g.at(i, 0)] = a[g.at(i - 1, 0)] - hx * (g.vy[g.at(i - 1, 0)] + g.vy[g.at(i, 0)]) / 2;
  for (std::size_t i = 0; i < nx; ++i)
    for (std::size_t j = 1; j < ny; ++j) a[g.at(i, j)] = a[g.at(i, j - 1)] + hy * (g.vx[g.at(i, j - 1)] + g.vx[g.at(i, j)]) / 2;
  // b: up the first column, then along each row. The two agree for a divergence-free field.
  for (std::size_t j = 1; j < ny; ++j) b[g.at(0, j)] = b[g.at(0, j - 1)] + hy * (g.vx[g.at(0, j - 1)] + g.vx[g.at(0, j)]) / 2;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 1; i < nx; ++i) b[g.at(i, j)] = b[g.at(i - 1, j)] - hx * (g.vy[g.at(i - 1, j)] + g.vy[g.at(i, j)]) / 2;
  for (std::size_t k = 0; k < a.size(); ++k) a[k] = (a[k] + b[k]) / 2;
  return a;
}

namespace {

// Zero of the bilinear interpolant of (vx, vy) in cell (i, j)-(i+1, j+1) by Newton; false if
// it does not converge inside the cell.
bool cell_zero(const Grid2D& g, std::size_t i, std::size_t j, double& x, double& y) {
  const std::size_t k00 = g.at(i, j), k10 = g.at(i + 1, j), k01 = g.at(i, j + 1), k11 = g.at(i + 1, j + 1);
  const auto corners = [&](const Vec& f) { return std::array<double, 4>{f[k00], f[k10], f[k01], f[k11]}; };
  const auto U = corners(g.vx), V = corners(g.vy);
  const auto val = [](const std::array<double, 4>& f, double s, double t) {
    return f[0] * (1 - s) * (1 - t) + f[1] * s * (1 - t) + f[2] * (1 - s) * t + f[3] * s * t;
  };
  const auto ds = [](const std::array<double, 4>& f, double t) { return (f[1] - f[0]) * (1 - t) + (f[3] - f[2]) * t; };
  const auto dt = [](const std::array<double, 4>& f, double s) { return (f[2] - f[0]) * (1 - s) + (f[3] - f[1]) * s; };
  double s = 0.5, t = 0.5;
  for (int it = 0; it < 50; ++it) {
    const double fu = val(U, s, t), fv = val(V, s, t);
    const double a = ds(U, t), b = dt(U, s), c = ds(V, t), d = dt(V, s), det = a * d - b * c;
    if (det == 0 || !std::isfinite(det)) return false;
    const double es = (d * fu - b * fv) / det, et = (a * fv - c * fu) / det;
    s -= es;
    t -= et;
    if (std::fabs(s) > 10 || std::fabs(t) > 10) return false;
    if (std::fabs(es) + std::fabs(et) < 1e-13) break;
  }
  const double tol = 1e-9;
  if (s < -tol || s > 1 + tol || t < -tol || t > 1 + tol) return false;
  x = g.xs[i] + s * spacing(g.xs);
  y = g.ys[j] + t * spacing(g.ys);
  return true;
}

}  // namespace

Vortex vortex_centre(const Grid2D& g, bool right_wall) {
  const std::size_t nx = g.nx(), ny = g.ny();
  if (nx < 3 || ny < 3) throw Error("vortex-centre: the grid needs 3 nodes or more along each axis");
  for (std::size_t k = 0; k < nx * ny; ++k)
    if (!std::isfinite(g.vx[k]) || !std::isfinite(g.vy[k]))
      throw Error("vortex-centre: velocity at node (" + std::to_string(g.xs[k / ny]) + ", " + std::to_string(g.ys[k % ny]) + ") is not finite");
  const Vec psi = stream_function(g);
  const double hx = spacing(g.xs), hy = spacing(g.ys);
  double edge = 0, omega = 0;
  std::size_t ne = 0;
  for (std::size_t i = 0; i < nx; ++i)
    for (std::size_t j = 0; j < ny; ++j)
      if (i == 0 || j == 0 || i == nx - 1 || j == ny - 1) {
        edge += psi[g.at(i, j)];
        ++ne;
      } else {  // vorticity dvy/dx - dvx/dy = -laplacian(psi)
        omega += (g.vy[g.at(i + 1, j)] - g.vy[g.at(i - 1, j)]) / (2 * hx) - (g.vx[g.at(i, j + 1)] - g.vx[g.at(i, j - 1)]) / (2 * hy);
      }
  edge /= double(ne);
  // The vortex turns with the field's net vorticity: a maximum of psi where it is positive
  // (anticlockwise), a minimum where negative; the interior node of that extremum.
  const double sense = omega >= 0 ? 1 : -1;
  Vortex v;
  double best = -kInf;
  for (std::size_t i = 1; i + 1 < nx; ++i)
    for (std::size_t j = 1; j + 1 < ny; ++j)
      if (sense * psi[g.at(i, j)] > best) {
        best = sense * psi[g.at(i, j)];
        v.psi = psi[g.at(i, j)] - edge;
        v.i = i;
        v.j = j;
      }
  const std::size_t i = v.i, j = v.j;
  const auto P = [&](std::size_t a, std::size_t b) { return psi[g.at(a, b)]; };
  // One Newton step on the central-difference gradient and Hessian: exact for a quadratic psi.
  const double px = (P(i + 1, j) - P(i - 1, j)) / (2 * hx), py = (P(i, j + 1) - P(i, j - 1)) / (2 * hy);
  const double pxx = (P(i + 1, j) - 2 * P(i, j) + P(i - 1, j)) / (hx * hx);
  const double pyy = (P(i, j + 1) - 2 * P(i, j) + P(i, j - 1)) / (hy * hy);
  const double pxy = (P(i + 1, j + 1) - P(i + 1, j - 1) - P(i - 1, j + 1) + P(i - 1, j - 1)) / (4 * hx * hy);
  const double det = pxx * pyy - pxy * pxy;
  const double dx = -(pyy * px - pxy * py) / det, dy = -(pxx * py - pxy * px) / det;
  v.x = g.xs[i];
  v.y = g.ys[j];
  if (det > 0 && std::fabs(dx) <= hx && std::fabs(dy) <= hy) {
    v.x += dx;
    v.y += dy;
    v.refined = true;
  }
  // Cross-check: the stagnation point of the bilinear velocity in the cells within two of the node.
  v.x_zero = v.y_zero = std::nan("");
  double nearest = kInf;
  for (std::size_t a = i >= 2 ? i - 2 : 0; a <= std::min(i + 1, nx - 2); ++a)
    for (std::size_t b = j >= 2 ? j - 2 : 0; b <= std::min(j + 1, ny - 2); ++b) {
      double zx, zy;
      if (cell_zero(g, a, b, zx, zy) && std::hypot(zx - v.x, zy - v.y) < nearest) {
        nearest = std::hypot(zx - v.x, zy - v.y);
        v.x_zero = zx;
        v.y_zero = zy;
      }
    }
  const double len = g.xhi - g.xlo;
  v.ell = right_wall ? g.xhi - v.x : v.x - g.xlo;
  v.ell_over_l = v.ell / len;
  return v;
}

// ---------- local rheology ----------

Region paper_region(const Grid2D& g) {
  const double mid = (g.xlo + g.xhi) / 2, quarter = (g.xhi - g.xlo) / 4;
  return {mid - quarter, mid + quarter, (g.ylo + g.yhi) / 2, g.yhi};
}

namespace {

// Index range [i0, i1] of the coordinates inside [lo, hi].
bool range_in(const Vec& u, double lo, double hi, std::size_t& i0, std::size_t& i1) {
  bool any = false;
  for (std::size_t i = 0; i < u.size(); ++i)
    if (u[i] >= lo && u[i] <= hi) {
      if (!any) i0 = i;
      i1 = i;
      any = true;
    }
  return any;
}

// d f / d axis at position k of [k0, k1] (f(k) gives the value): central inside, second-order
// one-sided at the ends, so that no node outside the range is read.
template <class F>
double deriv(const F& f, std::size_t k, std::size_t k0, std::size_t k1, double h) {
  if (k1 - k0 == 1) return (f(k1) - f(k0)) / h;
  if (k > k0 && k < k1) return (f(k + 1) - f(k - 1)) / (2 * h);
  if (k == k0) return (-3 * f(k) + 4 * f(k + 1) - f(k + 2)) / (2 * h);
  return (3 * f(k) - 4 * f(k - 1) + f(k - 2)) / (2 * h);
}

double norm16(const double a[3][3]) {  // Eq. 16: sqrt(Tr(A A^T)/2)
  double s = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s += a[r][c] * a[r][c];
  return std::sqrt(s / 2);
}

void deviator(double a[3][3]) {  // Eq. 17: A - Tr(A)/3 I_3
  const double t = (a[0][0] + a[1][1] + a[2][2]) / 3;
  for (int r = 0; r < 3; ++r) a[r][r] -= t;
}

}  // namespace

Rheology local_rheology(const Grid2D& g, const Region& r, double d, double rho_p) {
  if (!(d > 0) || !(rho_p > 0)) throw Error("local-rheology: grain diameter and density must be positive");
  if (g.sxx.empty() || g.syy.empty() || g.sxy.empty()) throw Error("local-rheology: the grid has no stress field");
  Rheology out;
  if (!range_in(g.xs, r.xlo, r.xhi, out.i0, out.i1) || !range_in(g.ys, r.ylo, r.yhi, out.j0, out.j1))
    throw Error("local-rheology: no node inside the region");
  if (out.i1 == out.i0 || out.j1 == out.j0) throw Error("local-rheology: the region holds a single node along an axis (no gradient)");
  const double hx = spacing(g.xs), hy = spacing(g.ys);
  for (std::size_t i = out.i0; i <= out.i1; ++i)
    for (std::size_t j = out.j0; j <= out.j1; ++j) {
      const std::size_t k = g.at(i, j);
      const auto along_x = [&](const Vec& f) { return deriv([&](std::size_t a) { return f[g.at(a, j)]; }, i, out.i0, out.i1, hx); };
      const auto along_y = [&](const Vec& f) { return deriv([&](std::size_t b) { return f[g.at(i, b)]; }, j, out.j0, out.j1, hy); };
      RheologyPoint p{};
      p.x = g.xs[i];
      p.y = g.ys[j];
      p.dxx = along_x(g.vx);
      p.dyy = along_y(g.vy);
      p.dxy = (along_y(g.vx) + along_x(g.vy)) / 2;
      const double szz = g.szz.empty() ? 0.0 : g.szz[k];
      double D[3][3] = {{p.dxx, p.dxy, 0}, {p.dxy, p.dyy, 0}, {0, 0, 0}};
      double S[3][3] = {{g.sxx[k], g.sxy[k], 0}, {g.sxy[k], g.syy[k], 0}, {0, 0, szz}};
      for (double v : {p.dxx, p.dyy, p.dxy, g.sxx[k], g.syy[k], g.sxy[k], szz})
        if (!std::isfinite(v))
          throw Error("local-rheology: node (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") in the region is not finite");
      p.p = (S[0][0] + S[1][1] + S[2][2]) / 3;  // sigma = p I_3 + sigma'
      deviator(D);
      deviator(S);
      p.norm_d = norm16(D);
      p.norm_s = norm16(S);
      ++out.nodes;
      if (!(p.p > 0) || !(p.norm_d > 0)) {
        ++out.skipped;
        continue;
      }
      // Tr(sigma' D') with D taken compression positive as sigma is (-sym grad v): a flow that
      // dissipates gives tr > 0 (u = gd y carries sxy = -tau in fix ave/cg's convention)
      double tr = 0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) tr -= S[a][b] * D[b][a];
      p.i = d * std::sqrt(rho_p) * p.norm_d / std::sqrt(p.p);
      p.mu_loc = tr / 3 / (p.p * p.norm_d);
      p.mu_norm = p.norm_s / p.p;
      p.align = p.norm_s > 0 ? tr / (2 * p.norm_s * p.norm_d) : 0.0;
      out.points.push_back(p);
    }
  return out;
}

std::vector<RheologyBin> bin_rheology(const std::vector<RheologyPoint>& pts, int nbins) {
  if (nbins < 1) throw Error("local-rheology: --nbins must be >= 1");
  if (pts.empty()) return {};
  double lo = kInf, hi = 0;
  for (auto& p : pts) {
    lo = std::min(lo, p.i);
    hi = std::max(hi, p.i);
  }
  if (std::log(hi / lo) < 1e-9) nbins = 1;  // one value of I (to rounding): one bin
  const double llo = std::log(lo), step = std::log(hi / lo) / nbins;
  std::vector<std::vector<const RheologyPoint*>> members(static_cast<std::size_t>(nbins));
  for (auto& p : pts) {
    const double k = nbins == 1 ? 0 : std::floor((std::log(p.i) - llo) / step);
    members[std::min<std::size_t>(std::size_t(std::max(k, 0.0)), members.size() - 1)].push_back(&p);
  }
  std::vector<RheologyBin> out;
  for (std::size_t b = 0; b < members.size(); ++b) {
    if (members[b].empty()) continue;
    RheologyBin q;
    q.i_lo = nbins == 1 ? lo : std::exp(llo + step * double(b));
    q.i_hi = nbins == 1 ? hi : std::exp(llo + step * double(b + 1));
    q.n = members[b].size();
    const double n = double(q.n);
    for (auto* p : members[b]) {
      q.i_mean += p->i / n;
      q.mu_loc += p->mu_loc / n;
      q.mu_norm += p->mu_norm / n;
    }
    // Standard error of the bin mean, the nodes taken as independent (a lower bound: neighbours
    // share grains through the kernel).
    double vl = 0, vn = 0;
    for (auto* p : members[b]) {
      vl += (p->mu_loc - q.mu_loc) * (p->mu_loc - q.mu_loc);
      vn += (p->mu_norm - q.mu_norm) * (p->mu_norm - q.mu_norm);
    }
    q.mu_loc_se = q.n > 1 ? std::sqrt(vl / (n - 1) / n) : 0.0;
    q.mu_norm_se = q.n > 1 ? std::sqrt(vn / (n - 1) / n) : 0.0;
    out.push_back(q);
  }
  return out;
}

}  // namespace sable::analysis
