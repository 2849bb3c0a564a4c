// The cavity study's analysis (issue 43 item 3) recovers known answers: the Eq. 4 / Eq. 20
// sigmoid and the Eq. 5 line from synthetic data with known parameters, the centre of
// vortices with a known centre, and I, mu_loc of simple shear under a known stress
// (kneib2017 Eqs. 16-19). Noise from GSL's mt19937 with fixed seeds.
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <unistd.h>

#include "core/io/h5_series.h"
#include "reference_runs/analysis/analysis.h"
#include "reference_runs/analysis/tests/gsl_rng.h"

using namespace sable::analysis;

namespace {

// kneib2017 Sec. III A: r1 = 0.53, r2 = 0.86, I_M^0 = 0.02 over I_M = 1e-3 ... 0.5.
constexpr double kR1 = 0.53, kR2 = 0.86, kI0 = 0.02;
Vec im_points(int n) {
  Vec x;
  for (int i = 0; i < n; ++i) x.push_back(1e-3 * std::pow(500.0, i / double(n - 1)));
  return x;
}

const LsqParam& param(const LsqFit& f, const std::string& name) {
  for (auto& p : f.params)
    if (p.name == name) return p;
  throw Error("no parameter " + name);
}

struct Spread {  // estimates over seeds: their sd against the mean stated error, and the coverage
  Vec est, err;
  int inside = 0;
  void add(const LsqParam& p, double truth) {
    est.push_back(p.value);
    err.push_back(p.err);
    inside += p.lo <= truth && truth <= p.hi;
  }
  double sd_over_err() const {
    double m = 0, s = 0, e = 0;
    for (double v : est) m += v / double(est.size());
    for (double v : est) s += (v - m) * (v - m) / double(est.size() - 1);
    for (double v : err) e += v / double(err.size());
    return std::sqrt(s) / e;
  }
  double coverage() const { return inside / double(est.size()); }
};

}  // namespace

TEST(CavitySigmoid, ExactDataGiveExactParameters) {
  const Vec x = im_points(25);
  Vec y;
  for (double v : x) y.push_back(sigmoid(v, kR1, kR2, kI0));
  for (const LsqFit& f : {fit_sigmoid(x, y), fit_sigmoid(x, y, Vec(x.size(), 0.01))}) {
    SCOPED_TRACE(f.weighted);
    // Rounding only: the trust region stops at 1e-12 relative steps.
    EXPECT_NEAR(param(f, "a").value, kR1, 1e-9);
    EXPECT_NEAR(param(f, "b").value, kR2, 1e-9);
    EXPECT_NEAR(param(f, "x0").value, kI0, 1e-9 * kI0);
    EXPECT_NEAR(f.r2, 1, 1e-12);
    EXPECT_EQ(f.dof, 22u);
  }
}

TEST(CavitySigmoid, NoisyTruthInsideIntervalsAndTheErrorsMatchTheScatter) {
  // 400 noise seeds at sd 0.01 (Fig. 3(b)'s scatter about its fit is of that order). The
  // errors' sd over seeds against the mean stated error: a sample sd of 400 is uncertain by
  // 1/sqrt(2 * 399) = 3.5 %, so 0.88-1.12 is ~3.5 of those. The 95 % intervals' coverage:
  // binomial sd over 400 is 1.1 %, 0.92-0.98 is ~3 of those.
  const Vec x = im_points(25);
  const double sd = 0.01;
  for (bool weighted : {false, true}) {
    SCOPED_TRACE(weighted ? "weighted" : "errors from the scatter");
    Spread a, b, x0;
    for (unsigned long seed = 1; seed <= 400; ++seed) {
      Rng r(seed);
      Vec y;
      for (double v : x) y.push_back(sigmoid(v, kR1, kR2, kI0) + gsl_ran_gaussian(r, sd));
      const LsqFit f = fit_sigmoid(x, y, weighted ? Vec(x.size(), sd) : Vec{});
      a.add(param(f, "a"), kR1);
      b.add(param(f, "b"), kR2);
      x0.add(param(f, "x0"), kI0);
      if (seed == 1) {  // one fit read as a user would: truth inside each interval, a good R^2
        for (auto& p : f.params) {
          const double truth = p.name == "a" ? kR1 : p.name == "b" ? kR2 : kI0;
          EXPECT_LE(p.lo, truth) << p.name;
          EXPECT_GE(p.hi, truth) << p.name;
        }
        EXPECT_GT(f.r2, 0.98);
        EXPECT_LT(param(f, "x0").err / kI0, 0.2);  // informative
      }
    }
    for (auto* s : {&a, &b, &x0}) {
      EXPECT_NEAR(s->sd_over_err(), 1, 0.12);
      EXPECT_NEAR(s->coverage(), 0.95, 0.03);
    }
    std::printf("sigmoid (%s): sd/err a %.3f b %.3f x0 %.3f; coverage %.3f %.3f %.3f\n", weighted ? "weighted" : "scatter",
                a.sd_over_err(), b.sd_over_err(), x0.sd_over_err(), a.coverage(), b.coverage(), x0.coverage());
  }
}

