// cohesion sjkr / sjkr2 (contact_models/cohesion/sjkr.h, sjkr2.h) against
// their definitions (LIGGGHTS gran_cohesion_sjkr.txt, gran_cohesion_sjkr2.txt):
// a pull F = k A, k = cohesionEnergyDensity, A the contact area.
//  * Frozen contacts: the force with cohesion minus the force without it is
//    k A along -en, with A from geometry written out here (the intersection
//    circle of two spheres, a^2 = ri^2 - x^2 with x the distance from i's
//    centre to the plane of intersection; a wall's cut circle ri^2 - d^2), to
//    round-off (1e-9 of k A: the Hertz part cancels in the difference).
//  * tangential_reduce: the Coulomb cap mu |Fn| of a sliding grain uses Fn
//    without the pull (off, the default) or with it (on).
//  * Undamped head-on collisions (e = 1): Hertz spring and pull depend on the
//    overlap only, so the collision is elastic and the largest overlap solves
//    (1/2) m* v^2 = int_0^dmax (4/3 Y* sqrt(R*) d^(3/2) - k A(d)) dd
//    (integrated here with Simpson's rule). Tolerances: 1e-3 on dmax and 1e-4
//    on the rebound speed, the time step error at dt = contact time / ~2000.
//  * Damped (e = 0.5): a slow collision sticks with cohesion, rebounds without.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "core/input/style_registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_cohesion_sjkr {

using sable::test::Deck;

namespace {

constexpr double kPi = std::numbers::pi;

const char* kHead = R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 2 box
neighbor 0.0005 bin
timestep 1e-6
fix m1 all property/global youngsModulus peratomtype 5e6 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3 0.4
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.4 0.4 0.3
fix m5 all property/global cohesionEnergyDensity peratomtypepair 2 2e5 3e5 3e5 5e5
)";
const double kK12 = 3e5, kK11 = 2e5;

// x component of the force on atom `id` after `run 1` without an integrator.
double fx_after_setup(Deck& d, long id) {
  d("run 1");
  return d->atoms.f[3 * d->atoms.index_of(id)];
}

// Two frozen grains along x, radii 1 mm (type 1) and 1.5 mm (type 2), overlap dn.
double pair_fx(const std::string& cohesion, double dn) {
  Deck d;
  d(kHead);
  d("create_atoms 1 single 0 0 0 units box");
  d("create_atoms 2 single " + std::to_string(0.0025 - dn) + " 0 0 units box");
  d("set atom 1 diameter 0.002 density 2500");
  d("set atom 2 diameter 0.003 density 2500");
  d("pair_style gran model hertz tangential history" + (cohesion.empty() ? "" : " cohesion " + cohesion));
  d("pair_coeff * *");
  return fx_after_setup(d, 1);
}

TEST(CohesionSjkr, PairPullIsEnergyDensityTimesContactArea) {
  const double ri = 0.001, rj = 0.0015;
  for (double dn : {2e-6, 5e-5, 3e-4}) {
    const double r = std::stod(std::to_string(0.0025 - dn));  // the deck's centre distance
    const double d = ri + rj - r;
    const double x = (r * r + ri * ri - rj * rj) / (2 * r);  // centre i to the intersection plane
    const double circle = kPi * (ri * ri - x * x);
    const double cap = 2 * kPi * (2 * ri * rj / (ri + rj)) * d;
    const double base = pair_fx("", dn);
    // Grain 1 is left of grain 2: en = -x, so the pull on 1 is +x.
    EXPECT_NEAR(pair_fx("sjkr", dn) - base, kK12 * circle, 1e-9 * kK12 * circle) << "dn " << dn;
    EXPECT_NEAR(pair_fx("sjkr2", dn) - base, kK12 * cap, 1e-9 * kK12 * cap) << "dn " << dn;
  }
}

