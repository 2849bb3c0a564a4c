// fix freeze, fix enforce2d, fix viscous.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/engine/error.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_fixes_simple {

using sable::test::Deck;
using sable::test::error_of;

namespace {

const char* kTwoGrains = R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 2 box
create_atoms 1 single 0.5 0.5 0.5 units box
create_atoms 1 single 0.2 0.5 0.5 units box
set atom * diameter 0.01 density 2500
group frozen id 1
timestep 1e-4
)";

}  // namespace

// A frozen grain under gravity does not move at all (exact: its force is zeroed before
// each kick); the free one falls as z0 - g t^2/2 (round-off, 1e-12 m). f_ID[3] is the
// force removed from the frozen group, -m g (1e-12 relative).
TEST(FixFreeze, FrozenGrainStaysPutUnderGravity) {
  Deck d;
  d(std::string(kTwoGrains) + R"(fix g all gravity 9.81 vector 0 0 -1
fix fr frozen freeze
fix i all nve/sphere
run 1000)");
  const auto& a = d->atoms;
  const std::size_t f = a.index_of(1), m = a.index_of(2);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.x[3 * f + k], 0.5);
    EXPECT_EQ(a.v[3 * f + k], 0.0);
    EXPECT_EQ(a.omega[3 * f + k], 0.0);
  }
  EXPECT_NEAR(a.x[3 * m + 2], 0.5 - 0.5 * 9.81 * 0.01, 1e-12);
  const double mg = a.rmass[f] * 9.81;
  EXPECT_NEAR(d->find_fix("fr")->compute_vector(3), -mg, 1e-12 * mg);
}

// LIGGGHTS runs post-force fixes in definition order: gravity defined after freeze still
// pulls the frozen grain (as liggghts does); sable warns about it.
TEST(FixFreeze, GravityDefinedAfterFreezeStillActsAndIsWarnedAbout) {
  Deck d;
  const std::string out = sable::test::printed(std::string(kTwoGrains) + R"(fix fr frozen freeze
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
run 10)",
                                               d);
  EXPECT_NE(out.find("adds force to frozen grains"), std::string::npos) << out;
  EXPECT_LT(d->atoms.x[3 * d->atoms.index_of(1) + 2], 0.5);
}

// Velocities are left alone (LIGGGHTS zeroes force and torque only): a moving frozen grain drifts, with a warning.
TEST(FixFreeze, KeepsVelocityLikeLiggghtsAndWarns) {
  Deck d;
  const std::string out = sable::test::printed(std::string(kTwoGrains) + R"(set atom 1 vx 1
fix g all gravity 9.81 vector 0 0 -1
fix fr frozen freeze
fix i all nve/sphere
run 10)",
                                               d);
  EXPECT_NE(out.find("keep it"), std::string::npos) << out;
  const std::size_t f = d->atoms.index_of(1);
  EXPECT_NEAR(d->atoms.x[3 * f], 0.5 + 10 * 1e-4, 1e-12);
  EXPECT_EQ(d->atoms.x[3 * f + 2], 0.5);
}

TEST(FixFreeze, OnlyOneAllowed) {
  Deck d;
  d(std::string(kTwoGrains) + "fix a frozen freeze\nfix b all freeze\nfix i all nve/sphere");
  EXPECT_NE(error_of(d, "run 1").find("more than one fix freeze"), std::string::npos);
  EXPECT_NE(error_of(d, "fix c all freeze now").find("nothing after 'freeze'"), std::string::npos);
}