TEST(CavityLinear, Eq5LineRecovered) {
  // kneib2017 Fig. 4: c1 = 0.88, c2 = 0.5 over l/L in 0.2-0.5. Exact to rounding; with noise
  // sd 0.01 the same spread and coverage checks as the sigmoid's.
  Vec x, y;
  for (int i = 0; i < 15; ++i) {
    x.push_back(0.2 + 0.3 * i / 14.0);
    y.push_back(0.88 - 0.5 * x.back());
  }
  const LsqFit e = fit_linear_down(x, y);
  EXPECT_NEAR(param(e, "c1").value, 0.88, 1e-13);
  EXPECT_NEAR(param(e, "c2").value, 0.5, 1e-13);
  EXPECT_NEAR(e.r2, 1, 1e-13);
  Spread c1, c2;
  for (unsigned long seed = 1; seed <= 400; ++seed) {
    Rng r(seed + 1000);
    Vec yn;
    for (double v : y) yn.push_back(v + gsl_ran_gaussian(r, 0.01));
    const LsqFit f = fit_linear_down(x, yn);
    c1.add(param(f, "c1"), 0.88);
    c2.add(param(f, "c2"), 0.5);
  }
  for (auto* s : {&c1, &c2}) {
    EXPECT_NEAR(s->sd_over_err(), 1, 0.12);
    EXPECT_NEAR(s->coverage(), 0.95, 0.03);
  }
  std::printf("line: sd/err c1 %.3f c2 %.3f; coverage %.3f %.3f\n", c1.sd_over_err(), c2.sd_over_err(), c1.coverage(), c2.coverage());
}

namespace {

// Nodes at cell centres of [0, L] x [0, H], as fix ave/cg places them.
Grid2D cells(std::size_t nx, std::size_t ny, double L, double H) {
  Grid2D g;
  for (std::size_t i = 0; i < nx; ++i) g.xs.push_back((i + 0.5) * L / double(nx));
  for (std::size_t j = 0; j < ny; ++j) g.ys.push_back((j + 0.5) * H / double(ny));
  g.xlo = 0;
  g.xhi = L;
  g.ylo = 0;
  g.yhi = H;
  g.vx.assign(nx * ny, 0.0);
  g.vy.assign(nx * ny, 0.0);
  return g;
}

template <class V>
void fill_velocity(Grid2D& g, V v) {
  for (std::size_t i = 0; i < g.nx(); ++i)
    for (std::size_t j = 0; j < g.ny(); ++j) {
      const auto [u, w] = v(g.xs[i], g.ys[j]);
      g.vx[g.at(i, j)] = u;
      g.vy[g.at(i, j)] = w;
    }
}

}  // namespace

