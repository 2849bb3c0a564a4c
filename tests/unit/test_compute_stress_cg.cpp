// compute stress/cg and fix ave/cg: kernels and line integrals against
// quadrature, lattice fields against their analytic values, contact and
// kinetic stress signs, periodic images, wall contacts, the mesh frame, and
// the HDF5 averages read back. Tolerances are stated per test with their cause.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "computes/cg_field.h"
#include "computes/compute_stress_cg.h"
#include "core/engine/error.h"
#include "core/geometry/mesh.h"
#include "fixes/fix_mesh_surface.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_compute_stress_cg {

using sable::CgField;
using sable::CgKernel;
using sable::test::Deck;
using sable::test::error_of;
using sable::test::TempDir;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kRho = 0, kPhi = 1, kU = 2, kS = 5, kSc = 11, kSk = 17;  // field offsets (cg_field.h)
enum { XX, YY, ZZ, XY, XZ, YZ };

CgKernel kernel(CgKernel::Kind kind, double w) { return CgKernel(kind, w); }
const CgKernel::Kind kKinds[2] = {CgKernel::Kind::Lucy, CgKernel::Kind::Gauss};

// Composite Simpson of f on [a, b] with n (even) intervals.
template <class F>
double simpson(F&& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

// Nodes sampling one lattice cell [-d/2, d/2]^3 uniformly (m per axis).
CgField cell_grid(const CgKernel& k, double d, int m) {
  const double lo[3] = {-d / 2, -d / 2, -d / 2}, hi[3] = {d / 2, d / 2, d / 2};
  const int n[3] = {m, m, m};
  return CgField(k, lo, hi, n);
}

// Simple cubic lattice of spacing d, |i|, |j|, |k| <= h, calling put(i, j, k, x).
template <class Put>
void lattice(double d, int h, Put&& put) {
  for (int i = -h; i <= h; ++i)
    for (int j = -h; j <= h; ++j)
      for (int k = -h; k <= h; ++k) {
        const double x[3] = {i * d, j * d, k * d};
        put(i, j, k, x);
      }
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

}  // namespace

// Both kernels integrate to 1 over space (radial Simpson, 2e4 intervals: 1e-10),
// Lucy has its textbook peak, and the lowered Gaussian vanishes at its cut.
TEST(StressCG, KernelsIntegrateToOne) {
  for (auto kind : kKinds) {
    const CgKernel k = kernel(kind, 0.003);
    const double R = k.support();
    const double I = simpson([&](double r) { return 4 * kPi * r * r * k.value(r); }, 0.0, R, 20000);
    EXPECT_NEAR(I, 1.0, 1e-10) << k.name();
    EXPECT_EQ(k.value(R), 0.0);
    EXPECT_LT(k.value(R * (1 - 1e-9)), 1e-6 * k.value(0));  // continuous at the edge
  }
  EXPECT_NEAR(kernel(CgKernel::Kind::Lucy, 2.0).value(0), 105.0 / (16 * kPi * 8), 1e-15);
}

// The closed-form line integral against Simpson on s in [0, 1] (1e5
// intervals; both kernels are continuous, so Simpson is good to ~1e-12 W(0)):
// agreement within 1e-9 W(0) for random branches inside, across and beyond
// the support, through the node itself, and for a vanishing branch.
TEST(StressCG, LineIntegralMatchesQuadrature) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (auto kind : kKinds) {
    const CgKernel k = kernel(kind, 1.0);
    const double R = k.support(), W0 = k.value(0);
    auto check = [&](const double q[3], const double b[3]) {
      const double ref = simpson(
          [&](double s) {
            const double p[3] = {q[0] + s * b[0], q[1] + s * b[1], q[2] + s * b[2]};
            return k.value(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
          },
          0.0, 1.0, 100000);
      EXPECT_NEAR(k.line(q, b), ref, 1e-9 * W0) << k.name() << " q " << q[0] << " " << q[1] << " " << q[2];
    };
    for (int t = 0; t < 200; ++t) {
      const double q[3] = {1.2 * R * U(rng), 1.2 * R * U(rng), 1.2 * R * U(rng)};
      const double L = 1.5 * R * (U(rng) + 1) / 2 + 0.05 * R;
      double b[3] = {U(rng), U(rng), U(rng)};
      const double n = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
      for (double& c : b) c *= L / n;
      check(q, b);
    }
    const double through[3] = {-0.3 * R, 0, 0}, along[3] = {0.6 * R, 0, 0};  // the node lies on the branch
    check(through, along);
    const double q0[3] = {0.1 * R, 0.2 * R, 0}, b0[3] = {1e-13, 0, 0};  // a point
    EXPECT_NEAR(k.line(q0, b0), k.value(std::sqrt(0.05) * R), 1e-12 * W0);
  }
}

// One contact spread on a fine grid (spacing w/10) gives back its whole tensor:
// sum over nodes of stress * cell volume = sym(f (x) b), within 1e-6
// (the Riemann sum of a smooth kernel); nothing else is deposited.
TEST(StressCG, ContactSpreadsItsWholeTensor) {
  for (auto kind : kKinds) {
    const CgKernel k = kernel(kind, 1.0);
    const double R = k.support();
    const double lo[3] = {-2 * R, -2 * R, -2 * R}, hi[3] = {2 * R, 2 * R, 2 * R};
    const int m = static_cast<int>(std::lround(4 * R / 0.1));
    const int n[3] = {m, m, m};
    CgField g(k, lo, hi, n);
    const double x[3] = {0.31, -0.17, 0.05}, b[3] = {0.4, 0.3, -0.2}, f[3] = {1.5, -0.5, 0.25};
    g.add_contact(x, b, f);
    std::vector<double> out;
    g.finish(out);
    const double dv = std::pow(4 * R / m, 3);
    const double want[6] = {f[0] * b[0], f[1] * b[1], f[2] * b[2], (f[0] * b[1] + f[1] * b[0]) / 2,
                            (f[0] * b[2] + f[2] * b[0]) / 2, (f[1] * b[2] + f[2] * b[1]) / 2};
    for (int c = 0; c < 6; ++c) {
      double sum = 0;
      for (std::size_t p = 0; p < g.nodes(); ++p) sum += out[p * CgField::kFields + kS + c] * dv;
      EXPECT_NEAR(sum, want[c], 1e-6) << k.name() << " component " << c;
    }
    EXPECT_EQ(maxabs(out, kRho), 0.0);
    EXPECT_EQ(maxabs(out, kSk), 0.0);
  }
}

// A simple cubic lattice of touching spheres (diameter d, mass m): phi = pi/6,
// rho = m/d^3. Averaged over a unit cell of nodes (8^3), the lattice sum is
// the kernel's integral (1e-5). At single nodes the discrete lattice aliases
// the kernel (its Fourier transform at 2 pi / d): with w = 2 d, measured at
// most 1.43 % (Lucy, a C2 kernel; worst at lattice points and cell centres,
// 0.4 % at a generic point) and 0.24 % (lowered Gaussian): tolerances 1.5 % and 0.3 %.
TEST(StressCG, LatticeVolumeFractionAndDensity) {
  const double d = 0.002, m = 1.3e-5;
  for (auto kind : kKinds) {
    const CgKernel k = kernel(kind, 2 * d);
    CgField g = cell_grid(k, d, 8);
    const double v[3] = {0, 0, 0};
    lattice(d, 6, [&](int, int, int, const double* x) { g.add_grain(x, v, m, kPi / 6 * d * d * d); });
    std::vector<double> out;
    g.finish(out);
    const double tol = kind == CgKernel::Kind::Lucy ? 0.015 : 0.003;
    const Stats phi = stats(out, kPhi, kPi / 6), rho = stats(out, kRho, m / (d * d * d));
    EXPECT_NEAR(phi.mean, kPi / 6, 1e-5 * kPi / 6) << k.name();
    EXPECT_NEAR(rho.mean, m / (d * d * d), 1e-5 * m / (d * d * d)) << k.name();
    EXPECT_LT(phi.maxdev, tol) << k.name();
    EXPECT_LT(rho.maxdev, tol) << k.name();
    std::printf("[ measured ] %s w = 2d: phi max deviation %.2e, cell mean %.2e\n", k.name().c_str(), phi.maxdev,
                phi.mean / (kPi / 6) - 1);
  }
}

// Every contact along x carries the same force F: stress_xx = F / d^2
// (compression positive: the force on i from its left neighbour points +x,
// the branch from that neighbour to i too), all other components zero (the
// lattice is symmetric under y -> -y, z -> -z: 1e-12). Cell mean 1e-5;
// single nodes: the 2D lattice aliasing of the kernel's projection, measured
// 0.91 % (Lucy) / 0.099 % (Gauss), tolerances 1 % / 0.15 %. Pulling flips the sign.
TEST(StressCG, LatticeContactStressAlongX) {
  const double d = 0.002, F = 0.7;
  for (auto kind : kKinds)
    for (double sign : {1.0, -1.0}) {
      const CgKernel k = kernel(kind, 2 * d);
      CgField g = cell_grid(k, d, 8);
      const double b[3] = {d, 0, 0}, f[3] = {sign * F, 0, 0};
      lattice(d, 6, [&](int i, int, int, const double* x) {
        if (i > -6) g.add_contact(x, b, f);  // the contact with the left neighbour
      });
      std::vector<double> out;
      g.finish(out);
      const double want = sign * F / (d * d);
      const Stats s = stats(out, kS + XX, want);
      EXPECT_NEAR(s.mean, want, 1e-5 * F / (d * d)) << k.name();
      EXPECT_LT(s.maxdev, kind == CgKernel::Kind::Lucy ? 0.01 : 0.0015) << k.name();
      for (int c : {YY, ZZ, XY, XZ, YZ}) EXPECT_LT(maxabs(out, kS + c), 1e-12 * F / (d * d)) << c;
      for (int c = 0; c < 6; ++c) EXPECT_EQ(out[kSc + c], out[kS + c]);  // no kinetic part
      std::printf("[ measured ] %s: stress_xx max deviation %.2e\n", k.name().c_str(), s.maxdev);
    }
}

// Grains moving +v and -v alternately (along x: by the parity of i; or as a
// 3D checkerboard: parity of i + j + k), at rest on average. Per node
// stress_kinetic_xx = rho v^2 - rho u_x^2 exactly (sum m v_x^2 W = rho v^2;
// 1e-12), the other components 0. u itself is the lattice's aliasing of the
// kernel at the pattern's wave vector: measured |u|/v at most 0.31 (Lucy,
// parity of i: w = 2 d cannot resolve a wave of length 2 d), 0.014 (Gauss,
// exp(-pi^2/2) twice), and for the checkerboard 4.3e-3 (Lucy) and 1.7e-3
// (Gauss, the kink at its cut): tolerances 0.32, 0.015, 5e-3, 2e-3. So with
// w = 2 d, stress_kinetic_xx equals rho v^2 within 10 % (Lucy, along x) and 0.02 % (Gauss).
TEST(StressCG, KineticStressOfAlternatingVelocities) {
  const double d = 0.002, m = 1.3e-5, V = 0.3;
  for (bool checker : {false, true})
    for (auto kind : kKinds) {
      const CgKernel k = kernel(kind, 2 * d);
      CgField g = cell_grid(k, d, 6);
      lattice(d, 6, [&](int i, int j, int l, const double* x) {
        const double v[3] = {(checker ? i + j + l : i) % 2 ? -V : V, 0, 0};
        g.add_grain(x, v, m, kPi / 6 * d * d * d);
      });
      std::vector<double> out;
      g.finish(out);
      double umax = 0;
      for (std::size_t p = 0; p < g.nodes(); ++p) {
        const double* o = &out[p * CgField::kFields];
        umax = std::max(umax, std::fabs(o[kU]) / V);
        EXPECT_NEAR(o[kSk + XX], o[kRho] * (V * V - o[kU] * o[kU]), 1e-12 * o[kRho] * V * V);
        EXPECT_EQ(o[kU + 1], 0.0);
        EXPECT_EQ(o[kS + XX], o[kSk + XX]);  // no contacts
        for (int c : {YY, ZZ, XY, XZ, YZ}) EXPECT_NEAR(o[kSk + c], 0.0, 1e-12 * o[kRho] * V * V);
      }
      const bool lucy = kind == CgKernel::Kind::Lucy;
      EXPECT_LT(umax, checker ? (lucy ? 5e-3 : 2e-3) : (lucy ? 0.32 : 0.015)) << k.name();
      std::printf("[ measured ] %s, %s: |u|/v at most %.2e\n", k.name().c_str(), checker ? "checkerboard" : "along x",
                  umax);
    }
}

namespace {

// Linear springs (kn = 2000 N/m): a contact of overlap dn carries kn dn at rest.
std::string head(const std::string& boundary, const std::string& box) {
  return "units si\natom_style granular\nboundary " + boundary + "\nregion box block " + box +
         R"( units box
create_box 1 box
neighbor 0.0004 bin
fix k1 all property/global kn peratomtypepair 1 2000
fix k2 all property/global kt peratomtypepair 1 1000
fix k3 all property/global gamman_abs peratomtypepair 1 0.02
fix k4 all property/global gammat_abs peratomtypepair 1 0.01
fix k5 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hooke/stiffness tangential history absolute_damping on
pair_coeff * *
timestep 1e-6
)";
}

sable::ComputeStressCG* cg_of(Deck& d, const char* id) {
  return dynamic_cast<sable::ComputeStressCG*>(d->find_compute(id));
}

// An ASCII STL square [-h, h]^2 in the plane z = 0 (two triangles).
std::string floor_stl(const std::string& path, double h) {
  std::ofstream f(path);
  f << "solid floor\n";
  const double t[2][9] = {{-h, -h, 0, h, -h, 0, h, h, 0}, {-h, -h, 0, h, h, 0, -h, h, 0}};
  for (auto& tri : t) {
    f << "facet normal 0 0 1\nouter loop\n";
    for (int k = 0; k < 3; ++k) f << "vertex " << tri[3 * k] << " " << tri[3 * k + 1] << " " << tri[3 * k + 2] << "\n";
    f << "endloop\nendfacet\n";
  }
  f << "endsolid\n";
  return path;
}

}  // namespace

