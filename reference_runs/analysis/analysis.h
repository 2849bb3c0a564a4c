#pragma once
// sable-analyze: the statistics every study needs (issue 23), written once on GSL.
// Formulas and conventions: reference_runs/analysis/README.md.
#include <cstddef>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sable::analysis {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Vec = std::vector<double>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------- histograms (stats.cpp) ----------
struct Histogram {
  Vec edges, centres, counts, pdf;  // pdf = counts / (n * width): integrates to the fraction inside
  double mean = 0;                  // the mean the values were divided by (1 when not normalised)
  std::size_t n = 0, outside = 0;   // values used; values outside the bins (log bins: also x <= 0)
};
Histogram histogram(const Vec& x, int nbins, bool log_bins, bool by_mean, double lo = 0, double hi = 0);
double mean_of(const Vec& x);

// ---------- Kolmogorov-Smirnov (stats.cpp) ----------
struct Ks {
  double d = 0, p = 0, critical = 0;  // distance, p-value, distance rejected at level alpha
  double n_eff = 0;
};
double kolmogorov_q(double lambda);  // P(K > lambda), the Kolmogorov survival function
Ks ks_two_sample(Vec a, Vec b, double alpha = 0.05);
Ks ks_one_sample(Vec x, const std::function<double(double)>& cdf, double alpha = 0.05);

// ---------- autocorrelation and correlated errors (stats.cpp) ----------
Vec autocorrelation(const Vec& x, std::size_t max_lag);  // C(k), C(0) = 1 (FFT)
double first_lag_below(const Vec& c, double threshold);  // interpolated in ln C; -1 if never
struct CorrTime {
  double g = 1;            // statistical inefficiency 1 + 2 sum_{k=1}^{M} C(k)
  std::size_t window = 0;  // M: smallest with M >= 3 g (Sokal's window, c = 6 on tau = g/2)
};
CorrTime integrated_time(const Vec& c);
struct BlockError {
  double mean = 0, error = 0, error_of_error = 0, naive = 0;  // naive: sigma / sqrt(N)
  double g = 1;
  std::size_t block = 0, nblocks = 0;
};
BlockError block_error(const Vec& x, std::size_t block = 0);  // 0: block = ceil(10 g)

// ---------- maximum likelihood (fit.cpp) ----------
using Objective = std::function<double(const Vec&)>;
struct Minimum {
  Vec theta;
  double value = kInf;
};
Minimum nelder_mead(const Objective& f, const Vec& start, const Vec& step, double tol = 1e-7, int max_iter = 4000);
Minimum best_of_starts(const Objective& f, const std::vector<Vec>& starts, const Vec& step);
struct Interval {
  double lo = -kInf, hi = kInf;
  bool lo_open = true, hi_open = true;  // the likelihood did not fall by delta before the search bound
};
// prof(t, free): the minimum over the other parameters with the one of interest at t
// (free: their start, updated to their optimum). Steps out from t_hat until the profile
// rises by delta (1.92 = chi2_1(95 %) / 2), then bisects.
using Profile = std::function<double(double, Vec&)>;
Interval profile_interval(const Profile& prof, double t_hat, const Vec& free_hat, double nll_hat, double scale,
                          double t_min, double t_max, double delta = 1.92);

struct Param {
  std::string name;
  double value = 0;
  Interval ci;
};
struct Fit {
  std::string model;  // "eq7", "normal", "eq8", "eq9", "eq10"
  std::vector<Param> params;
  double loglik = 0, aic = 0;
  Ks ks;  // against the fitted CDF (parameters estimated from the same data: p is optimistic)
  std::function<double(double)> pdf, cdf;
};
// kneib2017 Eq. 7: P(x) = lognormal(x + x0; mu, sigma) / S, x > 0, S = lognormal survival at x0.
double eq7_pdf(double x, double mu, double sigma, double x0);
double eq7_cdf(double x, double mu, double sigma, double x0);
struct LogNormalFit {
  Fit eq7;                      // mu, sigma, x0
  Fit normal;                   // the Gaussian limit: normal(m, s) truncated to x > 0
  bool gaussian_limit = false;  // loglik(eq7) - loglik(normal) < delta: x0 -> inf is inside the 95 % region
  int starts = 0;
};
LogNormalFit fit_truncated_lognormal(const Vec& x, double delta = 1.92);
Fit fit_truncated_normal(const Vec& x, double delta = 1.92);
Fit fit_eq8(const Vec& x, double delta = 1.92);   // q-model, k^k/Gamma(k) x^(k-1) exp(-k x), mean 1
Fit fit_eq9(const Vec& x, double delta = 1.92);   // a [1 - b exp(-x^2)] exp(-beta x), a normalises
Fit fit_eq10(const Vec& x, double delta = 1.92);  // Radjai, beta0 = (1 + g0) ln((1 + g0) / g0) (mean 1)

