// fix particletemplate/multisphere + fix multisphere (LIGGGHTS clumps): the
// Monte-Carlo mass and inertia against analytic values, given mass and
// inertia, free fall and spin of an inserted clump, sliding on an incline,
// insert/pack counting clumps, restarts and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/engine/error.h"
#include "core/input/variable.h"
#include "fixes/fix_multisphere.h"
#include "fixes/fix_particletemplate_multisphere.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_multisphere {

using sable::ClumpShape;
using sable::FixMultisphere;
using sable::FixParticletemplateMultisphere;
using sable::test::Deck;
using sable::test::error_of;

namespace {

constexpr double kRho = 2500, kR = 0.002, kG = 9.81;
constexpr double kPi = std::numbers::pi;

std::string box(const std::string& gravity = "fix g all gravity 9.81 vector 0 0 -1\n") {
  return R"(units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region box block -0.05 0.15 -0.05 0.05 -0.01 0.1 units box
create_box 1 box
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.3
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-6
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
)" + gravity;
}

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// A template of spheres (x y z r each), Monte Carlo with ntry points unless `extra` gives mass and inertia.
std::string tmpl(const std::vector<std::array<double, 4>>& s, long ntry = 1000000, const std::string& extra = "") {
  std::string t = "fix pt all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres " +
                  std::to_string(s.size()) + " ntry " + std::to_string(ntry) + " spheres";
  for (auto& q : s)
    for (double v : q) t += " " + num(v);
  return t + " type 1" + extra + "\nfix pdd all particledistribution/discrete 15485867 1 pt 1.0\n";
}

// One clump inserted with its centre of mass at (x, y, z) (a region a nanometre wide).
std::string insert_at(double x, double y, double z, const std::string& extra = "") {
  const double e = 1e-9;
  return "region ins block " + num(x - e) + " " + num(x + e) + " " + num(y - e) + " " + num(y + e) + " " + num(z - e) +
         " " + num(z + e) + " units box\nfix ms all multisphere\n"
         "fix ins all insert/pack seed 32452843 distributiontemplate pdd insert_every once overlapcheck yes "
         "region ins particles_in_region 1" + extra + "\n";
}

// Volume and inertia of a union of spheres centred on the x axis, by
// quadrature of its profile as a solid of revolution (Simpson, 20001 points):
// V = int pi rho^2, Ixx = int pi/2 rho^4, Iyy = int pi/4 rho^4 + pi rho^2 (x - xc)^2.
struct Revolution {
  double volume, xc, ixx, iyy;
};
Revolution revolve(const std::vector<std::array<double, 2>>& spheres) {  // (x, r)
  double lo = 1e300, hi = -1e300;
  for (auto& s : spheres) lo = std::min(lo, s[0] - s[1]), hi = std::max(hi, s[0] + s[1]);
  const int n = 20000;
  const double h = (hi - lo) / n;
  auto rho2 = [&](double x) {
    double m = 0;
    for (auto& s : spheres) m = std::max(m, s[1] * s[1] - (x - s[0]) * (x - s[0]));
    return m;
  };
  auto simpson = [&](auto f) {
    double sum = 0;
    for (int i = 0; i <= n; ++i) sum += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * f(lo + i * h);
    return sum * h / 3;
  };
  Revolution r;
  r.volume = simpson([&](double x) { return kPi * rho2(x); });
  r.xc = simpson([&](double x) { return kPi * rho2(x) * x; }) / r.volume;
  r.ixx = simpson([&](double x) { return kPi / 2 * rho2(x) * rho2(x); });
  r.iyy = simpson([&](double x) { return kPi / 4 * rho2(x) * rho2(x) + kPi * rho2(x) * (x - r.xc) * (x - r.xc); });
  return r;
}

// Relative standard error of a Monte-Carlo hit fraction p over n points: sqrt((1 - p) / (p n)).
double mc_error(double volume, double box_volume, long n) {
  const double p = volume / box_volume;
  return std::sqrt((1 - p) / (p * n));
}