// A periodic simple cubic lattice (spacing a = 1.98 mm, diameter 2 mm) at
// rest, its contacts from pair_style gran: every contact carries F = kn (d - a),
// so the stress is isotropic F / a^2, compression positive. The node cell
// straddles the box corner, so the grains and branches near the far faces
// count through their periodic images. Cell means within 1e-5; phi, rho too.
TEST(StressCG, PeriodicLatticeDeck) {
  const double a = 0.00198, dia = 0.002, F = 2000 * (dia - a);
  Deck d;
  d(head("p p p", "0 0.01584 0 0.01584 0 0.01584"));
  d("lattice sc 0.00198\ncreate_atoms 1 box\nset group all diameter 0.002 density 2500");
  ASSERT_EQ(d->atoms.n, 512u);
  d("compute cg all stress/cg kernel lucy 0.004 grid -0.00099 0.00099 6 -0.00099 0.00099 6 -0.00099 0.00099 6");
  d("run 0");
  const std::vector<double>& out = cg_of(d, "cg")->fields();
  const double m = d->atoms.rmass[0];
  for (int c : {XX, YY, ZZ}) EXPECT_NEAR(stats(out, kS + c, 1).mean, F / (a * a), 1e-5 * F / (a * a)) << c;
  for (int c : {XY, XZ, YZ}) EXPECT_LT(maxabs(out, kS + c), 1e-9 * F / (a * a)) << c;
  EXPECT_LT(maxabs(out, kSk), 1e-20);  // at rest
  EXPECT_NEAR(stats(out, kPhi, 1).mean, kPi / 6 * dia * dia * dia / (a * a * a), 1e-5);
  EXPECT_NEAR(stats(out, kRho, 1).mean, m / (a * a * a), 1e-5 * m / (a * a * a));
  EXPECT_GT(out[kS + XX], 0.0);  // compression positive
}

