// compute stress/cg in 2D (dimension 2): kernels normalised over the plane
// (kneib2017 App. C: a Gaussian of standard deviation d/2 in 2D), so that a
// lattice of disks gives the area fraction Phi_2D and the stress in N/m.
// Lattice sums against their exact values: square lattice of touching disks
// Phi = pi/4, hexagonal pi/(2 sqrt 3); every contact carrying F gives
// sigma = F/d (square, d = 2r: F/(2r)) and sqrt(3) F/d (hexagonal); the same
// through decks with `dimension 2`, `grains spheres` and `grains disks`.
// Tolerances are stated per test with their cause.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "computes/cg_field.h"
#include "computes/compute_stress_cg.h"
#include "tests/unit/deck_runner.h"
#include "tests/unit/lattice_deck_2d.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_stress_cg_2d {

using sable::CgField;
using sable::CgKernel;
using sable::test::Deck;
using sable::test::lattice_deck;

namespace {

constexpr double kPi = std::numbers::pi;
const double kSqrt3 = std::sqrt(3.0);
constexpr int kRho = 0, kPhi = 1, kS = 5;  // field offsets (cg_field.h)
enum { XX, YY, ZZ, XY, XZ, YZ };
const CgKernel::Kind kKinds[2] = {CgKernel::Kind::Lucy, CgKernel::Kind::Gauss};

template <class F>
double simpson(F&& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

// Nodes sampling the rectangle [-hx, hx] x [-hy, hy] uniformly, one node in z
// (at z = 0.4: a 2D kernel ignores z, the grains lie at z = 0).
CgField plane_grid(const CgKernel& k, double hx, double hy, int mx, int my) {
  const double lo[3] = {-hx, -hy, 0.3}, hi[3] = {hx, hy, 0.5};
  const int n[3] = {mx, my, 1};
  return CgField(k, lo, hi, n);
}

struct Stats {
  double mean = 0, maxdev = 0;  // mean over the nodes, largest |value / ref - 1|
};
Stats stats(const std::vector<double>& f, int field, double ref) {
  Stats s;
  const std::size_t n = f.size() / CgField::kFields;
  for (std::size_t p = 0; p < n; ++p) {
    const double v = f[p * CgField::kFields + field];
    s.mean += v / n;
    s.maxdev = std::max(s.maxdev, std::fabs(v / ref - 1));
  }
  return s;
}
double maxabs(const std::vector<double>& f, int field) {
  double m = 0;
  for (std::size_t p = 0; p < f.size() / CgField::kFields; ++p)
    m = std::max(m, std::fabs(f[p * CgField::kFields + field]));
  return m;
}

// Lattice sites within |i|, |j| <= h: square (x = i d, y = j d) or hexagonal
// (rows sqrt(3)/2 d apart, odd rows shifted by d/2), calling put(x).
template <class Put>
void sites(bool hex, double d, int h, Put&& put) {
  for (int j = -h; j <= h; ++j)
    for (int i = -h; i <= h; ++i) {
      const double x[3] = {(i + (hex && (j & 1) ? 0.5 : 0.0)) * d, j * d * (hex ? kSqrt3 / 2 : 1.0), 0.0};
      put(x);
    }
}

// Nodes sampling one unit cell: d x d (square) or d x sqrt(3) d (hexagonal,
// two sites); m per d along x (8 for w = 2 d, 16 for w = d).
CgField cell(bool hex, const CgKernel& k, double d) {
  const int m = k.w() < 1.5 * d ? 16 : 8;
  return hex ? plane_grid(k, d / 2, kSqrt3 * d / 2, m, 2 * m - 2) : plane_grid(k, d / 2, d / 2, m, m);
}

}  // namespace

// Both kernels in 2D integrate to 1 over the plane (radial Simpson, 2e4
// intervals: 1e-10), with the closed-form peaks 5/(pi w^2) (Lucy) and
// (1 - e^-4.5) / (pi s^2 (2 - 11 e^-4.5)), s = w/2 (Gauss), and the Gauss
// kernel has App. C's shape: W(r)/W(0) = (exp(-r^2/2s^2) - e^-4.5)/(1 - e^-4.5).
// The 3D kernels are those of dimension 3 (bit for bit).
TEST(StressCG2D, KernelsIntegrateToOneOverThePlane) {
  const double w = 0.003, s = w / 2, c = std::exp(-4.5);
  for (auto kind : kKinds) {
    const CgKernel k(kind, w, 2);
    EXPECT_EQ(k.dimension(), 2);
    const double I = simpson([&](double r) { return 2 * kPi * r * k.value(r); }, 0.0, k.support(), 20000);
    EXPECT_NEAR(I, 1.0, 1e-10) << k.name();
    const CgKernel k3(kind, w), k3b(kind, w, 3);
    EXPECT_EQ(k3.dimension(), 3);
    for (double r : {0.0, 0.3 * w, 0.9 * w}) EXPECT_EQ(k3.value(r), k3b.value(r));
  }
  const CgKernel lucy(CgKernel::Kind::Lucy, w, 2), gauss(CgKernel::Kind::Gauss, w, 2);
  EXPECT_NEAR(lucy.value(0), 5 / (kPi * w * w), 1e-14 * lucy.value(0));
  EXPECT_NEAR(gauss.value(0), (1 - c) / (kPi * s * s * (2 - 11 * c)), 1e-14 * gauss.value(0));
  for (double r : {0.5 * s, s, 2 * s, 2.9 * s})
    EXPECT_NEAR(gauss.value(r) / gauss.value(0), (std::exp(-r * r / (2 * s * s)) - c) / (1 - c), 1e-14);
}

// The closed-form line integral of a 2D kernel against Simpson along branches
// in the plane (1e5 intervals: 1e-9 W(0)), and the node's z does not count:
// a node lifted out of the plane gets the same share, bit for bit.
TEST(StressCG2D, LineIntegralInThePlane) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  for (auto kind : kKinds) {
    const CgKernel k(kind, 1.0, 2);
    const double R = k.support(), W0 = k.value(0);
    for (int t = 0; t < 100; ++t) {
      const double q[3] = {1.2 * R * U(rng), 1.2 * R * U(rng), 0};
      const double b[3] = {R * U(rng), R * U(rng), 0};
      const double ref = simpson([&](double u) { return k.value(std::hypot(q[0] + u * b[0], q[1] + u * b[1])); }, 0.0,
                                 1.0, 100000);
      EXPECT_NEAR(k.line(q, b), ref, 1e-9 * W0) << k.name();
    }
    // Through CgField: one contact, nodes at z = 0 and z = 0.4 R.
    for (double z : {0.0, 0.4 * R}) {
      const double lo[3] = {-R, -R, z}, hi[3] = {R, R, z + 1e-3};
      const int n[3] = {5, 5, 1};
      CgField g(k, lo, hi, n);
      const double x[3] = {0.1, 0.2, 0}, br[3] = {0.3, -0.2, 0}, f[3] = {1, 0.5, 0};
      g.add_contact(x, br, f);
      std::vector<double> out;
      g.finish(out);
      const double q[3] = {g.coord(0, 1) - x[0], g.coord(1, 3) - x[1], 0};
      ASSERT_GT(k.line(q, br), 0.1 * W0);
      EXPECT_EQ(out[(1 * 5 + 3) * CgField::kFields + kS + XX], f[0] * br[0] * k.line(q, br)) << z;
    }
  }
}

