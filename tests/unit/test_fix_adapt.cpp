// fix adapt N atom diameter v_name (LIGGGHTS/LAMMPS): when the diameters change
// (at the start of a run and every N steps), the masses that follow at constant
// density, scale/reset, and a fresh neighbour list for grown grains.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/engine/error.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_fix_adapt {

using sable::test::Deck;
using sable::test::error_of;

namespace {

const char* kMaterials = R"(fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
)";

const std::string kTwo = std::string(R"(units si
atom_style granular
atom_modify map array
region box block -0.1 0.1 -0.1 0.1 -0.1 0.1 units box
create_box 1 box
neighbor 0.001 bin
)") + kMaterials + R"(timestep 1e-6
create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0.0125 0 0 units box
set group all diameter 0.01 density 2500
fix i all nve/sphere
)";

double mass_of(double d, double rho) { return std::numbers::pi / 6.0 * d * d * d * rho; }

}  // namespace

// Equal-style: every grain gets the variable's value at the last change (step 50,
// a multiple of N = 10), and the mass follows at density 2500 (round-off only).
TEST(FixAdapt, EqualStyleDiameterAndMass) {
  Deck d;
  d(kTwo + "variable s equal 0.004+0.0001*step\nfix a all adapt 10 atom diameter v_s\nrun 55\n");
  const sable::Atoms& at = d->atoms;
  for (std::size_t i = 0; i < at.n; ++i) {
    EXPECT_DOUBLE_EQ(2.0 * at.radius[i], 0.004 + 0.0001 * 50);
    EXPECT_NEAR(at.rmass[i], mass_of(0.009, 2500), 1e-12 * at.rmass[i]);
  }
}

// Atom-style growth as in LIGGGHTS' packing tutorial: d_new = g * 2 r every N steps.
// Changes happen at the run's start and at steps N, 2N, ...: 1 + 40/10 = 5 times.
TEST(FixAdapt, AtomStyleGrowthCountsTheRunStart) {
  Deck d;
  d(kTwo + "compute rad all property/atom radius\nvariable g atom 1.01*2*c_rad\n"
                        "fix a all adapt 10 atom diameter v_g\nrun 40\n");
  for (std::size_t i = 0; i < d->atoms.n; ++i) EXPECT_NEAR(2.0 * d->atoms.radius[i], 0.01 * std::pow(1.01, 5), 1e-15);
}

// scale yes multiplies the diameters of the run's start; reset yes restores them after the run.
TEST(FixAdapt, ScaleAndReset) {
  Deck d;
  d(kTwo + "variable f equal 0.5\nfix a all adapt 0 atom diameter v_f scale yes reset yes\nrun 5\n");
  // after the run: reset to 0.01 and its mass
  for (std::size_t i = 0; i < d->atoms.n; ++i) {
    EXPECT_DOUBLE_EQ(2.0 * d->atoms.radius[i], 0.01);
    EXPECT_NEAR(d->atoms.rmass[i], mass_of(0.01, 2500), 1e-12 * d->atoms.rmass[i]);
  }
  Deck e;
  e(kTwo + "variable f equal 0.5\nfix a all adapt 0 atom diameter v_f scale yes\nrun 5\n");
  for (std::size_t i = 0; i < e->atoms.n; ++i) EXPECT_DOUBLE_EQ(2.0 * e->atoms.radius[i], 0.005);
}

// Two grains 12.5 mm apart, gap 2.5 mm > skin 1 mm, at rest: nothing moves, so only
// the rebuild that fix adapt asks for finds the contact once they have grown to
// 13 mm (overlap 0.5 mm). They must then push each other apart along x.
TEST(FixAdapt, GrownGrainsMeetInTheNeighbourList) {
  Deck d;
  d(kTwo + "variable s equal 0.01+0.003*step/100\nfix a all adapt 10 atom diameter v_s\nrun 100\n");
  const sable::Atoms& at = d->atoms;
  const std::size_t a = at.index_of(1), b = at.index_of(2);
  EXPECT_LT(at.v[3 * a], 0.0);
  EXPECT_GT(at.v[3 * b], 0.0);
  EXPECT_NEAR(at.v[3 * a], -at.v[3 * b], 1e-12 * std::fabs(at.v[3 * b]));  // momentum: equal masses
}

