// set, velocity, group and delete_atoms: counts, values, LIGGGHTS semantics, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/engine/error.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_setup_commands {

using sable::test::Deck;
using sable::test::error_of;

namespace {

const char* kBox = R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 2 box
create_atoms 1 single 0.1 0.5 0.5 units box
create_atoms 1 single 0.3 0.5 0.5 units box
create_atoms 2 single 0.5 0.5 0.5 units box
create_atoms 2 single 0.7 0.5 0.5 units box)";

std::size_t at(Deck& d, long id) { return d->atoms.index_of(id); }

long count_group(Deck& d, const std::string& g) {
  const int gi = d->groups.find(g);
  EXPECT_GE(gi, 0) << g;
  long n = 0;
  for (std::size_t i = 0; i < d->atoms.n; ++i) n += (d->atoms.mask[i] & d->groups.bit(gi)) != 0;
  return n;
}

}  // namespace

// Mass follows diameter and density: 4/3 pi r^3 rho; tolerance 1e-12 relative (round-off only).
TEST(SetCommand, DiameterAndDensitySetTheSphereMass) {
  Deck d;
  d(kBox);
  d("set atom 1 diameter 0.004 density 2500\nset atom 2 density 1000 diameter 0.01\nset type 2 mass 0.5");
  const auto& a = d->atoms;
  const double r1 = 0.002, m1 = 4.0 / 3.0 * std::numbers::pi * r1 * r1 * r1 * 2500;
  EXPECT_DOUBLE_EQ(a.radius[at(d, 1)], r1);
  EXPECT_NEAR(a.rmass[at(d, 1)], m1, 1e-12 * m1);
  EXPECT_EQ(a.density[at(d, 1)], 2500);
  const double m2 = 4.0 / 3.0 * std::numbers::pi * 0.005 * 0.005 * 0.005 * 1000;
  EXPECT_NEAR(a.rmass[at(d, 2)], m2, 1e-12 * m2);
  // mass sets the mass only (LIGGGHTS): radius and density unchanged.
  EXPECT_EQ(a.rmass[at(d, 3)], 0.5);
  EXPECT_EQ(a.rmass[at(d, 4)], 0.5);
  EXPECT_EQ(a.radius[at(d, 3)], 0.5);
}

// LIGGGHTS 3.8 in 2D: set diameter/density give the disc mass pi r^2 rho (checked against liggghts).
TEST(SetCommand, TwoDimensionalMassIsDiscMass) {
  Deck d;
  d(R"(units si
atom_style granular
dimension 2
boundary f f p
region box block 0 1 0 1 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0 units box
set atom 1 diameter 0.01 density 2000)");
  const double m = std::numbers::pi * 0.005 * 0.005 * 2000;
  EXPECT_NEAR(d->atoms.rmass[0], m, 1e-12 * m);
}

TEST(SetCommand, SelectionStylesAndKinematicKeywords) {
  Deck d;
  d(kBox);
  d(R"(region left block 0 0.4 0 1 0 1 units box
set region left vx 1.5 omegaz 2
set type 2 vy -1 omegax 3
set atom 2*3 z 0.25
set atom * y 0.75
set atom 4 type 1
group two id 2
set group two x 0.35 vz 7 omegay 4)");
  const auto& a = d->atoms;
  EXPECT_EQ(a.v[3 * at(d, 1)], 1.5);
  EXPECT_EQ(a.v[3 * at(d, 2)], 1.5);
  EXPECT_EQ(a.v[3 * at(d, 3)], 0.0);  // not in region
  EXPECT_EQ(a.omega[3 * at(d, 1) + 2], 2.0);
  EXPECT_EQ(a.v[3 * at(d, 3) + 1], -1.0);
  EXPECT_EQ(a.omega[3 * at(d, 4)], 3.0);
  EXPECT_EQ(a.x[3 * at(d, 1) + 2], 0.5);
  EXPECT_EQ(a.x[3 * at(d, 2) + 2], 0.25);
  EXPECT_EQ(a.x[3 * at(d, 3) + 2], 0.25);
  for (long id = 1; id <= 4; ++id) EXPECT_EQ(a.x[3 * at(d, id) + 1], 0.75);
  EXPECT_EQ(a.type[at(d, 4)], 1);
  EXPECT_EQ(a.x[3 * at(d, 2)], 0.35);
  EXPECT_EQ(a.v[3 * at(d, 2) + 2], 7.0);
  EXPECT_EQ(a.omega[3 * at(d, 2) + 1], 4.0);
}

