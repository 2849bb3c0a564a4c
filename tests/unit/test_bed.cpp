// A poured bed at rest: the floor carries the whole weight (no side walls:
// x and y are periodic, so no Janssen redirection onto walls).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_bed {

using sable::test::Deck;

TEST(Bed, FloorForceEqualsWeightOfSettledBed) {
  Deck d;
  d(R"D(units si
atom_style granular
boundary p p f
region box block 0 0.04 0 0.04 0 0.05 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
region ins block 0 0.04 0 0.04 0.001 0.045 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.001
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 2000 region ins
fix i all nve/sphere
run 1
unfix ins
run 45000)D");
  ASSERT_EQ(d->atoms.n, 2000u);
  double weight = 0;
  for (std::size_t i = 0; i < d->atoms.n; ++i) weight += d->atoms.rmass[i] * 9.81;
  // Average the floor force over 0.05 s of rest (sampled every 100 steps).
  double sum = 0;
  int n = 0;
  sable::Fix* floor = d->find_fix("floor");
  for (int k = 0; k < 50; ++k) {
    d("run 100");
    sum += floor->compute_vector(3);
    ++n;
  }
  const double mean = -sum / n;  // grains push the floor down (-z)
  EXPECT_NEAR(mean / weight, 1.0, 0.005) << "floor force " << mean << " N vs weight " << weight << " N";
}

}  // namespace test_bed