TEST(CavityVortex, SolidBodyRotationCentreOffTheNodes) {
  // u = -Omega (y - yc), v = Omega (x - xc): psi is a paraboloid, the trapezoid rule and the
  // Newton step on its 3x3 stencil are exact, and so is the bilinear velocity's zero.
  Grid2D g = cells(30, 20, 0.6, 0.4);
  const double xc = 0.3137, yc = 0.2281, om = 2;  // 0.19 and 0.41 of a cell off the nearest node
  fill_velocity(g, [&](double x, double y) { return std::pair{-om * (y - yc), om * (x - xc)}; });
  const Vortex v = vortex_centre(g);
  EXPECT_TRUE(v.refined);
  EXPECT_NEAR(v.x, xc, 1e-12);
  EXPECT_NEAR(v.y, yc, 1e-12);
  EXPECT_NEAR(v.x_zero, xc, 1e-12);
  EXPECT_NEAR(v.y_zero, yc, 1e-12);
  EXPECT_NEAR(v.ell_over_l, (0.6 - xc) / 0.6, 1e-12);
  EXPECT_NEAR(vortex_centre(g, false).ell, xc, 1e-12);  // from the left wall
  // Near a corner and turning clockwise: psi's deepest interior node is the centre's, though
  // nodes across the grid lie farther from psi's mean along the edges.
  const double xd = 0.5237, yd = 0.0913;
  fill_velocity(g, [&](double x, double y) { return std::pair{om * (y - yd), -om * (x - xd)}; });
  const Vortex c = vortex_centre(g);
  EXPECT_NEAR(c.x, xd, 1e-12);
  EXPECT_NEAR(c.y, yd, 1e-12);
}

TEST(CavityVortex, RankineVortexCentreToAFractionOfACell) {
  // Solid-body core of radius 3 cells, 1/r outside: the 3x3 stencil lies in the core, but psi
  // integrates the 1/r part by the trapezoid rule along the paths; measured error 5e-3 cell,
  // required 0.05 cell.
  Grid2D g = cells(40, 30, 1.0, 0.75);
  const double h = 0.025, xc = 0.4421, yc = 0.3973, R = 3 * h;
  fill_velocity(g, [&](double x, double y) {
    const double dx = x - xc, dy = y - yc, r2 = dx * dx + dy * dy;
    const double f = r2 < R * R ? 1.0 : R * R / r2;  // u_theta / (Omega r)
    return std::pair{-f * dy, f * dx};
  });
  const Vortex v = vortex_centre(g);
  EXPECT_TRUE(v.refined);
  EXPECT_NEAR(v.x, xc, 0.05 * h);
  EXPECT_NEAR(v.y, yc, 0.05 * h);
  EXPECT_NEAR(v.x_zero, xc, 1e-12);  // the core is linear: bilinear is exact there
  EXPECT_NEAR(v.y_zero, yc, 1e-12);
  std::printf("Rankine: centre off by (%.2e, %.2e) cells\n", (v.x - xc) / h, (v.y - yc) / h);
}

TEST(CavityVortex, CavityLikeVortexShiftedTowardsTheRightWall) {
  // psi = sin(pi s) sin(pi y/H), s = (x/L)^p: zero on all four walls, one vortex, centre at
  // s = 1/2, x = L 2^(-1/p), y = H/2; p = 1.5 puts it at l/L = 0.370 (kneib2017 Fig. 3(a)'s
  // range at high I_M). Divergence free; O(h^2) trapezoid and stencil errors: 0.05 cell.
  const double L = 1, H = 0.5, p = 1.5, pi = M_PI;
  Grid2D g = cells(40, 20, L, H);
  fill_velocity(g, [&](double x, double y) {
    const double s = std::pow(x / L, p), ds = p * std::pow(x / L, p - 1) / L;
    return std::pair{std::sin(pi * s) * pi / H * std::cos(pi * y / H), -pi * std::cos(pi * s) * ds * std::sin(pi * y / H)};
  });
  const double xc = L * std::pow(0.5, 1 / p), yc = H / 2, h = L / 40;
  const Vortex v = vortex_centre(g);
  EXPECT_NEAR(v.x, xc, 0.05 * h);
  EXPECT_NEAR(v.y, yc, 0.05 * h);
  EXPECT_NEAR(v.x_zero, xc, 0.05 * h);
  EXPECT_NEAR(v.y_zero, yc, 0.05 * h);
  EXPECT_NEAR(v.ell_over_l, 1 - std::pow(0.5, 1 / p), 0.05 * h / L);
  std::printf("cavity-like: psi centre off by (%.2e, %.2e) cells, velocity zero by (%.2e, %.2e)\n", (v.x - xc) / h,
              (v.y - yc) / h, (v.x_zero - xc) / h, (v.y_zero - yc) / h);
  for (double& a : g.vx) a = -a;  // the other sense of rotation: the same centre
  for (double& a : g.vy) a = -a;
  const Vortex r = vortex_centre(g);
  EXPECT_NEAR(r.x, v.x, 1e-12);
  EXPECT_NEAR(r.y, v.y, 1e-12);
}