// A grain of radius 1 mm over a zplane, gap below its centre, the wall
// sliding at `slide` along x; `tail`: keywords after the primitive. Returns (fx, fz).
std::pair<double, double> wall_force(const std::string& cohesion, double gap, double slide = 0.0,
                                     const std::string& tail = "") {
  Deck d;
  d(kHead);
  d("create_atoms 1 single 0 0 0 units box");
  d("set atom 1 diameter 0.002 density 2500");
  d("pair_style gran model hertz tangential no_history");
  d("pair_coeff * *");
  d("fix w all wall/gran model hertz tangential no_history " + cohesion + " primitive type 1 zplane " +
    std::to_string(-gap) + (slide != 0 ? " shear x " + std::to_string(slide) : std::string()) + " " + tail);
  d("run 1");
  return {d->atoms.f[0], d->atoms.f[2]};
}

TEST(CohesionSjkr, WallPullIsEnergyDensityTimesContactArea) {
  const double ri = 0.001;
  for (double gap : {0.00099, 0.0009}) {
    const double g = std::stod(std::to_string(gap));
    const double circle = kPi * (ri * ri - g * g), cap = 2 * kPi * ri * (ri - g);
    const double base = wall_force("", gap).second;
    EXPECT_NEAR(wall_force("cohesion sjkr", gap).second - base, -kK11 * circle, 1e-9 * kK11 * circle);
    EXPECT_NEAR(wall_force("cohesion sjkr2", gap).second - base, -kK11 * cap, 1e-9 * kK11 * cap);
  }
}

TEST(CohesionSjkr, CoulombCapSeesThePullOnlyWithTangentialReduce) {
  const double ri = 0.001, gap = 0.0008, mu = 0.5;
  const double g = std::stod(std::to_string(gap));
  const double pull = kK11 * kPi * (ri * ri - g * g);
  // Sliding at 20 m/s: the viscous tangential force is far above the cap, so |Ft| = mu |Fn|.
  const auto dry = wall_force("", gap, 20.0);
  const auto off = wall_force("cohesion sjkr", gap, 20.0);
  const auto on = wall_force("cohesion sjkr", gap, 20.0, "tangential_reduce on");
  const double fn = dry.second;  // the Hertz force alone (vn = 0: no damping)
  ASSERT_GT(fn, pull);           // the pull does not open the contact
  EXPECT_NEAR(std::fabs(dry.first), mu * fn, 1e-12 * fn);
  EXPECT_NEAR(std::fabs(off.first), mu * fn, 1e-12 * fn);          // default: cap from Fn alone
  EXPECT_NEAR(std::fabs(on.first), mu * (fn - pull), 1e-9 * fn);   // on: cap from Fn - k A
  EXPECT_NEAR(on.second, off.second, 1e-12 * fn);                   // the normal force is the same
  EXPECT_NEAR(off.second, fn - pull, 1e-9 * fn);
}

// --- collisions ---------------------------------------------------------------

std::function<void(sable::Simulation&)> g_probe;
class FixProbeSjkr : public sable::Fix {
 public:
  FixProbeSjkr(sable::Simulation& s, const sable::Args& a) : Fix(s, a) { hooks = sable::END_OF_STEP; }
  void end_of_step() override {
    if (g_probe) g_probe(sim);
  }
};
SABLE_FIX("test/probe_sjkr", FixProbeSjkr);

constexpr double kR = 0.001, kRho = 2500, kY = 5e7, kNu = 0.3, kDt = 2e-8;

struct Outcome {
  double dmax, vout, final_gap;
};

// Equal grains (type 1) head-on at relative speed v; e = coefficientRestitution.
Outcome head_on(const std::string& cohesion, double v, double e, double k, double t_end) {
  Deck d;
  char mat[1024];  // the fixed text is ~470 characters, each %.17g up to 24
  std::snprintf(mat, sizeof mat, R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
timestep %.17g
fix m1 all property/global youngsModulus peratomtype %.17g
fix m2 all property/global poissonsRatio peratomtype %.17g
fix m3 all property/global coefficientRestitution peratomtypepair 1 %.17g
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global cohesionEnergyDensity peratomtypepair 1 %.17g
)",
                kDt, kY, kNu, e, k);
  d(mat);
  d("pair_style gran model hertz tangential history" + (cohesion.empty() ? "" : " cohesion " + cohesion));
  d("pair_coeff * *");
  d("create_atoms 1 single -0.00101 0 0 units box");
  d("create_atoms 1 single 0.00101 0 0 units box");
  for (long id : {1, 2}) {
    const std::size_t i = d->atoms.index_of(id);
    d->atoms.set_radius_density(i, kR, kRho);
    d->atoms.v[3 * i] = d->atoms.x[3 * i] < 0 ? v / 2 : -v / 2;
  }
  d("fix i all nve/sphere");
  d("fix p all test/probe_sjkr");
  double dmax = 0;
  g_probe = [&](sable::Simulation& s) { dmax = std::max(dmax, 2 * kR - std::fabs(s.atoms.x[3] - s.atoms.x[0])); };
  d("run " + std::to_string(static_cast<long>(t_end / kDt)));
  g_probe = nullptr;
  const auto& at = d->atoms;
  return {dmax, std::fabs(at.v[3] - at.v[0]), std::fabs(at.x[3] - at.x[0]) - 2 * kR};
}

