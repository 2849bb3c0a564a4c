// compute pair/gran/local: columns, order, values, group filter, periodic
// flag, and that producing records never changes forces or history.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/compute.h"
#include "core/error.h"
#include "tests/unit/deck_runner.h"

using sable::test::Deck;
using sable::test::entry_history;

namespace {

const char* kDeck = R"(units si
atom_style granular
boundary p f f
region box block 0 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
create_atoms 1 single 0.004 0 0 units box
create_atoms 1 single 0.00598 0 0 units box
create_atoms 1 single 0.00001 0 0 units box
create_atoms 1 single 0.00999 0.0019 0 units box)";

void setup(Deck& d) {
  d(kDeck);
  for (std::size_t i = 0; i < d->atoms.n; ++i) {
    d->atoms.set_radius_density(i, 0.001, 2500);
    d->atoms.v[3 * i + 1] = 0.01 * static_cast<double>(i);  // some sliding, so the springs load
  }
}

}  // namespace

TEST(ContactLocal, PairColumnsValuesAndPeriodicFlag) {
  Deck d;
  setup(d);
  d("compute c all pair/gran/local pos vel id force force_normal force_tangential torque history contactArea delta");
  d("run 3");
  sable::Compute* c = d->find_compute("c");
  c->local_now();
  // Contacts: 1-2 (overlap 2e-5) and 3-4 across the periodic x boundary.
  ASSERT_EQ(c->local_rows(), 2u);
  ASSERT_EQ(c->local_cols, 32);
  EXPECT_EQ(c->local_names[12], "id1");
  EXPECT_EQ(c->local_names[27], "shearx");
  EXPECT_EQ(c->local_names[30], "contactArea");
  EXPECT_EQ(c->local_names[31], "delta");
  for (std::size_t r = 0; r < 2; ++r) {
    const double* row = &c->local[r * 32];
    const long a = static_cast<long>(row[12]), b = static_cast<long>(row[13]);
    const bool periodic = (a == 3 || a == 4);
    EXPECT_EQ(row[14], periodic ? 1.0 : 0.0);
    // Records are re-evaluated now with history read, not advanced: with only
    // this contact on grain a, its force equals f[a] of the last force pass
    // up to the half-step velocity change (tiny at this overlap).
    const std::size_t ia = d->atoms.index_of(a);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(row[15 + k], d->atoms.f[3 * ia + k], 1e-3 * std::fabs(d->atoms.f[3 * ia]));
    // force = normal + tangential parts
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(row[15 + k], row[18 + k] + row[21 + k], 1e-15);
    // Overlap and sphere-sphere contact area pi (r^2 - (d/2)^2) for equal radii.
    const double dist = 0.002 - row[31];
    EXPECT_NEAR(row[30], std::numbers::pi * (1e-6 - dist * dist / 4), 1e-18);
    EXPECT_GT(row[31], 0.0);
    EXPECT_NE(b, 0);
  }
}

TEST(ContactLocal, RecordsDoNotChangeHistoryOrForces) {
  Deck d;
  setup(d);
  d("compute c all pair/gran/local");
  d("run 5");
  const std::vector<double> hist = entry_history(*d->pair->history());
  const std::vector<double> f = d->atoms.f;
  sable::Compute* c = d->find_compute("c");
  c->local_now();
  EXPECT_EQ(entry_history(*d->pair->history()), hist);
  EXPECT_EQ(d->atoms.f, f);
  // LIGGGHTS' default columns: pos vel id force torque history contactArea.
  EXPECT_EQ(c->local_cols, 6 + 6 + 3 + 3 + 3 + 3 + 1);
}

TEST(ContactLocal, GroupFilterNeedsBothGrains) {
  Deck d;
  setup(d);
  d("group one id 1 3");
  d("compute c one pair/gran/local id");
  d("run 0");
  sable::Compute* c = d->find_compute("c");
  c->local_now();
  EXPECT_EQ(c->local_rows(), 0u);
}

TEST(ContactLocal, HistoryColumnNeedsAModelWithHistory) {
  Deck d;
  d(R"(units si
atom_style granular
region box block 0 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
pair_style gran model hertz tangential no_history)");
  try {
    d("compute c all pair/gran/local history");
    FAIL() << "expected an error";
  } catch (const sable::SableError& e) {
    EXPECT_NE(std::string(e.what()).find("keeps no contact history"), std::string::npos) << e.what();
  }
}

// Evaluated between runs, the compute re-reads a pair style redefined since its
// last init (Compute::ready): here the new model keeps no history, which the
// compute's 'history' column needs, and it says so instead of reading a freed pair.
TEST(ContactLocal, FollowsAPairStyleRedefinedBetweenRuns) {
  Deck d;
  setup(d);
  d("compute c all pair/gran/local id force history");
  d("run 2");
  d("pair_style gran model hertz tangential no_history");
  d("pair_coeff * *");
  try {
    d->find_compute("c")->local_now();
    FAIL() << "expected an error";
  } catch (const sable::SableError& e) {
    EXPECT_NE(std::string(e.what()).find("keeps no contact history"), std::string::npos) << e.what();
  }
}