// enforce2d: z, v_z, omega_x, omega_y stay exactly 0 although the initial state and
// gravity have out-of-plane parts; in-plane motion is untouched (round-off, 1e-12).
TEST(FixEnforce2d, KeepsGrainsInThePlane) {
  Deck d;
  d(R"(units si
atom_style granular
dimension 2
boundary f f p
region box block 0 1 0 1 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0 units box
set atom 1 diameter 0.01 density 2500 vx 1 vz 5 omegax 3 omegay 4 omegaz 2
fix g all gravity 9.81 vector 0 -1 -1
fix i all nve/sphere
fix e all enforce2d
timestep 1e-4
run 100)");
  const auto& a = d->atoms;
  EXPECT_EQ(a.x[2], 0.0);
  EXPECT_EQ(a.v[2], 0.0);
  EXPECT_EQ(a.omega[0], 0.0);
  EXPECT_EQ(a.omega[1], 0.0);
  EXPECT_EQ(a.omega[2], 2.0);
  EXPECT_NEAR(a.x[0], 0.5 + 0.01, 1e-12);
  EXPECT_NEAR(a.x[1], 0.5 - 0.5 * 9.81 / std::sqrt(2.0) * 0.01 * 0.01, 1e-12);
}

TEST(FixEnforce2d, MustBeLastAnd2D) {
  Deck d;
  const std::string out = sable::test::printed(R"(units si
atom_style granular
dimension 2
region box block 0 1 0 1 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0 units box
fix e all enforce2d
fix g all gravity 9.81 vector 0 -1 0
fix i all nve/sphere
run 1)",
                                               d);
  EXPECT_NE(out.find("define fix enforce2d last"), std::string::npos) << out;
  Deck d3;
  d3("units si\natom_style granular\nregion box block 0 1 0 1 0 1 units box\ncreate_box 1 box");
  EXPECT_NE(error_of(d3, "fix e all enforce2d").find("a 2D simulation"), std::string::npos);
}

// F = -gamma v. Velocity Verlet with a velocity-dependent force gives exactly
// v_N = v0 (1 - e/2)^2 (1 - e)^(N-1), e = gamma dt / m (checked to 1e-10, round-off over
// N steps). Against v0 exp(-gamma t / m) its relative error is about (gamma t/m) e / 2
// = 0.5 * 2e-6 / 2 = 5e-7 here, inside the required 1e-6.
TEST(FixViscous, ExponentialDecayOfVelocity) {
  Deck d;
  d(R"(units si
atom_style granular
region box block -1 1 -1 3 -1 1 units box
create_box 2 box
neighbor 2 bin
create_atoms 1 single 0 0 0 units box
create_atoms 2 single 0.5 0 0 units box
set atom * diameter 0.01 density 1000 vy 0.5
timestep 1e-5)");
  const double m = d->atoms.rmass[0], eps = 2e-6, gamma = eps * m / 1e-5;
  char line[200];
  std::snprintf(line, sizeof line, "fix v all viscous %.17g scale 2 2\nfix i all nve/sphere\nrun 250000", gamma);
  d(line);
  const double t = 2.5, v0 = 0.5;
  const std::size_t i1 = d->atoms.index_of(1), i2 = d->atoms.index_of(2);
  const double v = d->atoms.v[3 * i1 + 1];
  const double discrete = v0 * std::pow(1 - eps / 2, 2) * std::pow(1 - eps, 249999);
  EXPECT_NEAR(v, discrete, 1e-10 * discrete);
  const double exact = v0 * std::exp(-gamma * t / m);
  EXPECT_NEAR(v, exact, 1e-6 * exact);
  // scale 2 2: type 2 is damped twice as hard
  const double exact2 = v0 * std::exp(-2 * gamma * t / m);
  EXPECT_NEAR(d->atoms.v[3 * i2 + 1], exact2, 3e-6 * exact2);
}

TEST(FixViscous, Errors) {
  Deck d;
  d("units si\natom_style granular\nregion box block 0 1 0 1 0 1 units box\ncreate_box 1 box");
  EXPECT_NE(error_of(d, "fix v all viscous fast").find("(a number)"), std::string::npos);
  EXPECT_NE(error_of(d, "fix v all viscous 0.1 scale 3 2").find("between 1 and 1"), std::string::npos);
  EXPECT_NE(error_of(d, "fix v all viscous 0.1 damp 3 2").find("'scale type ratio'"), std::string::npos);
}

}  // namespace test_fixes_simple
