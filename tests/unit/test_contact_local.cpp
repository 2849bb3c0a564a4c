// compute pair/gran/local: columns, order, values, group filter, periodic
// flag, and that producing records never changes forces or history.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include "core/engine/compute.h"
#include "core/engine/error.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_local {

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

// A contact is recorded only when both grains are in the compute's group:
// {1, 3} holds one grain of each contact (1-2 and the periodic 3-4) and gets
// no row; the positive controls {1, 2} and {3, 4} get exactly their contact,
// with the force LIGGGHTS' Hertz law gives at set-up (run 0: the tangential
// spring is zero, so Ft is the dashpot alone). By hand, equal grains
// (r = 1 mm, 2500 kg/m^3): R* = r/2, m* = m/2, Y* = E / (2 (1 - nu^2)),
// G* = E / (4 (2 - nu)(1 + nu)), beta = ln e / sqrt(ln^2 e + pi^2);
// Fn = 4/3 Y* sqrt(R* dn) dn - gamman vn along en (j -> i), Ft = -gammat vtr,
// gamman = -2 sqrt(5/6) beta sqrt(2 Y* sqrt(R* dn) m*), gammat likewise with 8 G*.
TEST(ContactLocal, GroupFilterNeedsBothGrains) {
  Deck d;
  setup(d);
  d("group one id 1 3\ngroup pair12 id 1 2\ngroup pair34 id 3 4");
  d("compute c one pair/gran/local id");
  d("compute c12 pair12 pair/gran/local id force_normal force_tangential delta");
  d("compute c34 pair34 pair/gran/local id force_normal force_tangential delta");
  d("run 0");
  sable::Compute* c = d->find_compute("c");
  c->local_now();
  EXPECT_EQ(c->local_rows(), 0u);

  const double r = 0.001, E = 5e7, nu = 0.3, e = 0.5, pi = std::numbers::pi;
  const double m = 4.0 / 3.0 * pi * r * r * r * 2500, meff = m / 2, reff = r / 2;
  const double Ystar = E / (2 * (1 - nu * nu)), Gstar = E / (4 * (2 - nu) * (1 + nu));
  const double beta = std::log(e) / std::sqrt(std::log(e) * std::log(e) + pi * pi);
  const auto& a = d->atoms;
  for (const auto& [id, want_a, want_b] : {std::tuple{"c12", 1L, 2L}, std::tuple{"c34", 3L, 4L}}) {
    sable::Compute* p = d->find_compute(id);
    p->local_now();
    ASSERT_EQ(p->local_rows(), 1u) << id;
    ASSERT_EQ(p->local_cols, 3 + 3 + 3 + 1) << id;
    const double* row = p->local.data();
    const long ia = static_cast<long>(row[0]), ib = static_cast<long>(row[1]);
    EXPECT_EQ(std::min(ia, ib), want_a) << id;
    EXPECT_EQ(std::max(ia, ib), want_b) << id;
    EXPECT_EQ(row[2], ia == 3 || ia == 4 ? 1.0 : 0.0) << id;  // periodic flag
    const std::size_t i = a.index_of(ia), j = a.index_of(ib);
    double dx[3], v[3];
    for (int k = 0; k < 3; ++k) {
      dx[k] = a.x[3 * i + k] - a.x[3 * j + k];
      v[k] = a.v[3 * i + k] - a.v[3 * j + k];
    }
    dx[0] -= 0.01 * std::round(dx[0] / 0.01);  // nearest periodic image in x
    const double dist = std::sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]), dn = 2 * r - dist;
    ASSERT_GT(dn, 0) << id;
    const double en[3] = {dx[0] / dist, dx[1] / dist, dx[2] / dist};
    const double vn = v[0] * en[0] + v[1] * en[1] + v[2] * en[2];
    const double sq = std::sqrt(reff * dn);
    const double gamman = -2 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(2 * Ystar * sq * meff);
    const double gammat = -2 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(8 * Gstar * sq * meff);
    const double fn = 4.0 / 3.0 * Ystar * sq * dn - gamman * vn;
    EXPECT_NEAR(row[9], dn, 1e-15) << id;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(row[3 + k], fn * en[k], 1e-10 * fn) << id << " normal " << k;
      EXPECT_NEAR(row[6 + k], -gammat * (v[k] - vn * en[k]), 1e-10 * fn) << id << " tangential " << k;
    }
  }
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

}  // namespace test_contact_local