namespace {

// Simple shear u = gd y (+ a uniform drift), v = 0 resisted by a shear stress tau > 0: compression
// positive (fix ave/cg's convention), sigma = [[P, -tau], [-tau, P]], szz.
Grid2D simple_shear(double gd, double P, double tau, double szz) {
  Grid2D g = cells(40, 20, 0.8, 0.4);
  fill_velocity(g, [&](double, double y) { return std::pair{0.3 + gd * y, 0.0}; });
  const std::size_t n = g.nx() * g.ny();
  g.sxx.assign(n, P);
  g.syy.assign(n, P);
  g.sxy.assign(n, -tau);
  g.szz.assign(n, szz);
  return g;
}

}  // namespace

TEST(CavityRheology, SimpleShearGivesKnownIAndMu) {
  // D' = [[0, gd/2], [gd/2, 0]]: ||D'|| = gd/2 (Eq. 16). With szz = P: p = P, sigma' = -tau
  // off the diagonal, ||sigma'|| = tau, Tr(sigma' D') = tau gd with D compression positive as
  // sigma (-sym grad v; a dissipating flow has mu_loc > 0), so Eq. 18 gives
  // I = d sqrt(rho_p) gd / (2 sqrt(P)) and Eq. 19 mu_loc = (tau gd / 3)/(P gd / 2) = 2 tau/(3 P),
  // mu_norm = tau/P. Linear fields: finite differences exact, rounding only (1e-13).
  const double gd = 7.5, P = 1200, tau = 0.35 * P, d = 1e-3, rho = 2500;
  const Rheology r = local_rheology(simple_shear(gd, P, tau, P), Region{}, d, rho);
  ASSERT_EQ(r.points.size(), 800u);
  const double I = d * std::sqrt(rho) * gd / (2 * std::sqrt(P));
  for (const RheologyPoint& q : r.points) {
    EXPECT_NEAR(q.norm_d, gd / 2, 1e-13 * gd);
    EXPECT_NEAR(q.p, P, 1e-13 * P);
    EXPECT_NEAR(q.i, I, 1e-13 * I);
    EXPECT_NEAR(q.mu_loc, 2 * tau / (3 * P), 1e-13);
    EXPECT_NEAR(q.mu_norm, tau / P, 1e-13);
    EXPECT_NEAR(q.align, 1, 1e-13);
  }
  // A planar assembly (szz = 0, kneib2017's grains in a plane): p = 2P/3, and Eq. 19 as
  // printed becomes tau/P exactly, the 1/3 and the 3D trace cancelling.
  const Rheology s = local_rheology(simple_shear(gd, P, tau, 0), Region{}, d, rho);
  for (const RheologyPoint& q : s.points) {
    EXPECT_NEAR(q.p, 2 * P / 3, 1e-13 * P);
    EXPECT_NEAR(q.i, d * std::sqrt(rho) * gd / 2 / std::sqrt(2 * P / 3), 1e-13 * I);
    EXPECT_NEAR(q.mu_loc, tau / P, 1e-13);
  }
  // Control on the sign: a stress that drives the shear instead of resisting it (sxy = +tau)
  // gives a negative friction.
  for (const RheologyPoint& q : local_rheology(simple_shear(gd, P, -tau, P), Region{}, d, rho).points)
    EXPECT_NEAR(q.mu_loc, -2 * tau / (3 * P), 1e-13);
}