// Largest overlap of the undamped collision from the energy balance.
double energy_balance_dmax(double v, double k, const std::function<double(double)>& area) {
  const double m = 4.0 / 3.0 * kPi * kR * kR * kR * kRho, meff = m / 2, reff = kR / 2;
  const double ys = kY / (2 * (1 - kNu * kNu));
  auto force = [&](double dd) { return 4.0 / 3.0 * ys * std::sqrt(reff) * std::pow(dd, 1.5) - k * area(dd); };
  auto work = [&](double dm) {  // Simpson, 2000 intervals
    const int n = 2000;
    double s = force(0) + force(dm);
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * force(dm * i / n);
    return s * dm / (3 * n);
  };
  const double ke = 0.5 * meff * v * v;
  double lo = 0, hi = kR;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (work(mid) < ke ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(CohesionSjkr, UndampedHeadOnOverlapFromEnergyBalance) {
  const double v = 0.5, k = 1e5;
  auto circle = [](double dd) {  // equal spheres: the plane halves the overlap
    const double x = kR - dd / 2;
    return kPi * (kR * kR - x * x);
  };
  auto cap = [](double dd) { return 2 * kPi * kR * dd; };  // 2 pi (2 R*) dn, R* = R/2
  for (const auto& [name, area] : {std::pair<std::string, std::function<double(double)>>{"sjkr", circle},
                                   {"sjkr2", cap}}) {
    const double want = energy_balance_dmax(v, k, area);
    const double plain = energy_balance_dmax(v, 0, area);
    const Outcome o = head_on(name, v, 1.0, k, 0.0003);
    std::printf("%s undamped v %g: dmax %.6g (energy balance %.6g, without pull %.6g), rebound %.6f v\n",
                name.c_str(), v, o.dmax, want, plain, o.vout / v);
    EXPECT_NEAR(o.dmax, want, 1e-3 * want) << name;
    EXPECT_GT(o.dmax - plain, 20e-3 * plain) << name;  // the pull deepens the contact visibly
    EXPECT_NEAR(o.vout, v, 1e-4 * v) << name;
    EXPECT_GT(o.final_gap, 0) << name;
  }
}

TEST(CohesionSjkr, DampedSlowCollisionSticksOnlyWithCohesion) {
  const double v = 0.02, k = 1e6;
  const Outcome dry = head_on("", v, 0.5, k, 0.003);
  const Outcome stuck = head_on("sjkr", v, 0.5, k, 0.003);
  const Outcome stuck2 = head_on("sjkr2", v, 0.5, k, 0.003);
  std::printf("e 0.5 v %g: final gap dry %.3g, sjkr %.3g, sjkr2 %.3g m; speeds %.3g %.3g %.3g\n", v, dry.final_gap,
              stuck.final_gap, stuck2.final_gap, dry.vout, stuck.vout, stuck2.vout);
  EXPECT_GT(dry.final_gap, 0);
  EXPECT_LT(stuck.final_gap, 0);  // still overlapping
  EXPECT_LT(stuck2.final_gap, 0);
  EXPECT_LT(stuck.vout, 0.05 * v);  // and nearly at rest relative to each other
  EXPECT_LT(stuck2.vout, 0.05 * v);
}

}  // namespace

}  // namespace test_cohesion_sjkr
