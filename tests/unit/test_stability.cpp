// The setup-time step check: Rayleigh and Hertz bounds stop an unsafe run
// (naming the timestep line) unless the deck accepts it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/engine/error.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_stability {

using sable::test::Deck;
using sable::test::printed;

namespace {
std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}
// Two grains 2 mm across about to collide at +-v; E and dt from the caller.
std::string deck(double E, double v, double dt, bool accept) {
  std::string s = R"D(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype )D" +
                  num(E) + R"D(
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
create_atoms 1 single -0.0011 0 0 units box
create_atoms 1 single 0.0011 0 0 units box
set atom 1 diameter 0.002 density 2500 vx )D" +
                  num(v) + "\nset atom 2 diameter 0.002 density 2500 vx -" + num(v) +
                  "\ntimestep " + num(dt) + "\nfix i all nve/sphere\n";
  if (accept) s += "timestep_check accept\n";
  return s + "run 10\n";
}
}  // namespace

TEST(Stability, RayleighBoundStopsAndNamesTheTimestepLine) {
  // E = 1.5 GPa, r = 1 mm, rho = 2500: t_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766) = 7.066e-6 s.
  Deck d;
  try {
    d(deck(1.5e9, 0.1, 1e-5, false));
    FAIL() << "an unsafe step must stop the run";
  } catch (const sable::SableError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("test:17: 'timestep 1e-05' exceeds 20% of the Rayleigh time"), std::string::npos) << m;
    EXPECT_NE(m.find("7.06595e-06"), std::string::npos) << m;  // the bound itself (hand value 7.066e-6)
    EXPECT_NE(m.find("timestep_check accept"), std::string::npos) << m;  // how to override
  }
  EXPECT_EQ(d->step, 0);
}

TEST(Stability, HertzBoundCatchesFastImpacts) {
  // Soft grains (E = 1e7 Pa) meeting at +-20 m/s: the Rayleigh time 8.65e-5 s is fine for
  // dt = 1.2e-5 (13.9 %), but the Hertz time at v_rel = 40 m/s,
  // 2.87 (m*^2 / (R* Y*^2 v))^(1/5) = 9.75e-5 s, is not (dt is 12.3 % of it, limit 10 %).
  Deck d;
  try {
    d(deck(1e7, 20.0, 1.2e-5, false));
    FAIL() << "a step above 10 % of the Hertz time must stop the run";
  } catch (const sable::SableError& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds 10% of the contact (Hertz) time"), std::string::npos) << e.what();
  }
}

TEST(Stability, AcceptRunsWithAWarning) {
  Deck d;
  const std::string out = printed(deck(1.5e9, 0.1, 1e-5, true), d);
  EXPECT_NE(out.find("WARNING: test:17: 'timestep 1e-05' exceeds 20% of the Rayleigh time"), std::string::npos) << out;
  EXPECT_NE(out.find("accepted because of 'timestep_check accept'"), std::string::npos) << out;
  EXPECT_EQ(d->step, 10);
}

TEST(Stability, SafeStepPrintsTheBounds) {
  Deck d;
  const std::string out = printed(deck(1e8, 1.0, 1e-7, false), d);
  EXPECT_NE(out.find("Time-step check: dt = 1e-07 s is"), std::string::npos) << out;
  EXPECT_EQ(out.find("WARNING"), std::string::npos) << out;
  EXPECT_EQ(d->step, 10);
}

}  // namespace test_stability