// A grain pressed into a wall (overlap 20 um, F = kn dn): the wall contact's
// branch runs from the contact point to the centre, so the stress summed over
// a fine grid times the cell volume is F (r - dn) in zz and nothing else
// (1e-5 relative: the grid's Riemann sum), positive (compression). The same
// for a primitive zplane and a flat mesh, whose force on the wall is f_floor[3] = -F.
TEST(StressCG, WallContactsPrimitiveAndMesh) {
  TempDir tmp;
  const double r = 0.001, dn = 2e-5, F = 2000 * dn;
  const std::string walls[2] = {
      "fix floor all wall/gran model hooke/stiffness tangential history primitive type 1 zplane 0.0 "
      "absolute_damping on",
      "fix m all mesh/surface file " + floor_stl(tmp / "floor.stl", 0.01) +
          " type 1\nfix floor all wall/gran model hooke/stiffness tangential history mesh n_meshes 1 meshes m "
          "absolute_damping on"};
  for (const std::string& wall : walls) {
    Deck d;
    d(head("f f f", "-0.01 0.01 -0.01 0.01 -0.01 0.01"));
    d(wall);
    d("create_atoms 1 single 0.0003 -0.0002 0.00098 units box\nset group all diameter 0.002 density 2500");
    d("compute cg all stress/cg kernel lucy 0.002 grid -0.0027 0.0033 30 -0.0032 0.0028 30 -0.0025 0.0035 30");
    d("run 0");
    EXPECT_NEAR(d->find_fix("floor")->compute_vector(3), -F, 1e-9 * F);
    const std::vector<double>& out = cg_of(d, "cg")->fields();
    const double dv = std::pow(0.0002, 3);
    double sum[6] = {};
    for (std::size_t p = 0; p < out.size() / CgField::kFields; ++p)
      for (int c = 0; c < 6; ++c) sum[c] += out[p * CgField::kFields + kS + c] * dv;
    EXPECT_NEAR(sum[ZZ], F * (r - dn), 1e-5 * F * r) << wall;
    for (int c : {XX, YY, XY, XZ, YZ}) EXPECT_LT(std::fabs(sum[c]), 1e-12 * F * r) << c;
    double smin = 0;
    for (std::size_t p = 0; p < out.size() / CgField::kFields; ++p)
      smin = std::min(smin, out[p * CgField::kFields + kS + ZZ]);
    EXPECT_EQ(smin, 0.0);  // compression positive everywhere
  }
}