const FixParticletemplateMultisphere& templ(Deck& d) {
  return *d->find_fix_style<FixParticletemplateMultisphere>();
}

}  // namespace

// Two spheres of radius R whose centres are R apart: the union's volume is
// 2 (4/3 pi R^3) minus the lens pi (4R + d)(2R - d)^2 / 12 (sphere-sphere
// intersection, e.g. Weisstein, MathWorld "Sphere-Sphere Intersection"); the
// centre at d/2; the moments by quadrature of the profile. The Monte Carlo
// (10^6 points) agrees within 4 of its standard errors (0.09 % for the volume).
TEST(Multisphere, MonteCarloMatchesLensVolumeAndInertia) {
  const double d = kR;
  Deck deck;
  deck(box() + tmpl({{{0, 0, 0, kR}}, {{d, 0, 0, kR}}}));
  const ClumpShape& s = templ(deck).shape();
  const double lens = kPi * (4 * kR + d) * (2 * kR - d) * (2 * kR - d) / 12;
  const double v = 2 * 4.0 / 3 * kPi * kR * kR * kR - lens;
  const double box_volume = (2 * kR + d) * 4 * kR * kR;
  const double err = mc_error(v, box_volume, 1000000);
  EXPECT_NEAR(s.volume / v - 1, 0, 4 * err);
  EXPECT_NEAR(s.mass / (kRho * v) - 1, 0, 4 * err);
  EXPECT_NEAR(templ(deck).centre_of_mass()[0] / (d / 2) - 1, 0, 4 * err * (2 * kR + d) / d);
  const Revolution r = revolve({{{0, kR}}, {{d, kR}}});
  EXPECT_NEAR(r.volume / v - 1, 0, 1e-9);  // the quadrature reproduces the lens formula
  std::array<double, 3> m = s.moments;
  std::sort(m.begin(), m.end());  // the axis of revolution has the smallest moment
  EXPECT_NEAR(m[0] / (kRho * r.ixx) - 1, 0, 5 * err);
  EXPECT_NEAR(m[1] / (kRho * r.iyy) - 1, 0, 5 * err);
  EXPECT_NEAR(m[2] / (kRho * r.iyy) - 1, 0, 5 * err);
}

// Two separate spheres (radii R and R/2, 3R apart): mass = sum of the spheres,
// I = sum of 2/5 m r^2 plus m (distance to the centre of mass)^2 (parallel axes).
TEST(Multisphere, MonteCarloMatchesSeparateSpheres) {
  Deck deck;
  deck(box() + tmpl({{{0, 0, 0, kR}}, {{3 * kR, 0, 0, kR / 2}}}));
  const ClumpShape& s = templ(deck).shape();
  const double m1 = kRho * 4.0 / 3 * kPi * kR * kR * kR, m2 = m1 / 8, m = m1 + m2;
  const double xc = m2 * 3 * kR / m;
  const double ix = 0.4 * m1 * kR * kR + 0.4 * m2 * kR * kR / 4;
  const double iy = ix + m1 * xc * xc + m2 * (3 * kR - xc) * (3 * kR - xc);
  const double err = mc_error(m / kRho, 3.5 * kR * 4 * kR * kR, 1000000);
  EXPECT_NEAR(s.mass / m - 1, 0, 4 * err);
  std::array<double, 3> mo = s.moments;
  std::sort(mo.begin(), mo.end());
  EXPECT_NEAR(mo[0] / ix - 1, 0, 5 * err);
  EXPECT_NEAR(mo[1] / iy - 1, 0, 5 * err);
  EXPECT_NEAR(mo[2] / iy - 1, 0, 5 * err);
  // The bounding radius about the Monte-Carlo centre (which is within its error, 3 um here, of xc).
  EXPECT_NEAR(s.r_bound, 3 * kR - templ(deck).centre_of_mass()[0] + kR / 2, 1e-8);  // the centre is off-axis by its MC error
  EXPECT_NEAR(templ(deck).centre_of_mass()[0], xc, 2e-5);
}

