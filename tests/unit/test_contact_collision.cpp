// Head-on binary collisions (and a sphere hitting a plane) against analytic
// contact mechanics.
//
// Restitution. LIGGGHTS' coefficientRestitution may be 1 (0.05 < e <= 1,
// global_properties.cpp): ln e = 0 gives beta = 0 for hertz and gamman = 0 for
// hooke, i.e. purely elastic contacts, so the undamped Hertz duration is
// tested with e = 1 honestly, with the same deck a LIGGGHTS user would write.
// For e < 1 both damping laws give exactly e when the collision is measured
// from touch to separation (overlap back to zero): Hooke's gamman is the
// critical-damping fraction of a linear oscillator with restitution e, and
// Hertz's -2 sqrt(5/6) beta sqrt(Sn m*) is Tsuji's damping, whose restitution
// is velocity independent and equal to e (checked by integrating
// m x'' = -kn(x) x - gn(x) x' with RK4 while writing this test: 0.9000001 for e = 0.9,
// 0.5000003 for e = 0.5). The residual of a run is the time-step error of
// velocity Verlet at dt = t_c / ~1000, so the tolerance is 1 % as asked, and
// the measured values are in fact within 1e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include "core/input/style_registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_collision {

using sable::test::Deck;

namespace {

constexpr double kPi = std::numbers::pi;

std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

// A fix that hands the simulation to a callback at the end of every step.
std::function<void(sable::Simulation&)> g_probe;
class FixProbe : public sable::Fix {
 public:
  FixProbe(sable::Simulation& s, const sable::Args& a) : Fix(s, a) { hooks = sable::END_OF_STEP; }
  void end_of_step() override {
    if (g_probe) g_probe(sim);
  }
};
SABLE_FIX("test/probe_collision", FixProbe);

struct Collision {
  double duration = 0;     // touch to separation, interpolated on the overlap crossing zero
  double restitution = 0;  // |relative normal velocity after| / before
};

// Two grains of radius r approach along x at +-v/2 (or one grain at -v onto a plane x = 0).
Collision collide(const std::string& model, double e, double v, bool wall, double dt) {
  const double r = 0.001, rho = 2500;
  Deck d;
  d(R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global characteristicVelocity scalar 2.0)");
  d("fix m3 all property/global coefficientRestitution peratomtypepair 1 " + num(e));
  d("pair_style gran model " + model + " tangential history");
  d("pair_coeff * *");
  d("timestep " + num(dt));
  if (wall) {
    d("create_atoms 1 single 0.0011 0 0 units box");
    d("fix w all wall/gran model " + model + " tangential history primitive type 1 xplane 0.0");
  } else {
    d("create_atoms 1 single -0.0011 0 0 units box");
    d("create_atoms 1 single 0.0011 0 0 units box");
  }
  d("fix i all nve/sphere");
  d("fix p all test/probe_collision");
  auto& at = d->atoms;
  for (std::size_t i = 0; i < at.n; ++i) {
    at.set_radius_density(i, r, rho);
    at.v[3 * i] = wall ? -v : (at.x[3 * i] < 0 ? v / 2 : -v / 2);
  }
  auto overlap = [&](sable::Simulation& s) {
    const auto& a = s.atoms;
    return wall ? r - a.x[0] : 2 * r - std::fabs(a.x[3] - a.x[0]);
  };
  double prev = overlap(*d), t_in = -1, t_out = -1;
  g_probe = [&](sable::Simulation& s) {
    const double o = overlap(s);
    if (prev <= 0 && o > 0 && t_in < 0) t_in = s.time - dt * o / (o - prev);
    if (prev > 0 && o <= 0 && t_in >= 0 && t_out < 0) t_out = s.time - dt * o / (o - prev);
    prev = o;
  };
  d("run " + std::to_string(static_cast<long>((0.0003 / v + 0.0003) / dt)));
  g_probe = nullptr;
  Collision c;
  c.duration = t_out - t_in;
  const double vx_after = wall ? at.v[0] : std::fabs(at.v[3] - at.v[0]);
  c.restitution = std::fabs(vx_after) / v;
  return c;
}

// Hertz theory for F = 4/3 Y* sqrt(R*) dn^(3/2): t_c = 2 I dmax / v, with
// dmax = (15 m* v^2 / (16 Y* sqrt(R*)))^(2/5) and I = int_0^1 dx / sqrt(1 - x^(5/2))
// = (2/5) B(2/5, 1/2) = 1.47164 (e.g. Johnson, Contact Mechanics, sec. 11.4).
// This equals 2.868 (m*^2 / (R* Y*^2 v))^(1/5); LIGGGHTS' check uses 2.87.
double hertz_time(double meff, double reff, double ystar, double v) {
  const double dmax = std::pow(15.0 * meff * v * v / (16.0 * ystar * std::sqrt(reff)), 0.4);
  return 2.0 * (0.4 * std::beta(0.4, 0.5)) * dmax / v;
}

const double kR = 0.001, kM = 4.0 / 3.0 * kPi * kR * kR * kR * 2500, kYstar = 5e7 / (2 * (1 - 0.09));

}  // namespace