// frame mesh: the same two touching grains (and a third alone) set up once
// in the world at body positions p, velocities v, and once moved by a mesh
// pose (R: 30 degrees about (1, 2, 2)/3, T) to R p + T with velocities R v.
// With `frame mesh` the second gives the first's fields (u and the tensors
// rotated back by R^T; 1e-9 of each field's largest value: round-off of the
// rotation). The lone grain sits on a node: rho there is m W(0) (1e-12), so
// node p is at world R p + T.
TEST(StressCG, FrameMeshMapsNodesAndRotatesTensorsBack) {
  TempDir tmp;
  const double p[3][3] = {{-0.002, 0.0, 0.0}, {-0.0002, 0.0005, 0.0002}, {0.0035, -0.0025, 0.0005}};
  const double v[3][3] = {{0.05, -0.02, 0.01}, {-0.04, 0.03, 0.0}, {0.01, 0.02, -0.03}};
  // Rotation by angle t about unit axis n (Rodrigues), row-major.
  const double n[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, t = kPi / 6, c = std::cos(t), s = std::sin(t);
  double R[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[3 * i + j] = (i == j ? c : 0.0) + (1 - c) * n[i] * n[j];
  R[1] -= s * n[2], R[2] += s * n[1], R[3] += s * n[2], R[5] -= s * n[0], R[6] -= s * n[1], R[7] += s * n[0];
  const double T[3] = {0.001, -0.002, 0.0005};
  const std::string grid = " kernel lucy 0.002 grid -0.006 0.006 12 -0.006 0.006 12 -0.006 0.006 12";
  std::vector<double> fields[2];
  for (int moved = 0; moved < 2; ++moved) {
    Deck d;
    d(head("f f f", "-0.01 0.01 -0.01 0.01 -0.01 0.01"));
    d("fix m all mesh/surface file " + floor_stl(tmp / "far.stl", 0.001) + " type 1 move 0 0 -0.009");
    char line[200];
    for (int g = 0; g < 3; ++g) {
      double x[3];
      for (int i = 0; i < 3; ++i)
        x[i] = moved ? R[3 * i] * p[g][0] + R[3 * i + 1] * p[g][1] + R[3 * i + 2] * p[g][2] + T[i] : p[g][i];
      std::snprintf(line, sizeof line, "create_atoms 1 single %.17g %.17g %.17g units box", x[0], x[1], x[2]);
      d(line);
    }
    d("set group all diameter 0.002 density 2500");
    for (int g = 0; g < 3; ++g)
      for (int i = 0; i < 3; ++i)
        d->atoms.v[3 * g + i] = moved ? R[3 * i] * v[g][0] + R[3 * i + 1] * v[g][1] + R[3 * i + 2] * v[g][2] : v[g][i];
    if (moved) {
      sable::TriMesh& mesh = dynamic_cast<sable::FixMeshSurface*>(d->find_fix("m"))->mesh();
      std::copy(R, R + 9, mesh.R);
      mesh.T = {T[0], T[1], T[2]};
    }
    d(std::string("compute cg all stress/cg") + grid + (moved ? " frame mesh m" : ""));
    d("run 0");
    fields[moved] = cg_of(d, "cg")->fields();
    if (moved) {
      // Node (9, 3, 6) is body (0.0035, -0.0025, 0.0005): the lone grain's place.
      const std::size_t node = (9 * 12 + 3) * 12 + 6;
      EXPECT_NEAR(fields[1][node * CgField::kFields + kRho],
                  d->atoms.rmass[2] * kernel(CgKernel::Kind::Lucy, 0.002).value(0), 1e-12 * fields[1][node * 23]);
    }
  }
  ASSERT_GT(maxabs(fields[0], kSc + XX), 0.0);  // the pair touches
  // u is momentum over rho: where rho vanishes (a node at the support's edge), it jumps from v to 0.
  const double rho_min = 1e-9 * maxabs(fields[0], kRho);
  for (int f = 0; f < CgField::kFields; ++f) {
    const double scale = maxabs(fields[0], f);
    for (std::size_t q = 0; q < fields[0].size() / CgField::kFields; ++q)
      if (f < kU || f >= kU + 3 || fields[0][q * CgField::kFields] > rho_min) {
        ASSERT_NEAR(fields[1][q * CgField::kFields + f], fields[0][q * CgField::kFields + f], 1e-9 * scale)
          << "field " << f << " node " << q;
      }
  }
}

// A column at rest under gravity, built in equilibrium: 12 layers of 4 x 4
// touching grains (periodic in x and y) on a zplane floor, each layer's
// contacts with the one below compressed by the weight above (kn dn = k m g).
// Away from the floor and the top by more than the support, stress_zz(z) is
// the weight above per area, m g (z_top - z) / d^3 (z_top = top layer + d/2:
// a linear profile is unchanged by a symmetric kernel; the layers' staircase
// differs from it by a sawtooth the kernel damps). Measured deviation at most
// 2.3e-3 m g / d^2 (Lucy, w = 2 d): tolerance 0.01 m g / d^2 (of a stress up to
// 9.5 m g / d^2); stress_xx, stress_yy 0 (no lateral forces; 1e-9).
TEST(StressCG, ColumnUnderGravityCarriesTheWeightAbove) {
  const double d = 0.002, kn = 2e5, g = 9.81;
  const int N = 12;
  Deck deck;
  std::string h = head("p p f", "0 0.008 0 0.008 0 0.03");
  h.replace(h.find("kn peratomtypepair 1 2000"), 25, "kn peratomtypepair 1 200000");
  deck(h);
  deck("fix floor all wall/gran model hooke/stiffness tangential history primitive type 1 zplane 0.0 "
       "absolute_damping on\nfix grav all gravity 9.81 vector 0 0 -1");
  deck("create_atoms 1 single 0.001 0.001 0.001 units box\nset group all diameter 0.002 density 2500");
  const double mg = deck->atoms.rmass[0] * g;
  deck("delete_atoms group all");
  double z = d / 2 - N * mg / kn;  // the floor carries all N layers
  char line[160];
  for (int k = 0; k < N; ++k) {
    if (k > 0) z += d - (N - k) * mg / kn;  // the contacts below layer k carry N - k layers
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        std::snprintf(line, sizeof line, "create_atoms 1 single %.17g %.17g %.17g units box", (i + 0.5) * d,
                      (j + 0.5) * d, z);
        deck(line);
      }
  }
  deck("set group all diameter 0.002 density 2500");
  const double ztop = z + d / 2;
  deck("compute cg all stress/cg kernel lucy 0.004 grid 0.0013 0.0017 1 0.0023 0.0027 1 0.0049 0.0191 29");
  deck("run 0");
  const std::vector<double>& out = cg_of(deck, "cg")->fields();
  const sable::CgField& f = cg_of(deck, "cg")->field();
  double worst = 0;
  for (int k = 0; k < 29; ++k) {
    const double zk = f.coord(2, k), want = mg * (ztop - zk) / (d * d * d);
    const double* o = &out[k * CgField::kFields];
    worst = std::max(worst, std::fabs(o[kS + ZZ] - want) / (mg / (d * d)));
    EXPECT_NEAR(o[kS + ZZ], want, 0.01 * mg / (d * d)) << "z " << zk;
    EXPECT_NEAR(o[kS + XX], 0.0, 1e-9 * mg / (d * d));
    EXPECT_NEAR(o[kS + YY], 0.0, 1e-9 * mg / (d * d));
  }
  std::printf("[ measured ] column: stress_zz deviation at most %.2e m g / d^2\n", worst);
}

// fix ave/cg: two colliding grains sampled every 2 steps, averaged every 6:
// the file's rows are the means of the compute's samples (1e-12 relative),
// with the step, sample count, node coordinates and attributes; f_ID is the last mean.
TEST(FixAveCG, FileHoldsTheWindowMeans) {
  TempDir tmp;
  Deck d;
  d(head("f f f", "-0.01 0.01 -0.01 0.01 -0.01 0.01"));
  d("create_atoms 1 single -0.00099 0 0 units box\ncreate_atoms 1 single 0.00099 0.0002 0 units box");
  d("set group all diameter 0.002 density 2500\nvelocity all set 0.5 0 0\nfix i all nve/sphere");
  d->atoms.v[3] = -0.5;
  d("compute cg all stress/cg kernel gauss 0.002 grid -0.003 0.003 5 -0.002 0.002 4 -0.002 0.002 3");
  d("fix a all ave/cg 2 6 c_cg file " + (tmp / "cg.h5"));
  std::vector<std::vector<double>> samples;
  for (int k = 0; k < 6; ++k) {
    d("run 2");
    samples.push_back(cg_of(d, "cg")->fields());
  }
  const std::size_t nodes = 5 * 4 * 3, nf = CgField::kFields;
  std::vector<double> mean[2];
  for (int w = 0; w < 2; ++w) {
    mean[w].assign(nodes * nf, 0.0);
    for (int k = 0; k < 3; ++k)
      for (std::size_t i = 0; i < nodes * nf; ++i) mean[w][i] += samples[3 * w + k][i];
    for (double& x : mean[w]) x /= 3;
  }
  ASSERT_GT(maxabs(mean[1], kSc + XX), 0.0);  // they collide
  ASSERT_NE(samples[0], samples[2]);
  EXPECT_EQ(d->find_fix("a")->compute_vector(static_cast<int>(7 * nf + kS + 1)), mean[1][7 * nf + kS]);

  const hid_t f = H5Fopen((tmp / "cg.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  auto read = [&](const char* name, hid_t type, std::vector<hsize_t>& dims, void* out) {
    const hid_t ds = H5Dopen2(f, name, H5P_DEFAULT);
    ASSERT_GE(ds, 0) << name;
    const hid_t sp = H5Dget_space(ds);
    dims.assign(H5Sget_simple_extent_ndims(sp), 0);
    H5Sget_simple_extent_dims(sp, dims.data(), nullptr);
    EXPECT_GE(H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out), 0);
    H5Sclose(sp);
    H5Dclose(ds);
  };
  std::vector<hsize_t> dims;
  std::int64_t steps[2];
  double count[2], xs[5];
  read("step", H5T_NATIVE_INT64, dims, steps);
  EXPECT_EQ(dims, std::vector<hsize_t>{2});
  EXPECT_EQ(steps[0], 6);
  EXPECT_EQ(steps[1], 12);
  read("samples", H5T_NATIVE_DOUBLE, dims, count);
  EXPECT_EQ(count[0], 3.0);
  EXPECT_EQ(count[1], 3.0);
  read("x", H5T_NATIVE_DOUBLE, dims, xs);
  EXPECT_NEAR(xs[1], -0.003 + 1.5 * 0.0012, 1e-15);
  for (const auto& grp : CgField::kGroups) {
    std::vector<double> rows(2 * nodes * grp.count);
    read(grp.name, H5T_NATIVE_DOUBLE, dims, rows.data());
    std::vector<hsize_t> want{2, 5, 4, 3};
    if (grp.count > 1) want.push_back(grp.count);
    EXPECT_EQ(dims, want) << grp.name;
    for (int w = 0; w < 2; ++w)
      for (std::size_t q = 0; q < nodes; ++q)
        for (int c = 0; c < grp.count; ++c) {
          const double m = mean[w][q * nf + grp.first + c];
          EXPECT_NEAR(rows[(w * nodes + q) * grp.count + c], m, 1e-12 * std::fabs(m)) << grp.name;
        }
  }
  // The kernel's name, a variable-length string attribute.
  const hid_t at = H5Aopen(f, "kernel", H5P_DEFAULT);
  ASSERT_GE(at, 0);
  const hid_t st = H5Tcopy(H5T_C_S1);
  H5Tset_size(st, H5T_VARIABLE);
  char* name = nullptr;
  EXPECT_GE(H5Aread(at, st, &name), 0);
  EXPECT_STREQ(name, "gauss");
  H5free_memory(name);
  H5Tclose(st);
  H5Aclose(at);
  H5Fclose(f);
}

TEST(StressCG, ErrorsNameTheWord) {
  TempDir tmp;
  Deck d;
  d(head("f f f", "0 1 0 1 0 1"));
  const std::string grid = " grid 0 1 2 0 1 2 0 1 2";
  EXPECT_NE(error_of(d, "compute c all stress/cg kernal lucy 0.1" + grid)
                .find("'kernal' in 'compute c all stress/cg kernal lucy 0.1 grid 0 1 2 0 1 2 0 1 2': expected a "
                      "stress/cg keyword: kernel, grid or frame"),
            std::string::npos);
  EXPECT_NE(error_of(d, "compute c all stress/cg kernel cubic 0.1" + grid).find("'cubic'"), std::string::npos);
  EXPECT_NE(error_of(d, "compute c all stress/cg kernel lucy -1" + grid).find("expected a kernel width W > 0"),
            std::string::npos);
  EXPECT_NE(error_of(d, "compute c all stress/cg kernel lucy 0.1 grid 0 1 2 1 0 2 0 1 2").find("expected the grid's yhi > ylo"),
            std::string::npos);
  EXPECT_NE(error_of(d, "compute c all stress/cg kernel lucy 0.1").find("expected 'grid xlo xhi nx"), std::string::npos);
  EXPECT_NE(error_of(d, "compute c all stress/cg kernel lucy 0.1" + grid + " frame mesh nope")
                .find("'nope' in"),
            std::string::npos);
  d("compute ke all ke");
  d("compute c all stress/cg kernel lucy 0.1" + grid);
  EXPECT_NE(error_of(d, "fix a all ave/cg 2 5 c_c file " + (tmp / "x.h5")).find("a multiple of Nevery (2)"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/cg 2 4 c_ke file " + (tmp / "x.h5")).find("(ke is a compute ke)"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/cg 2 4 c_c hdf5 " + (tmp / "x.h5")).find("expected file F.h5"),
            std::string::npos);
}

}  // namespace test_compute_stress_cg