// ---------- Mohr circles, power laws, quadrature (mohr.cpp) ----------
struct Circle {
  double centre, radius;
};
Circle mohr_circle(double s1, double s3);
void principal_2d(double sxx, double syy, double sxy, double& s1, double& s3);
struct Envelope {
  double mu = 0, c = 0, mu_err = 0, c_err = 0, cov = 0;  // |tau| = C + mu sigma (petit2017 Eq. 8)
  double phi = 0;                                     // friction angle, sin(phi) = slope of r on centre
  double rms = 0;                                     // rms of (distance from centre to line - radius)
};
Envelope mohr_envelope(const std::vector<Circle>& circles);
struct PowerLaw {
  double k0 = 0, alpha = 0, k0_err = 0, alpha_err = 0, cov = 0, x0 = 1, chi2 = 0;
  std::size_t dof = 0;
  std::string method;
};
// y = K0 (x / x0)^alpha; yerr empty: unweighted, covariance scaled by chi2/dof.
PowerLaw power_law_loglog(const Vec& x, const Vec& y, const Vec& yerr, double x0);
PowerLaw power_law_nls(const Vec& x, const Vec& y, const Vec& yerr, double x0);
struct Eq9 {
  double mu_m = 0;         // petit2017 Eq. 9 with P as given
  double mu_m_window = 0;  // with P normalised over [phi_min, phi_max]
  double weight = 0;       // integral of P over the window
  double phi_max = 0, abserr = 0;
};
// P(phi) on radians; phi_max = atan(mu) + pi/4; breaks: where P has kinks or steps.
Eq9 quad_eq9(const std::function<double(double)>& p, double mu, double phi_min, Vec breaks = {});

// ---------- cavity study: kneib2017 Eqs. 4, 5, 16-20 (cavity.cpp) ----------
struct LsqParam {
  std::string name;
  double value = 0, err = 0;  // standard error
  double lo = 0, hi = 0;      // 95 % interval: value -+ q err (x0: exp(ln x0 -+ q err(ln x0)))
};
struct LsqFit {
  std::string model;
  std::vector<LsqParam> params;
  double chi2 = 0;          // sum of squared residuals, each divided by its error when errors are given
  double r2 = 0;            // 1 - SS_res/SS_tot (weighted by 1/yerr^2 when errors are given)
  double q = 0;             // err -> 95 % half-width: normal 1.96 with errors, Student t(dof) without
  std::size_t n = 0, dof = 0;
  bool weighted = false;    // false: covariance scaled by chi2/dof (errors from the scatter)
};
// The pieces every least-squares fit shares (cavity.cpp): one place for the checks, the weights,
// R^2, the 95 % quantile, the start scan and GSL's trust-region driver.
namespace lsq {
void check(const char* what, const Vec& x, const Vec& y, const Vec& yerr, std::size_t np);
Vec weights(const Vec& yerr, std::size_t n);                  // 1/yerr^2, or 1 without errors
double r_squared(const Vec& y, const Vec& fit, const Vec& w);  // 1 - SS_res/SS_tot about the weighted mean
double quantile95(bool weighted, std::size_t dof);             // normal 1.96 with errors, Student t(dof) without
LsqFit start(const std::string& model, std::size_t n, std::size_t np, bool weighted);  // model, n, dof = n - np, weighted
LsqParam symmetric(const std::string& name, double v, double err, double q);
// For a model c0 + c1 s(x; t): t scanned over [t0, t1] in `steps` steps, (c0, c1) by weighted linear
// least squares at each; returns the best chi2's {c0, c1, t}.
Vec scan_linear(const std::function<double(double, double)>& s, const Vec& x, const Vec& y, const Vec& w, double t0, double t1,
                int steps);
// Residuals f_i(theta) (already divided by their sd) and, when jac is given, df_i/dtheta_k at jac[i p + k].
using Residuals = std::function<void(const Vec& theta, Vec& f, Vec* jac)>;
struct Nls {
  Vec theta, cov;  // cov: (J^T J)^-1, p x p row-major, unscaled
  double chi2 = 0;
  int status = 0;
  bool converged = false;
};
Nls solve(const Residuals& r, std::size_t n, Vec t0, int max_iter = 500);  // gsl_multifit_nlinear, trust region
}  // namespace lsq