// A lattice of 3 mm grains 60 um apart, skin 40 um, grown as in LIGGGHTS' packing
// tutorial (x 1.001 every 20 steps, 600 steps: diameters +91 um; the contacts form
// by growth alone, beyond the first list): the rebuilds that fix adapt's growth
// triggers (Neighbor::grown) miss no contact. The same deck rebuilt at every
// step ends with the same positions and velocities, to round-off (different
// summation orders only), with a small fraction of the rebuilds.
TEST(FixAdapt, GrowthRebuildsOnlyWhenNeededAndMissesNoContact) {
  auto deck = [](const std::string& neigh) {
    return std::string(R"(units si
atom_style granular
atom_modify map array
boundary f f f
region box block 0 0.03 0 0.03 0 0.03 units box
create_box 1 box
neighbor 0.00004 bin
)") + neigh + "\n" + kMaterials + R"(timestep 1e-6
fix w1 all wall/gran model hertz tangential history primitive type 1 xplane 0
fix w2 all wall/gran model hertz tangential history primitive type 1 xplane 0.03
lattice sc 0.00306
region in block 0.002 0.028 0.002 0.028 0.002 0.028 units box
create_atoms 1 region in
set group all diameter 0.003 density 2500
fix i all nve/sphere
compute rad all property/atom radius
variable g atom 1.001*2*c_rad
fix a all adapt 20 atom diameter v_g
run 600
)";
  };
  Deck lazy, every;
  lazy(deck("neigh_modify delay 0"));
  every(deck("neigh_modify every 1 delay 0 check no"));
  const sable::Atoms &a = lazy->atoms, &b = every->atoms;
  ASSERT_EQ(a.n, b.n);
  ASSERT_GT(a.n, 500u);
  double vmax = 0.0, dv = 0.0, dx = 0.0;
  for (std::size_t i = 0; i < a.n; ++i) {
    const std::size_t j = b.index_of(a.id[i]);
    for (int k = 0; k < 3; ++k) {
      vmax = std::max(vmax, std::fabs(b.v[3 * j + k]));
      dv = std::max(dv, std::fabs(a.v[3 * i + k] - b.v[3 * j + k]));
      dx = std::max(dx, std::fabs(a.x[3 * i + k] - b.x[3 * j + k]));
    }
  }
  EXPECT_GT(vmax, 1e-3) << "the growth must have pushed grains apart (contacts formed)";
  EXPECT_LT(dv, 1e-9 * vmax);
  EXPECT_LT(dx, 1e-12);
  EXPECT_GE(every->neighbor.builds, 600);
  EXPECT_GE(lazy->neighbor.builds, 3) << "radii +45 um: at least two rebuilds by growth (half skin 20 um)";
  EXPECT_LT(lazy->neighbor.builds, 30);
}

TEST(FixAdapt, Errors) {
  Deck d1;
  EXPECT_NE(error_of(d1, kTwo + "fix a all adapt 10 pair soft a 1 1 v_x\n").find("atom diameter only"),
            std::string::npos);
  Deck d2;
  EXPECT_NE(error_of(d2, kTwo + "fix a all adapt -1 atom diameter v_x\n").find("a period N >= 0"),
            std::string::npos);
  Deck d3;
  EXPECT_NE(error_of(d3, kTwo + "fix a all adapt 1 atom charge v_x\n").find("'diameter'"), std::string::npos);
  Deck d4;
  EXPECT_NE(error_of(d4, kTwo + "fix a all adapt 1 atom diameter v_nothere\nrun 1\n").find("'nothere' is not defined"),
            std::string::npos);
  Deck d5;
  EXPECT_NE(error_of(d5, kTwo + "variable s equal -0.01\nfix a all adapt 1 atom diameter v_s\nrun 1\n")
                .find("must be > 0"),
            std::string::npos);
}

}  // namespace test_fix_adapt