TEST(HertzCollision, ElasticDurationMatchesHertzTheory) {
  const double v = 2.0;  // relative impact speed
  const Collision c = collide("hertz", 1.0, v, false, 1e-7);
  const double meff = kM / 2, reff = kR / 2;
  const double t_exact = hertz_time(meff, reff, kYstar, v);
  const double t_287 = 2.87 * std::pow(meff * meff / (reff * kYstar * kYstar * v), 0.2);
  std::printf("hertz e=1: duration %.6g s, Hertz theory %.6g s (2.87 form %.6g s), restitution %.7f\n", c.duration,
              t_exact, t_287, c.restitution);
  EXPECT_NEAR(c.duration, t_exact, 0.01 * t_exact);
  EXPECT_NEAR(c.duration, t_287, 0.01 * t_287);  // the form the brief and LIGGGHTS quote
  EXPECT_NEAR(c.restitution, 1.0, 1e-3);          // e = 1: no damping at all
  // Against the wall: R* = r, m* = m (infinite partner), duration from the same formula.
  const Collision w = collide("hertz", 1.0, 1.0, true, 1e-7);
  const double tw = hertz_time(kM, kR, kYstar, 1.0);
  EXPECT_NEAR(w.duration, tw, 0.01 * tw);
  EXPECT_NEAR(w.restitution, 1.0, 1e-3);
}

TEST(HertzCollision, RestitutionIsTheRequestedCoefficient) {
  for (double e : {0.9, 0.5}) {
    const Collision c = collide("hertz", e, 2.0, false, 1e-7);
    std::printf("hertz e=%.2f: pair %.6f\n", e, c.restitution);
    EXPECT_NEAR(c.restitution, e, 0.01 * e) << "pair, e = " << e;
    // Velocity independence (Tsuji damping): the same e at a quarter of the speed.
    const Collision slow = collide("hertz", e, 0.5, false, 1e-7);
    EXPECT_NEAR(slow.restitution, e, 0.01 * e) << "pair slow, e = " << e;
    // Wall version: wall type = grain type, so Y* is the same pairing of two equal materials.
    const Collision w = collide("hertz", e, 1.0, true, 1e-7);
    std::printf("hertz e=%.2f: pair at v/4 %.6f, wall %.6f\n", e, slow.restitution, w.restitution);
    EXPECT_NEAR(w.restitution, e, 0.01 * e) << "wall, e = " << e;
  }
}

TEST(HookeCollision, RestitutionAndDurationOfTheDampedOscillator) {
  for (double e : {1.0, 0.9, 0.5}) {
    const Collision c = collide("hooke", e, 2.0, false, 1e-7);
    EXPECT_NEAR(c.restitution, e, 0.01 * e) << "e = " << e;
    // LIGGGHTS hooke: kn = 16/15 sqrt(R*) Y* (15 m* V^2 / (16 sqrt(R*) Y*))^(1/5), V = characteristicVelocity,
    // gamman = sqrt(4 m* kn / (1 + (pi/ln e)^2)); duration pi / sqrt(kn/m* - (gamman/2m*)^2).
    const double meff = kM / 2, reff = kR / 2, V = 2.0;
    const double kn = 16.0 / 15.0 * std::sqrt(reff) * kYstar *
                      std::pow(15.0 * meff * V * V / (16.0 * std::sqrt(reff) * kYstar), 0.2);
    const double q = e < 1 ? kPi / std::log(e) : INFINITY;
    const double gn = std::sqrt(4 * meff * kn / (1 + q * q));
    const double tc = kPi / std::sqrt(kn / meff - gn * gn / (4 * meff * meff));
    EXPECT_NEAR(c.duration, tc, 0.01 * tc) << "e = " << e;
    std::printf("hooke e=%.2f: pair %.6f, duration %.6g s (theory %.6g s)\n", e, c.restitution, c.duration, tc);
    const Collision w = collide("hooke", e, 1.0, true, 1e-7);
    EXPECT_NEAR(w.restitution, e, 0.01 * e) << "wall, e = " << e;
  }
}

TEST(HertzCollision, ContactTimeUsedByTheStabilityCheck) {
  // Pair::contact_time is LIGGGHTS' 2.87 (m*^2/(R* Y*^2 v))^(1/5) for two equal grains.
  Deck d;
  d(R"(units si
atom_style granular
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
create_atoms 1 single 0 0 0 units box
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-7)");
  d->atoms.set_radius_density(0, kR, 2500);
  d("run 0");
  const double t = d->pair->contact_time(0, 0, 2.0);
  EXPECT_NEAR(t, 2.87 * std::pow((kM / 2) * (kM / 2) / ((kR / 2) * kYstar * kYstar * 2.0), 0.2), 1e-12 * t);
  // Rayleigh time pi r sqrt(rho/G) / (0.1631 nu + 0.8766), G = Y / (2 (1 + nu)).
  const double G = 5e7 / 2.6;
  EXPECT_NEAR(d->pair->rayleigh_time(0), kPi * kR * std::sqrt(2500 / G) / (0.1631 * 0.3 + 0.8766), 1e-15);
}

}  // namespace test_contact_collision