// Lattices of touching disks (diameter d, mass m) in the plane: Phi_2D =
// pi (d/2)^2 / cell area = pi/4 (square), pi/(2 sqrt 3) (hexagonal), rho =
// m / cell area. Averaged over a unit cell of nodes the lattice sum is the
// kernel's integral: within 1e-5 (measured at most 4.2e-6, the nodes' own
// sampling of the cell). At single nodes the lattice aliases the kernel,
// measured at most (square / hex): w = 2 d, Lucy 1.80e-2 / 7.27e-3, Gauss
// 9.85e-4 / 4.34e-4 (the kink at its cut); App. C's w = d (sd d/2), Gauss
// 3.24e-2 / 1.80e-2: a ripple of the field at the grain scale. Tolerances
// about 1.3x the measured.
TEST(StressCG2D, LatticeAreaFractionAndDensity) {
  const double d = 0.002, m = 1.3e-5;
  struct Case {
    bool hex;
    CgKernel::Kind kind;
    double w, tol;
  };
  const Case cases[] = {{false, CgKernel::Kind::Lucy, 2 * d, 0.024},  {true, CgKernel::Kind::Lucy, 2 * d, 0.0095},
                        {false, CgKernel::Kind::Gauss, 2 * d, 1.3e-3}, {true, CgKernel::Kind::Gauss, 2 * d, 5.7e-4},
                        {false, CgKernel::Kind::Gauss, d, 0.042},      {true, CgKernel::Kind::Gauss, d, 0.024}};
  for (const Case& c : cases) {
    const CgKernel k(c.kind, c.w, 2);
    CgField g = cell(c.hex, k, d);
    const double v[3] = {0, 0, 0};
    sites(c.hex, d, 12, [&](const double* x) { g.add_grain(x, v, m, kPi * d * d / 4); });
    std::vector<double> out;
    g.finish(out);
    const double area = c.hex ? kSqrt3 / 2 * d * d : d * d;  // per grain
    const double phi_want = c.hex ? kPi / (2 * kSqrt3) : kPi / 4;
    ASSERT_NEAR(kPi * d * d / 4 / area, phi_want, 1e-15);
    const Stats phi = stats(out, kPhi, phi_want), rho = stats(out, kRho, m / area);
    const std::string what = k.name() + (c.hex ? " hex" : " square") + " w/d " + std::to_string(c.w / d);
    EXPECT_NEAR(phi.mean, phi_want, 1e-5 * phi_want) << what;
    EXPECT_NEAR(rho.mean, m / area, 1e-5 * m / area) << what;
    EXPECT_LT(phi.maxdev, c.tol) << what;
    EXPECT_NEAR(phi.maxdev, rho.maxdev, 1e-12) << what;
    std::printf("[ measured ] %s: Phi max deviation %.2e, cell mean %.1e\n", what.c_str(), phi.maxdev,
                phi.mean / phi_want - 1);
  }
}