TEST(SetCommand, AtomStyleVariableGivesPerAtomValues) {
  Deck d;
  d(kBox);
  d("variable vv atom 2*x\nset group all vx v_vv");
  for (std::size_t i = 0; i < d->atoms.n; ++i) EXPECT_DOUBLE_EQ(d->atoms.v[3 * i], 2 * d->atoms.x[3 * i]);
}

// Nested atom-style variables (LAMMPS allows v_ of an atom variable inside
// another): each atom gets its own value at every level.
TEST(SetCommand, NestedAtomStyleVariables) {
  Deck d;
  d(kBox);
  d("variable a atom 2*x\nvariable b atom v_a+id\nvariable c atom v_b*v_a-v_a\nset group all vx v_c");
  ASSERT_GT(d->atoms.n, 1u);
  for (std::size_t i = 0; i < d->atoms.n; ++i) {
    const double a = 2 * d->atoms.x[3 * i], b = a + static_cast<double>(d->atoms.id[i]);
    EXPECT_EQ(d->atoms.v[3 * i], b * a - a) << "atom " << i;  // same operations: exact
  }
}

TEST(SetCommand, ImageOnlyOnPeriodicAxes) {
  Deck d;
  d(R"(units si
atom_style granular
boundary p f f
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.5 units box
set atom 1 image 2 NULL 0)");
  EXPECT_EQ(d->atoms.image[0], 2);
  EXPECT_NE(error_of(d, "set atom 1 image 0 1 0").find("is not periodic"), std::string::npos);
}

// type/fraction: each atom changes with probability f, from (seed, id) alone.
// 1000 atoms, f = 0.3: binomial sd = sqrt(1000*0.3*0.7) = 14.5; accept |n - 300| < 3 sd = 43.5.
TEST(SetCommand, TypeFractionIsBinomialAndReproducible) {
  auto run = [](long seed) {
    Deck d;
    d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 2 box
lattice sc 0.1)");
    d("create_atoms 1 box\nset group all type/fraction 2 0.3 " + std::to_string(seed));
    std::vector<int> t(d->atoms.n);
    for (std::size_t i = 0; i < d->atoms.n; ++i) t[d->atoms.id[i] - 1] = d->atoms.type[i];
    return t;
  };
  const auto a = run(12345), b = run(12345), c = run(54321);
  ASSERT_EQ(a.size(), 1000u);
  long n = 0;
  for (int t : a) n += t == 2;
  EXPECT_LT(std::abs(n - 300), 43.5);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(SetCommand, ErrorsNameTheWordAndWhatWasExpected) {
  Deck d;
  d(kBox);
  EXPECT_NE(error_of(d, "set atom 99 vx 1").find("there is no atom 99"), std::string::npos);
  EXPECT_NE(error_of(d, "set atom 1 colour 3").find("'colour' in 'set atom 1 colour 3': expected a set keyword"),
            std::string::npos);
  EXPECT_NE(error_of(d, "set group nogroup vx 1").find("expected an existing group ID"), std::string::npos);
  EXPECT_NE(error_of(d, "set region noregion vx 1").find("expected an existing region ID"), std::string::npos);
  EXPECT_NE(error_of(d, "set atom 1 diameter -1").find("a finite diameter > 0"), std::string::npos);
  EXPECT_NE(error_of(d, "set atom 1 type 3").find("an atom type between 1 and 2"), std::string::npos);
  EXPECT_NE(error_of(d, "set type 1*5 vx 0").find("within 1..2"), std::string::npos);
  EXPECT_NE(error_of(d, "set atom 1 vx fast").find("(a number)"), std::string::npos);
  EXPECT_NE(error_of(d, "set atom 1 vx v_nothing").find("no variable 'nothing'"), std::string::npos);
}