// mass + inertia_tensor + use_density: no Monte Carlo; principal moments are the
// tensor's eigenvalues, the volume M / rho, the spheres where given.
TEST(Multisphere, GivenMassAndInertiaAreExact) {
  Deck deck;
  deck(box() + tmpl({{{-kR, 0, 0, kR}}, {{kR, 0, 0, kR}}}, 1000,
                    " mass 1e-4 inertia_tensor 2e-10 0 0 5e-10 1e-10 5e-10 use_density"));
  const ClumpShape& s = templ(deck).shape();
  EXPECT_EQ(s.mass, 1e-4);
  EXPECT_DOUBLE_EQ(s.volume, 1e-4 / kRho);
  std::array<double, 3> m = s.moments;
  std::sort(m.begin(), m.end());
  EXPECT_NEAR(m[0], 2e-10, 1e-24);
  EXPECT_NEAR(m[1], 4e-10, 1e-24);
  EXPECT_NEAR(m[2], 6e-10, 1e-24);
  EXPECT_DOUBLE_EQ(s.r_bound, 2 * kR);
}

// An overlapping clump inserted with v = (0, 0, -1) falls freely: inserted
// after step 1's drift (as LIGGGHTS, in pre_exchange) and kicked by half a
// step at its end, it then falls for tau = 4999 steps: z = z0 + v1 tau - g
// tau^2 / 2 with v1 = -1 - g dt / 2 (velocity Verlet is exact for constant
// force; z0 within the 1 nm of the insertion region), with gravity M g on the
// body (not on each sphere, which carries the body's mass, nor the sum of
// sphere masses). Members keep their offsets.
TEST(Multisphere, InsertedClumpFallsFreely) {
  Deck deck;
  deck(box() + tmpl({{{0, 0, 0, kR}}, {{kR, 0, 0, kR}}, {{0, kR, 0, kR}}}, 100000) +
       insert_at(0, 0, 0.05, " vel constant 0 0 -1") + "run 5000");
  const auto& ms = *deck->find_fix_style<FixMultisphere>();
  ASSERT_EQ(ms.bodies().size(), 1u);
  ASSERT_EQ(deck->atoms.n, 3u);
  const double dt = 2e-6, tau = 4999 * dt, v1 = -1 - 0.5 * kG * dt;
  EXPECT_NEAR(ms.bodies()[0].xcm[2], 0.05 + v1 * tau - 0.5 * kG * tau * tau, 2e-9);
  EXPECT_NEAR(ms.bodies()[0].vcm[2], v1 - kG * tau, 1e-11);  // 5000 rounded kicks
  EXPECT_NEAR(deck->atoms.rmass[0], ms.bodies()[0].mass, 0);
  const auto& x = deck->atoms.x;
  EXPECT_NEAR(std::hypot(x[0] - x[3], x[1] - x[4], x[2] - x[5]), kR, 1e-15);
  EXPECT_NEAR(std::hypot(x[3] - x[6], x[4] - x[7], x[5] - x[8]), std::sqrt(2.0) * kR, 1e-15);
}