// kneib2017 Eq. 4 (r1, r2, I_M^0) and Eq. 20 (mu1, mu2, I0): y = a + (b - a)/(1 + x0/x), x > 0.
double sigmoid(double x, double a, double b, double x0);
// Weighted nonlinear least squares in (a, b, ln x0) (GSL trust region), started from the best
// of a scan in ln x0 where (a, b) follow by linear least squares. params: a, b, x0.
LsqFit fit_sigmoid(const Vec& x, const Vec& y, const Vec& yerr = {});
// kneib2017 Eq. 5: y = c1 - c2 x (F/(PLd) on l/L); params c1, c2.
LsqFit fit_linear_down(const Vec& x, const Vec& y, const Vec& yerr = {});

// A mean field on a regular 2D grid of the cavity's plane: x along the cavity (horizontal),
// y up. Nodes xs[i], ys[j] (increasing, evenly spaced); fields at node (i, j) at i ny + j.
struct Grid2D {
  Vec xs, ys;
  Vec vx, vy;                // mean velocity
  Vec sxx, syy, szz, sxy;    // stress, compression positive; szz out of the plane (empty: not read)
  double xlo = 0, xhi = 0, ylo = 0, yhi = 0;  // the cavity's walls (default: the nodes' cells, as fix ave/cg)
  std::size_t nx() const { return xs.size(); }
  std::size_t ny() const { return ys.size(); }
  std::size_t at(std::size_t i, std::size_t j) const { return i * ys.size() + j; }
};
// Rows (x, y, fields...) in any order, every node of a complete regular grid the same number
// of times (several windows: averaged). fields: pairs (column, the grid field it fills).
Grid2D grid_from_rows(const Vec& x, const Vec& y, const std::vector<std::pair<const Vec*, Vec Grid2D::*>>& fields);
// fix ave/cg's HDF5 (u [w][nx][ny][nz][3], stress* [w][nx][ny][nz][6], x y z, bounds): the mean
// over windows after the first `skip` (weighted by samples), averaged over the out-of-plane
// axis. plane: "xy" (x along, y up), "xz" (x along, z up) or "yz" (y along, z up).
Grid2D read_cg_grid(const std::string& path, const std::string& plane, const std::string& stress, std::size_t skip);

// Stream function (vx = dpsi/dy, vy = -dpsi/dx) by the trapezoid rule along two paths from
// node (0, 0) (along the bottom row then up; up the first column then along), averaged.
Vec stream_function(const Grid2D& g);
struct Vortex {
  double x = 0, y = 0;           // centre: the interior extremum of psi (a maximum where the net vorticity
                                 // is positive), refined by a Newton step on its 3x3 stencil
  bool refined = false;          // false: the step left the cell (the node is reported)
  std::size_t i = 0, j = 0;      // the extremal interior node
  double psi = 0;                // psi there minus its mean on the grid's edge
  double x_zero = 0, y_zero = 0; // zero of the bilinear velocity nearest the centre (NaN: none)
  double ell = 0, ell_over_l = 0;  // kneib2017 Sec. III A: distance from the wall (default the right one)
};
Vortex vortex_centre(const Grid2D& g, bool right_wall = true);

// kneib2017 Fig. 19: the upper half of the bed, within L/4 of the middle along x.
struct Region {
  double xlo = -kInf, xhi = kInf, ylo = -kInf, yhi = kInf;  // closed
};
Region paper_region(const Grid2D& g);
struct RheologyPoint {
  double x, y;
  double dxx, dyy, dxy;  // strain rate D = sym(grad v), in-plane (D_zz = 0)
  double norm_d;         // ||D'|| (Eqs. 16, 17)
  double p;              // Tr(sigma)/3
  double norm_s;         // ||sigma'||
  double i;              // Eq. 18: d sqrt(rho_p) ||D'|| / sqrt(p)
  double mu_loc;         // Eq. 19 as printed: Tr(sigma' D')/3 / (p ||D'||)
  double mu_norm;        // ||sigma'|| / p
  double align;          // Tr(sigma' D') / (2 ||sigma'|| ||D'||): 1 when collinear
};
struct Rheology {
  std::vector<RheologyPoint> points;
  std::size_t nodes = 0, skipped = 0;  // nodes in the region; of those, with p <= 0 or ||D'|| = 0
  std::size_t i0 = 0, i1 = 0, j0 = 0, j1 = 0;  // the region's node ranges (closed)
};
// Gradients from the nodes inside the region only (central; second-order one-sided at its edges).
Rheology local_rheology(const Grid2D& g, const Region& r, double d, double rho_p);
struct RheologyBin {
  double i_lo = 0, i_hi = 0, i_mean = 0;
  double mu_loc = 0, mu_loc_se = 0, mu_norm = 0, mu_norm_se = 0;
  std::size_t n = 0;
};
std::vector<RheologyBin> bin_rheology(const std::vector<RheologyPoint>& pts, int nbins);  // log bins in I; empty ones left out