// Every contact carries F along its branch (compression, the force on i
// pointing from j to i). Square lattice, contact forces Fx along x and Fy
// along y: per cell of area d^2 one x contact (branch d) and one y contact,
// so sigma_xx = Fx d / d^2 = Fx/d, sigma_yy = Fy/d (N/m; Fx = Fy = F: the
// isotropic F/(2r) of touching disks of radius r = d/2), sigma_xy = 0 at
// every node (no contact has an xy part: 1e-15). Hexagonal lattice, every
// contact F: per grain area sqrt(3)/2 d^2 three contacts at 0, 60 and 120
// degrees, sum F d n n = 3/2 F d I, so sigma = sqrt(3) F / d I; xy cancels
// over the cell (mean within 1e-5 of sigma), not at every node. z
// components 0. Cell means within 1e-5 (measured at most 3.2e-6). Nodes:
// the aliasing, measured at most (square / hex): w = 2 d, Lucy 8.32e-3 /
// 2.21e-3, Gauss 4.07e-4 / 1.49e-4; w = d (Gauss) 1.59e-2 / 6.05e-3; hex
// |xy| / sigma: 1.30e-3 (Lucy), 8.58e-5, 3.43e-3 (Gauss 2 d, d).
// Tolerances about 1.3x the measured.
TEST(StressCG2D, LatticeContactStress) {
  const double d = 0.002, F = 0.7, Fy = 0.25;
  struct Case {
    bool hex;
    CgKernel::Kind kind;
    double w, tol, tol_xy;
  };
  const Case cases[] = {{false, CgKernel::Kind::Lucy, 2 * d, 0.011, 1e-15},     {true, CgKernel::Kind::Lucy, 2 * d, 2.9e-3, 1.7e-3},
                        {false, CgKernel::Kind::Gauss, 2 * d, 5.3e-4, 1e-15},   {true, CgKernel::Kind::Gauss, 2 * d, 2e-4, 1.1e-4},
                        {false, CgKernel::Kind::Gauss, d, 0.021, 1e-15},         {true, CgKernel::Kind::Gauss, d, 7.9e-3, 4.5e-3}};
  for (const Case& c : cases) {
    const CgKernel k(c.kind, c.w, 2);
    CgField g = cell(c.hex, k, d);
    const int dirs = c.hex ? 3 : 2;
    sites(c.hex, d, 12, [&](const double* x) {
      for (int a = 0; a < dirs; ++a) {  // the contact with the neighbour at x - b
        const double th = c.hex ? a * kPi / 3 : a * kPi / 2, f = c.hex || a == 0 ? F : Fy;
        const double n[3] = {std::cos(th), std::sin(th), 0};
        const double b[3] = {d * n[0], d * n[1], 0}, fv[3] = {f * n[0], f * n[1], 0};
        g.add_contact(x, b, fv);
      }
    });
    std::vector<double> out;
    g.finish(out);
    const double sxx = c.hex ? kSqrt3 * F / d : F / d, syy = c.hex ? sxx : Fy / d;
    const std::string what = k.name() + (c.hex ? " hex" : " square") + " w/d " + std::to_string(c.w / d);
    const Stats xx = stats(out, kS + XX, sxx), yy = stats(out, kS + YY, syy);
    EXPECT_NEAR(xx.mean, sxx, 1e-5 * sxx) << what;
    EXPECT_NEAR(yy.mean, syy, 1e-5 * syy) << what;
    EXPECT_LT(std::max(xx.maxdev, yy.maxdev), c.tol) << what;
    const Stats xy = stats(out, kS + XY, 1.0);
    EXPECT_LT(std::fabs(xy.mean), 1e-5 * sxx) << what;
    EXPECT_LT(maxabs(out, kS + XY), c.tol_xy * sxx) << what;
    for (int z : {ZZ, XZ, YZ}) EXPECT_EQ(maxabs(out, kS + z), 0.0) << what;
    std::printf("[ measured ] %s: stress max deviation %.2e (xx), %.2e (yy), max |xy| / xx %.2e, cell means %.1e %.1e\n",
                what.c_str(), xx.maxdev, yy.maxdev, maxabs(out, kS + XY) / sxx, xx.mean / sxx - 1, yy.mean / syy - 1);
  }
}