// A clump spun about a non-principal axis without contacts or gravity: angular
// momentum L = I w stays exactly (no torque) and 1/2 w.L (compute
// erotate/multisphere) within 1e-6 over 10^4 steps of the Richardson integrator;
// ke/multisphere is 1/2 M v^2.
TEST(Multisphere, FreeSpinConservesEnergy) {
  Deck deck;
  deck(box("") + tmpl({{{0, 0, 0, kR}}, {{1.5 * kR, 0, 0, kR}}, {{0, 1.2 * kR, 0, 0.8 * kR}}}, 100000) +
       insert_at(0, 0, 0.05, " vel constant 0.1 0 0 omega constant 30 -20 50 orientation random") +
       "compute er all erotate/multisphere\ncompute ke all ke/multisphere\nthermo_style custom step c_er c_ke\n"
       "run 1\nvariable e0 equal c_er\nvariable e0s equal ${e0}\nrun 10000\nvariable e1 equal c_er\n");
  const auto& b = deck->find_fix_style<FixMultisphere>()->bodies()[0];
  double e0, e1, ke;
  ASSERT_TRUE(deck->variables->numeric("e0s", e0));
  ASSERT_TRUE(deck->variables->numeric("e1", e1));
  deck("variable k equal c_ke");
  ASSERT_TRUE(deck->variables->numeric("k", ke));
  EXPECT_GT(e0, 0);
  EXPECT_NEAR(e1 / e0 - 1, 0, 1e-6);
  EXPECT_NEAR(ke, 0.5 * b.mass * 0.01, 1e-15 * b.mass);
  // thermo ke counts the body once, translation only, as LIGGGHTS 3.8 (its
  // multisphere tutorial with vel 0.3 0 0 omega 0 0 20: KinEng = ke/multisphere),
  // not its spheres, which carry the body's mass and spin about its centre.
  deck("variable tk equal ke");
  ASSERT_TRUE(deck->variables->numeric("tk", ke));
  EXPECT_NEAR(ke, 0.5 * b.mass * 0.01, 1e-15 * b.mass);
  // 1/2 w.L from the body state, the same energy.
  EXPECT_NEAR(0.5 * (b.omega[0] * b.angmom[0] + b.omega[1] * b.angmom[1] + b.omega[2] * b.angmom[2]) / e1, 1, 1e-12);
}

// A flat 3-sphere clump resting on a 30 degree incline at mu = 0.3 slides with
// a = g (sin - mu cos) = 2.3563 m/s^2 (Coulomb sliding of a rigid body, as
// fix rigid's test); centre-of-mass velocity between 0.02 and 0.05 s, 0.5 %.
TEST(Multisphere, ClumpSlidesDownIncline) {
  const double s30 = 0.5, c30 = std::sqrt(3.0) / 2, h = std::sqrt(3.0) * kR;
  // Spheres about their centroid, mass and inertia given (no Monte-Carlo
  // offset of the centre): m_s each, Ixx = Iyy = 3.2 m_s R^2, Izz = 5.2 m_s R^2.
  const double m1 = kRho * 4.0 / 3 * kPi * kR * kR * kR, i0 = m1 * kR * kR;
  Deck deck;
  deck(box("fix g all gravity 9.81 vector " + num(s30) + " 0 " + num(-c30) + "\n") +
       tmpl({{{-kR, -h / 3, 0, kR}}, {{kR, -h / 3, 0, kR}}, {{0, 2 * h / 3, 0, kR}}}, 1000,
            " mass " + num(3 * m1) + " inertia_tensor " + num(3.2 * i0) + " 0 0 " + num(3.2 * i0) + " 0 " +
                num(5.2 * i0) + " use_density") +
       insert_at(0, 0, kR) + "run 10000");
  const auto& ms = *deck->find_fix_style<FixMultisphere>();
  const double v1 = ms.bodies()[0].vcm[0];
  deck("run 15000");
  const double a = (ms.bodies()[0].vcm[0] - v1) / (15000 * 2e-6);
  EXPECT_NEAR(a / (kG * (s30 - 0.3 * c30)) - 1, 0, 0.005);
}

// insert/pack counts a clump once (by its centre of mass), not per sphere:
// particles_in_region 3 with clumps of 3 spheres inserts 3 clumps, then none.
TEST(Multisphere, InsertPackCountsClumpsOnce) {
  Deck deck;
  deck(box() + tmpl({{{0, 0, 0, kR}}, {{kR, 0, 0, kR}}, {{0, kR, 0, kR}}}, 100000) +
       "region ins block 0 0.1 -0.04 0.04 0.02 0.08 units box\nfix ms all multisphere\n"
       "fix ins all insert/pack seed 32452843 distributiontemplate pdd insert_every 100 overlapcheck yes "
       "orientation random region ins particles_in_region 3\nrun 300");
  EXPECT_EQ(deck->find_fix_style<FixMultisphere>()->bodies().size(), 3u);
  EXPECT_EQ(deck->atoms.n, 9u);
}