TEST(CavityRheology, PaperRegionIgnoresEverythingOutsideIt) {
  // kneib2017 Fig. 19: upper half in y, the central L/2 in x. On 40 x 20 cell-centred nodes
  // that is i = 10..29, j = 10..19: 200 nodes. Outside, velocity and stress are garbage (and
  // NaN in one copy); inside, simple shear: the answers must be the exact ones.
  const double gd = 3, P = 800, tau = 0.25 * P, d = 2e-3, rho = 2500;
  Grid2D g = simple_shear(gd, P, tau, P);
  Grid2D nan = g;
  const Region reg = paper_region(g);
  EXPECT_DOUBLE_EQ(reg.xlo, 0.2);
  EXPECT_DOUBLE_EQ(reg.xhi, 0.6);
  EXPECT_DOUBLE_EQ(reg.ylo, 0.2);
  EXPECT_DOUBLE_EQ(reg.yhi, 0.4);
  Rng rng(77);
  for (std::size_t i = 0; i < g.nx(); ++i)
    for (std::size_t j = 0; j < g.ny(); ++j) {
      if (i >= 10 && i <= 29 && j >= 10) continue;
      const std::size_t k = g.at(i, j);
      for (Vec* f : {&g.vx, &g.vy, &g.sxx, &g.syy, &g.szz, &g.sxy}) (*f)[k] = 1e3 * gsl_rng_uniform(rng) - 200;
      for (Vec* f : {&nan.vx, &nan.vy, &nan.sxx, &nan.syy, &nan.szz, &nan.sxy}) (*f)[k] = std::nan("");
    }
  const double I = d * std::sqrt(rho) * gd / (2 * std::sqrt(P));
  for (const Grid2D* f : {&g, &nan}) {
    const Rheology r = local_rheology(*f, reg, d, rho);
    EXPECT_EQ(r.nodes, 200u);
    EXPECT_EQ(r.skipped, 0u);
    EXPECT_EQ(r.i0, 10u);
    EXPECT_EQ(r.i1, 29u);
    EXPECT_EQ(r.j0, 10u);
    EXPECT_EQ(r.j1, 19u);
    ASSERT_EQ(r.points.size(), 200u);
    for (const RheologyPoint& q : r.points) {
      EXPECT_NEAR(q.i, I, 1e-13 * I);  // one-sided differences at the region's edges: exact for linear u
      EXPECT_NEAR(q.mu_loc, 2 * tau / (3 * P), 1e-13);
    }
  }
  // Control: over the whole grid the garbage shows (the check above could fail).
  const Rheology all = local_rheology(g, Region{}, d, rho);
  double worst = 0;
  for (const RheologyPoint& q : all.points) worst = std::max(worst, std::fabs(q.i / I - 1));
  EXPECT_GT(worst, 1);
  EXPECT_THROW(local_rheology(nan, Region{}, d, rho), Error);
}

