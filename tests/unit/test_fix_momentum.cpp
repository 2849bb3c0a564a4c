// fix momentum (LAMMPS/LIGGGHTS): the group's centre-of-mass velocity removed
// along the flagged axes every N steps; rescale keeps the kinetic energy.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_fix_momentum {

using sable::test::Deck;
using sable::test::error_of;

namespace {

// Three free grains of different masses (no pair style: nothing touches), moving.
void three(Deck& d, const std::string& fix) {
  d(R"(units si
atom_style granular
atom_modify map array
region box block -10 10 -10 10 -10 10 units box
create_box 1 box
create_atoms 1 single 0 0 0 units box
create_atoms 1 single 1 0 0 units box
create_atoms 1 single 0 1 0 units box
set atom 1 diameter 0.1 density 1000 vx 1 vy 2 vz 3
set atom 2 diameter 0.2 density 1000 vx -1 vy 0.5 vz 0
set atom 3 diameter 0.1 density 3000 vx 0 vy -1 vz 1
fix i all nve/sphere
)" + fix + "\nrun 10\n");
}

double momentum(Deck& d, int k) {
  double p = 0;
  for (std::size_t i = 0; i < d->atoms.n; ++i) p += d->atoms.rmass[i] * d->atoms.v[3 * i + k];
  return p;
}
double kinetic(Deck& d) {
  double e = 0;
  for (std::size_t i = 0; i < 3 * d->atoms.n; ++i) e += d->atoms.rmass[i / 3] * d->atoms.v[i] * d->atoms.v[i];
  return 0.5 * e;
}

}  // namespace

// linear 1 1 0 (the ParScale tutorial's): x and y momentum zero (round-off), z untouched.
TEST(FixMomentum, RemovesTheFlaggedComponents) {
  Deck ref;
  three(ref, "");
  Deck d;
  three(d, "fix mom all momentum 1 linear 1 1 0");
  const double scale = std::fabs(momentum(ref, 0)) + std::fabs(momentum(ref, 1)) + std::fabs(momentum(ref, 2));
  EXPECT_NEAR(momentum(d, 0), 0.0, 1e-15 * scale);
  EXPECT_NEAR(momentum(d, 1), 0.0, 1e-15 * scale);
  EXPECT_DOUBLE_EQ(momentum(d, 2), momentum(ref, 2));
  EXPECT_LT(kinetic(d), kinetic(ref));
}

// rescale: momentum gone, kinetic energy as before (round-off).
TEST(FixMomentum, RescaleKeepsTheKineticEnergy) {
  Deck ref;
  three(ref, "");
  Deck d;
  three(d, "fix mom all momentum 5 rescale");
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(momentum(d, k), 0.0, 1e-14);
  EXPECT_NEAR(kinetic(d), kinetic(ref), 1e-13 * kinetic(ref));
}

TEST(FixMomentum, Errors) {
  Deck a, b, c;
  EXPECT_NE(error_of(a, "fix m all momentum 0\n").find("a period N >= 1"), std::string::npos);
  EXPECT_NE(error_of(b, "fix m all momentum 1 angular\n").find("does not remove the angular momentum"), std::string::npos);
  EXPECT_NE(error_of(c, "fix m all momentum 1 linear 1 2 0\n").find("a flag 0 or 1"), std::string::npos);
}

}  // namespace test_fix_momentum