// A clump bouncing on the floor, split by write_restart / read_restart, continues bit for bit.
TEST(Multisphere, RestartContinuesBitIdentically) {
  sable::test::TempDir tmp;
  const std::string setup = box() + tmpl({{{0, 0, 0, kR}}, {{kR, 0, 0, kR}}, {{0, kR, 0, kR}}}, 100000) +
                            insert_at(0, 0, 0.004, " vel constant 0.1 0 -0.5 orientation random");
  Deck whole;
  whole(setup + "run 3000\nrun 3000");
  Deck first;
  first(setup + "run 3000\nwrite_restart " + tmp / "r.bin");
  Deck second;
  second("read_restart " + tmp / "r.bin" + "\n" + box().substr(box().find("neighbor")) +
         tmpl({{{0, 0, 0, kR}}, {{kR, 0, 0, kR}}, {{0, kR, 0, kR}}}, 100000) +
         insert_at(0, 0, 0.004, " vel constant 0.1 0 -0.5 orientation random") + "run 3000");
  ASSERT_EQ(second->atoms.n, 3u);
  for (long id = 1; id <= 3; ++id) {
    const std::size_t a = whole->atoms.index_of(id), b = second->atoms.index_of(id);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(whole->atoms.x[3 * a + k], second->atoms.x[3 * b + k]);
      EXPECT_EQ(whole->atoms.v[3 * a + k], second->atoms.v[3 * b + k]);
      EXPECT_EQ(whole->atoms.omega[3 * a + k], second->atoms.omega[3 * b + k]);
    }
  }
}

// The body computes read fix multisphere whenever evaluated (Compute::ready):
// before the first run (no body yet) their energies are 0, and after the fix is
// unfixed a clear error names the compute. A fuzz mutant (print "$(c_ke)"
// before any run) crashed: the compute had not looked its fix up yet.
TEST(Multisphere, EnergyComputesBetweenRuns) {
  const std::string scene = box("") + tmpl({{{0, 0, 0, kR}}, {{kR, 0, 0, kR}}}, 1000) + insert_at(0, 0, 0.05) +
                            "compute er all erotate/multisphere\ncompute ke all ke/multisphere\n";
  Deck d;
  d(scene + "variable k equal c_ke+c_er\n");
  double k = -1;
  ASSERT_TRUE(d->variables->numeric("k", k));
  EXPECT_EQ(k, 0.0);
  Deck e;
  EXPECT_NE(error_of(e, scene + "run 1\nunfix ins\nunfix ms\nprint \"$(c_ke)\"\n").find("needs a fix multisphere"),
            std::string::npos);
}

TEST(Multisphere, BadInput) {
  Deck d1;
  EXPECT_NE(error_of(d1, box() + tmpl({{{0, 0, 0, kR}}, {{kR, 0, 0, kR}}}, 1000, " mass 1e-4")).find(
                "both 'mass' and 'inertia_tensor'"),
            std::string::npos);
  Deck d2;
  EXPECT_NE(error_of(d2, box() + "fix pt all particletemplate/multisphere 15485863 density constant 2500 nspheres 2 "
                               "ntry 1000 spheres file nowhere.txt scale 1 type 1")
                .find("cannot open"),
            std::string::npos);
  Deck d3;
  EXPECT_NE(error_of(d3, box() + tmpl({{{0, 0, 0, kR}}, {{kR, 0, 0, kR}}}, 100000) +
                             "region ins block 0 0.01 0 0.01 0.02 0.03 units box\n"
                             "fix ins all insert/pack seed 32452843 distributiontemplate pdd insert_every once "
                             "region ins particles_in_region 1\nrun 1")
                .find("define a fix multisphere"),
            std::string::npos);
}

}  // namespace test_multisphere