TEST(CavityRheology, BinnedMeansOverLogBinsInI) {
  // u = A y^2: gd = 2 A y spans a decade over the upper half; tau = mu P with mu = 0.3 fixed,
  // so every bin's mean mu_norm is 0.3 (rounding) and the counts add up to the points.
  Grid2D g = cells(20, 40, 0.4, 0.8);
  fill_velocity(g, [](double, double y) { return std::pair{5 * y * y, 0.0}; });
  const std::size_t n = g.nx() * g.ny();
  g.sxx.assign(n, 1000);
  g.syy.assign(n, 1000);
  g.szz.assign(n, 1000);
  g.sxy.assign(n, -300);  // compression positive: the stress resisting u = 5 y^2
  const Rheology r = local_rheology(g, paper_region(g), 1e-3, 2500);
  const std::vector<RheologyBin> b = bin_rheology(r.points, 5);
  std::size_t total = 0;
  for (const RheologyBin& q : b) {
    total += q.n;
    EXPECT_NEAR(q.mu_norm, 0.3, 1e-12);
    EXPECT_NEAR(q.mu_norm_se, 0, 1e-9);
    EXPECT_GE(q.i_mean, q.i_lo * (1 - 1e-12));
    EXPECT_LE(q.i_mean, q.i_hi * (1 + 1e-12));
  }
  EXPECT_EQ(total, r.points.size());
  EXPECT_EQ(b.size(), 5u);
}

TEST(CavityRheology, Eq20RecoveredThroughTheLocalRheology) {
  // u = A y^2 over the whole grid: gd = 2 A y (finite differences exact for a quadratic, one-sided
  // ones too), I = d sqrt(rho) A y / sqrt(P) from 0.006 to 0.49; the shear stress set so that
  // Eq. 19 gives kneib2017's mu_th(I) (mu1 0.12, mu2 0.40, I0 0.13): tau = 3/2 mu P (szz = P).
  // Fitting Eq. 20 to the nodes returns the three parameters (rounding: 1e-9).
  const double P = 1000, d = 1e-3, rho = 2500, A = 0.49 / 20 * std::sqrt(P) / (d * std::sqrt(rho));
  Grid2D g = cells(10, 40, 0.5, 20.0 * 40 / 39.5);  // top node at y = 20
  fill_velocity(g, [&](double, double y) { return std::pair{A * y * y, 0.0}; });
  const std::size_t n = g.nx() * g.ny();
  g.sxx.assign(n, P);
  g.syy.assign(n, P);
  g.szz.assign(n, P);
  g.sxy.assign(n, 0.0);
  for (std::size_t i = 0; i < g.nx(); ++i)
    for (std::size_t j = 0; j < g.ny(); ++j) {
      const double I = d * std::sqrt(rho) * A * g.ys[j] / std::sqrt(P);
      g.sxy[g.at(i, j)] = -1.5 * sigmoid(I, 0.12, 0.40, 0.13) * P;  // compression positive
    }
  const Rheology r = local_rheology(g, Region{}, d, rho);
  Vec I, mu;
  for (auto& q : r.points) {
    I.push_back(q.i);
    mu.push_back(q.mu_loc);
  }
  const auto [lo, hi] = std::minmax_element(I.begin(), I.end());
  EXPECT_NEAR(*hi, 0.49, 1e-12);
  EXPECT_LT(*lo, 0.02);
  const LsqFit f = fit_sigmoid(I, mu);
  EXPECT_NEAR(param(f, "a").value, 0.12, 1e-9);
  EXPECT_NEAR(param(f, "b").value, 0.40, 1e-9);
  EXPECT_NEAR(param(f, "x0").value, 0.13, 1e-9);
}

TEST(CavityGrid, RowsInAnyOrderAndWindowsAveraged) {
  // Two windows of a 3 x 2 grid, rows shuffled: each node's value is its mean.
  const Vec x{0.5, 1.5, 2.5, 0.5, 1.5, 2.5, 2.5, 0.5, 1.5, 2.5, 1.5, 0.5};
  const Vec y{0.25, 0.25, 0.25, 0.75, 0.75, 0.75, 0.25, 0.25, 0.25, 0.75, 0.75, 0.75};
  Vec v;
  for (std::size_t r = 0; r < x.size(); ++r) v.push_back(10 * x[r] + y[r] + (r < 6 ? 1 : -1));
  const Grid2D g = grid_from_rows(x, y, {{&v, &Grid2D::vx}, {&v, &Grid2D::vy}});
  ASSERT_EQ(g.nx(), 3u);
  ASSERT_EQ(g.ny(), 2u);
  EXPECT_DOUBLE_EQ(g.vx[g.at(2, 1)], 25.75);
  EXPECT_DOUBLE_EQ(g.xlo, 0);
  EXPECT_DOUBLE_EQ(g.yhi, 1);
  Vec xm = x, ym = y, vm = v;  // a node missing from the second window: refused
  xm.pop_back();
  ym.pop_back();
  vm.pop_back();
  EXPECT_THROW(grid_from_rows(xm, ym, {{&vm, &Grid2D::vx}}), Error);
}