// ---------- petit2017: bulk modulus, Mohr friction per cycle, Eq. 9 inverted, entropy (mohr.cpp) ----------
// Eq. 6 between successive states of each loading branch: K = (d syy + 2 d sxx) / (3 d eyy),
// compression positive. A branch is a run of consecutive rows with the same cycle and
// loading != 0 (cycle empty: one cycle; loading empty: every row loads).
struct BulkPoint {
  std::size_t row = 0;  // the increment's end state (0-based row)
  double cycle = 0, syy = 0, syy_mid = 0, eyy = 0, k = 0;  // syy at the end state, (syy_prev + syy)/2
};
std::vector<BulkPoint> bulk_modulus(const Vec& syy, const Vec& sxx, const Vec& eyy, const Vec& cycle = {}, const Vec& loading = {});
// Eq. 7 with its offset: K = K0 + a (s/s0 - 1)^alpha for s >= s0 (params K0, a, alpha; s0 fixed).
double offset_power(double s, double k0, double a, double alpha, double s0);
LsqFit fit_offset_power(const Vec& s, const Vec& k, const Vec& kerr, double s0);
// The Mohr envelope (Eq. 8) of each cycle's loading circles, cycles in order of first appearance.
struct CycleEnvelope {
  double cycle = 0;
  std::size_t n = 0;  // loading circles
  Envelope e;
};
std::vector<CycleEnvelope> cycle_envelopes(const std::vector<Circle>& circles, const Vec& cycle, const Vec& loading = {});
// The limit cycle: the first index k (before the last) with |mu_j - mu_k| <= tol |mu_k| for every
// j > k; -1 when none (the sequence has not settled within tol by its second-to-last cycle).
long limit_cycle(const Vec& mu, double tol = 0.005);
// Eq. 9 inverted: the phi_min at which quad_eq9 gives mu_m (window: P normalised over the range),
// by Brent's method between phi_max - 3 pi/4 (where tan reaches pi/2) and phi_max.
double phi_min_eq9(const std::function<double(double)>& p, double mu, double mu_m, bool window = false, const Vec& breaks = {});
// Eq. 10: S = -sum_k P_k ln P_k over nbins equal bins of [-pi/2, pi/2] (angles from the vertical;
// a contact is a line, so angles outside are folded by pi), P_k = count_k / n.
double fold_angle(double phi);
struct Entropy {
  double s = 0;
  Histogram h;  // counts per bin; P_k = counts[k] / n
  Vec p;
};
Entropy contact_entropy(const Vec& phi, int nbins);

// ---------- files (io.cpp) ----------
struct Column {
  Vec values;
  std::string label;  // "file, column NAME"
};
// HDF5 (dataset, default "values"; names from its "columns" attribute), LIGGGHTS dump
// (columns from ITEM: ATOMS, every snapshot), or a text table ('#' comments, the last
// comment line before the data names the columns). spec: 1-based number or name.
Column read_column(const std::string& path, const std::string& spec, const std::string& dataset = "");
struct Table {
  std::vector<std::string> names;
  std::vector<Vec> cols;
  std::vector<std::pair<std::string, std::string>> meta;  // '# key: value' lines / HDF5 attributes
};
void write_table(const std::string& path, const Table& t);  // .csv or .h5 (by extension)
bool is_hdf5_file(const std::string& path);
bool h5_has_dataset(const std::string& path, const std::string& name);
Vec read_h5_array(const std::string& path, const std::string& name, std::vector<std::size_t>& dims);  // row-major

}  // namespace sable::analysis