// compute stress/cg in decks with dimension 2: periodic square and hexagonal
// lattices of grains of diameter d = 2 mm at spacing a = 1.98 mm, every
// contact F = kn (d - a). Phi_2D = pi (d/2)^2 per grain area (a^2, or sqrt(3)/2
// a^2) for plain `dimension 2`, `grains disks` and `grains spheres` alike (a
// sphere in the plane covers its equator); rho = m per grain area with each
// convention's mass (pi r^2 rho_s, or 4/3 pi r^3 rho_s); sigma_xx = sigma_yy
// = F/a (square) or sqrt(3) F/a (hex) in N/m, sigma_xy = 0 (over the cell). Gauss kernel of
// App. C (w = a: sd a/2); nodes sampling one cell (straddling the box
// corner, so grains count through their periodic images), one node in z at
// z = 0.4 mm off the grains' plane. Cell means within 1e-5 (the nodes'
// sampling of the cell, as above).
TEST(StressCG2D, LatticeDecksInDimension2) {
  const double a = 0.00198, dia = 0.002, F = 2000 * (dia - a), r = dia / 2;
  for (const char* dim : {"dimension 2", "dimension 2 grains disks", "dimension 2 grains spheres"})
    for (bool hex : {false, true}) {
      Deck d;
      d(lattice_deck(dim, hex, a, 8, hex ? 5 : 8));
      ASSERT_EQ(d->atoms.n, 64u + (hex ? 16u : 0u)) << dim;
      char grid[200];
      const double hy = hex ? kSqrt3 * a / 2 : a / 2;
      std::snprintf(grid, sizeof grid, "grid %.17g %.17g 16 %.17g %.17g %d 0.0003 0.0005 1", -a / 2, a / 2, -hy, hy,
                    hex ? 30 : 16);
      d(std::string("compute cg all stress/cg kernel gauss 0.00198 ") + grid);
      d("run 0");
      const std::vector<double>& out = dynamic_cast<sable::ComputeStressCG*>(d->find_compute("cg"))->fields();
      const double area = hex ? kSqrt3 / 2 * a * a : a * a, m = d->atoms.rmass[0];
      const double rho_s = std::string(dim).find("spheres") != std::string::npos ? 4.0 / 3 * kPi * r * r * r * 2500
                                                                                   : kPi * r * r * 2500;
      EXPECT_NEAR(m, rho_s, 1e-15 * m) << dim;
      const double sig = hex ? kSqrt3 * F / a : F / a;
      const std::string what = std::string(dim) + (hex ? " hex" : " square");
      EXPECT_NEAR(stats(out, kPhi, 1).mean, kPi * r * r / area, 1e-5 * kPi * r * r / area) << what;
      EXPECT_NEAR(stats(out, kRho, 1).mean, m / area, 1e-5 * m / area) << what;
      for (int c : {XX, YY}) EXPECT_NEAR(stats(out, kS + c, 1).mean, sig, 1e-5 * sig) << what << " " << c;
      EXPECT_LT(std::fabs(stats(out, kS + XY, 1).mean), 1e-5 * sig) << what;
      for (int c : {ZZ, XZ, YZ}) EXPECT_EQ(maxabs(out, kS + c), 0.0) << what;
    }
}

}  // namespace test_stress_cg_2d