TEST(CavityGrid, ReadsFixAveCgHdf5InTheXzPlane) {
  // fix ave/cg's layout (fixes/fix_ave_cg.cpp): u [w][nx][ny][nz][3], stress* [w][nx][ny][nz][6]
  // (xx yy zz xy xz yz). Plane xz: x along, z up, y out of the plane (averaged over its nodes).
  const auto dir = std::filesystem::temp_directory_path() / ("sable_cavity_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "cg.h5").string();
  const std::size_t nx = 3, ny = 2, nz = 4;
  {
    sable::H5Series f(path);
    f.constant("x", {0.5, 1.5, 2.5});
    f.constant("y", {0.25, 0.75});
    f.constant("z", {0.125, 0.375, 0.625, 0.875});
    f.constant("shape", {double(nx), double(ny), double(nz)});
    f.constant("bounds", {0, 3, 0, 1, 0, 1});
    const int u = f.series("u", {nx, ny, nz, 3}, false), s = f.series("stress_contact", {nx, ny, nz, 6}, false);
    const int sm = f.series("samples", {}, false), st = f.series("step", {}, true);
    f.start();
    for (int w = 0; w < 3; ++w) {  // window 0 is skipped; windows 1 (1 sample) and 2 (3 samples) weighted
      Vec ur, sr;
      for (double i = 0; i < nx; ++i)
        for (double j = 0; j < ny; ++j)
          for (double k = 0; k < nz; ++k) {
            const double b = w == 0 ? 1e6 : w == 1 ? 4 : 0;  // weighted mean of b: (4 + 0)/4 = 1
            ur.insert(ur.end(), {i + b, 100 + j, 10 * k + b});
            sr.insert(sr.end(), {1 + b, 2 + j, 3 + k, 4, 5 + i, 6});
          }
      f.append(u, ur.data());
      f.append(s, sr.data());
      const double samples = w == 2 ? 3 : 1;
      f.append(sm, &samples);
      f.append(st, std::int64_t(100 * w));
    }
  }
  const Grid2D g = read_cg_grid(path, "xz", "stress_contact", 1);
  ASSERT_EQ(g.nx(), 3u);
  ASSERT_EQ(g.ny(), 4u);
  EXPECT_DOUBLE_EQ(g.ys[3], 0.875);
  EXPECT_DOUBLE_EQ(g.xhi, 3);
  EXPECT_DOUBLE_EQ(g.yhi, 1);
  EXPECT_DOUBLE_EQ(g.vx[g.at(2, 1)], 2 + 1);        // u_x = i + b
  EXPECT_DOUBLE_EQ(g.vy[g.at(2, 1)], 10 + 1);       // u_z = 10 k + b
  EXPECT_DOUBLE_EQ(g.sxx[g.at(1, 3)], 1 + 1);       // xx
  EXPECT_DOUBLE_EQ(g.syy[g.at(1, 3)], 3 + 3);       // zz: the vertical
  EXPECT_DOUBLE_EQ(g.szz[g.at(1, 3)], 2 + 0.5);     // yy out of the plane, mean over j = 0, 1
  EXPECT_DOUBLE_EQ(g.sxy[g.at(1, 3)], 5 + 1);       // xz
  EXPECT_THROW(read_cg_grid(path, "xz", "stress_contact", 3), Error);
  EXPECT_THROW(read_cg_grid(path, "xz", "stress_bogus", 0), Error);
  std::filesystem::remove_all(dir);
}