TEST(VelocityCommand, SetSumNullAndRamp) {
  Deck d;
  d(kBox);
  d("velocity all set 1 2 3\nvelocity all set NULL 5 NULL sum yes\ngroup t2 type 2\nvelocity t2 set NULL NULL 0");
  const auto& a = d->atoms;
  EXPECT_EQ(a.v[3 * at(d, 1)], 1.0);
  EXPECT_EQ(a.v[3 * at(d, 1) + 1], 7.0);
  EXPECT_EQ(a.v[3 * at(d, 1) + 2], 3.0);
  EXPECT_EQ(a.v[3 * at(d, 3) + 2], 0.0);
  // ramp: x = 0.1 -> 0 (clamped below clo = 0.2), 0.3 -> 0.25, 0.5 -> 0.75, 0.7 -> 1 (clamped).
  d("velocity all ramp vz 0 1 x 0.2 0.6");
  EXPECT_NEAR(a.v[3 * at(d, 1) + 2], 0.0, 1e-15);
  EXPECT_NEAR(a.v[3 * at(d, 2) + 2], 0.25, 1e-15);
  EXPECT_NEAR(a.v[3 * at(d, 3) + 2], 0.75, 1e-15);
  EXPECT_NEAR(a.v[3 * at(d, 4) + 2], 1.0, 1e-15);
}

// zero linear / angular: group momentum and angular momentum vanish to round-off
// (tolerance 1e-13 of the sum of |m v| resp. |m r x v| terms).
TEST(VelocityCommand, ZeroLinearAndAngularMomentum) {
  Deck d;
  d(kBox);
  d(R"(create_atoms 1 single 0.4 0.2 0.8 units box
set atom 1 diameter 0.1
set atom 5 density 3000
velocity all set 1 -2 0.5
set atom 2 vy 4
set atom 3 vz -1 vx 0.3
velocity all zero linear)");
  const auto& a = d->atoms;
  double p[3] = {0, 0, 0}, pscale = 0;
  for (std::size_t i = 0; i < a.n; ++i)
    for (int k = 0; k < 3; ++k) {
      p[k] += a.rmass[i] * a.v[3 * i + k];
      pscale += std::fabs(a.rmass[i] * a.v[3 * i + k]);
    }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], 0.0, 1e-13 * pscale);
  d("set atom 4 vy 3\nvelocity all zero angular");
  double xc[3] = {0, 0, 0}, m = 0, L[3] = {0, 0, 0}, lscale = 0;
  for (std::size_t i = 0; i < a.n; ++i) {
    m += a.rmass[i];
    for (int k = 0; k < 3; ++k) xc[k] += a.rmass[i] * a.x[3 * i + k];
  }
  for (double& c : xc) c /= m;
  for (std::size_t i = 0; i < a.n; ++i) {
    const double r[3] = {a.x[3 * i] - xc[0], a.x[3 * i + 1] - xc[1], a.x[3 * i + 2] - xc[2]};
    const double* v = &a.v[3 * i];
    L[0] += a.rmass[i] * (r[1] * v[2] - r[2] * v[1]);
    L[1] += a.rmass[i] * (r[2] * v[0] - r[0] * v[2]);
    L[2] += a.rmass[i] * (r[0] * v[1] - r[1] * v[0]);
    lscale +=
        a.rmass[i] * std::sqrt((r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  ASSERT_GT(lscale, 0);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(L[k], 0.0, 1e-13 * lscale);
}

TEST(VelocityCommand, Errors) {
  Deck d;
  d(kBox);
  EXPECT_NE(error_of(d, "velocity nogroup set 1 0 0").find("expected an existing group ID"), std::string::npos);
  EXPECT_NE(error_of(d, "velocity all set 1.0x 0 0").find("(a number)"), std::string::npos);
  EXPECT_NE(error_of(d, "velocity all create 300 4928459").find("not supported"), std::string::npos);
  EXPECT_NE(error_of(d, "velocity all set 1 0 0 sum maybe").find("yes/no"), std::string::npos);
  Deck d2;
  d2(R"(units si
atom_style granular
dimension 2
region box block 0 1 0 1 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0 units box)");
  EXPECT_NE(error_of(d2, "velocity all set 0 0 1").find("vz in a 2D simulation"), std::string::npos);
}

TEST(GroupCommand, TypeIdRegionAndLogicals) {
  Deck d;
  d(kBox);
  d(R"(create_atoms 2 single 0.9 0.5 0.5 units box
group t1 type 1
group t12 type 1:2
group odd id 1:5:2
group few id 2 4
group low id <= 2
group mid id <> 2 4
group ne id != 3
region right block 0.6 1 0 1 0 1 units box
group r region right
group r id 1
group e initialize
group e2 empty)");
  EXPECT_EQ(count_group(d, "t1"), 2);
  EXPECT_EQ(count_group(d, "t12"), 5);
  EXPECT_EQ(count_group(d, "odd"), 3);
  EXPECT_EQ(count_group(d, "few"), 2);
  EXPECT_EQ(count_group(d, "low"), 2);
  EXPECT_EQ(count_group(d, "mid"), 3);
  EXPECT_EQ(count_group(d, "ne"), 4);
  EXPECT_EQ(count_group(d, "r"), 3);  // 0.7, 0.9, plus atom 1 added to the existing group
  EXPECT_EQ(count_group(d, "e"), 0);
  EXPECT_EQ(count_group(d, "e2"), 0);
  EXPECT_EQ(count_group(d, "all"), 5);
}

TEST(GroupCommand, SetOperationsAndDelete) {
  Deck d;
  d(kBox);
  d(R"(group a id 1 2 3
group b id 2 3 4
group c id 3
group u union a b
group i intersect a b
group s subtract a b
group s2 subtract all c)");
  EXPECT_EQ(count_group(d, "u"), 4);
  EXPECT_EQ(count_group(d, "i"), 2);
  EXPECT_EQ(count_group(d, "s"), 1);
  EXPECT_EQ(count_group(d, "s2"), 3);
  const std::uint32_t bit_b = d->groups.bit(d->groups.find("b"));
  d("group a delete");
  EXPECT_EQ(d->groups.find("a"), -1);
  EXPECT_EQ(d->groups.bit(d->groups.find("b")), bit_b);  // other groups keep their bit
  d("group a id 4");                                     // the name can be reused, starting empty
  EXPECT_EQ(count_group(d, "a"), 1);
  EXPECT_NE(error_of(d, "group all delete").find("a group other than 'all'"), std::string::npos);
  d("fix f b viscous 0.1");
  EXPECT_NE(error_of(d, "group b delete").find("fix 'f' acts on it"), std::string::npos);
  EXPECT_NE(error_of(d, "group x union nogroup").find("expected an existing group ID"), std::string::npos);
  EXPECT_NE(error_of(d, "group x id 1:b").find("A:B"), std::string::npos);
  EXPECT_NE(error_of(d, "group x colour 3").find("a group style"), std::string::npos);
}

TEST(DeleteAtoms, CompressRenumbersByDefaultLikeLiggghts) {
  Deck d;
  d(kBox);
  d("group g id 2 3\ndelete_atoms group g");
  ASSERT_EQ(d->atoms.n, 2u);
  // LIGGGHTS default compress yes: IDs become 1..N (old 1 -> 1, old 4 -> 2, as liggghts 3.8 does).
  EXPECT_EQ(d->atoms.x[3 * at(d, 1)], 0.1);
  EXPECT_EQ(d->atoms.x[3 * at(d, 2)], 0.7);
  d("create_atoms 1 single 0.9 0.5 0.5 units box");
  EXPECT_NE(at(d, 3), sable::Atoms::npos);
}

TEST(DeleteAtoms, CompressNoKeepsIdsAndRegionDeletes) {
  Deck d;
  d(kBox);
  d("region mid block 0.2 0.6 0 1 0 1 units box\ndelete_atoms region mid compress no");
  ASSERT_EQ(d->atoms.n, 2u);
  EXPECT_NE(at(d, 1), sable::Atoms::npos);
  EXPECT_NE(at(d, 4), sable::Atoms::npos);
  EXPECT_EQ(at(d, 2), sable::Atoms::npos);
  // New atoms continue after the largest remaining ID (LIGGGHTS tag_extend).
  d("group top id 4\ndelete_atoms group top compress no\ncreate_atoms 1 single 0.9 0.5 0.5 units box");
  EXPECT_NE(at(d, 2), sable::Atoms::npos);
  EXPECT_EQ(d->atoms.x[3 * at(d, 2)], 0.9);
}

// porosity: each atom in the region goes with probability f. 1000 atoms, f = 0.25:
// sd = sqrt(1000*0.25*0.75) = 13.7, accept within 3 sd = 41; same seed -> same atoms.
TEST(DeleteAtoms, PorosityFractionAndReproducibility) {
  auto run = [](long seed) {
    Deck d;
    d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
lattice sc 0.1
create_atoms 1 box)");
    d("delete_atoms porosity box 0.25 " + std::to_string(seed) + " compress no");
    std::vector<long> ids(d->atoms.id.begin(), d->atoms.id.begin() + d->atoms.n);
    std::sort(ids.begin(), ids.end());
    return ids;
  };
  const auto a = run(4321), b = run(4321), c = run(9876);
  EXPECT_LT(std::abs(static_cast<long>(a.size()) - 750), 41);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(DeleteAtoms, Errors) {
  Deck d;
  d(kBox);
  EXPECT_NE(error_of(d, "delete_atoms group nogroup").find("expected an existing group ID"), std::string::npos);
  EXPECT_NE(error_of(d, "delete_atoms region noregion").find("expected an existing region ID"), std::string::npos);
  EXPECT_NE(error_of(d, "delete_atoms all").find("group, region or porosity"), std::string::npos);
  EXPECT_NE(error_of(d, "delete_atoms group all compress maybe").find("yes/no"), std::string::npos);
}

// lattice ... origin x y z (LAMMPS, LIGGGHTS): every basis site shifted by these
// fractions of the spacing. sc 0.1 in the unit box with origin 0.5: sites at
// (k + 0.5) 0.1, k = 0..9 on each axis, 1000 in all (none on the upper faces).
TEST(LatticeCommand, OriginShiftsTheSites) {
  Deck d;
  d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
lattice sc 0.1 origin 0.5 0.5 0.5
create_atoms 1 box)");
  ASSERT_EQ(d->atoms.n, 1000u);
  for (std::size_t i = 0; i < d->atoms.n; ++i)
    for (int k = 0; k < 3; ++k) {
      const double cell = d->atoms.x[3 * i + k] / 0.1 - 0.5;
      EXPECT_NEAR(cell, std::round(cell), 1e-9) << "atom " << i << " axis " << k;
    }
  Deck e;
  e(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box)");
  EXPECT_NE(error_of(e, "lattice sc 0.1 origin 0.5 1 0").find("expected an origin fraction in [0, 1)"), std::string::npos);
  EXPECT_NE(error_of(e, "lattice sc 0.1 orient x 1 0 0").find("expected 'origin' or nothing"), std::string::npos);
}

}  // namespace test_setup_commands
