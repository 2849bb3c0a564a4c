// compute ke against 1/2 m v^2 summed by hand (relative 1e-12: round-off only).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/input/variable.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_compute_ke {

using sable::test::Deck;

namespace {
void three_grains(Deck& d) {
  d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.9 units box
create_atoms 1 single 0.2 0.3 0.4 units box
create_atoms 1 single 0.7 0.1 0.2 units box)");
  sable::Atoms& a = d->atoms;
  const double v[3][3] = {{1.5, -2, 0.25}, {0.1, 0, 0}, {0, 0, -0.5}};
  const double f[3][3] = {{0.5, 0, -1}, {0, 0, 0}, {0, 2, 0}};
  const double r[3] = {0.05, 0.1, 0.025}, rho[3] = {2500, 1000, 3000};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      a.v[3 * i + k] = v[i][k];
      a.f[3 * i + k] = f[i][k];
    }
    a.set_radius_density(i, r[i], rho[i]);
  }
}
double mass(double r, double rho) { return 4.0 / 3.0 * std::numbers::pi * r * r * r * rho; }
}  // namespace

TEST(ComputeKe, SumsHalfMassSpeedSquaredOverTheGroup) {
  Deck d;
  three_grains(d);
  d("compute k all ke\ncompute k1 all ke update_on_run_end yes");
  const double m1 = mass(0.05, 2500), m2 = mass(0.1, 1000), m3 = mass(0.025, 3000);
  const double want = 0.5 * m1 * (1.5 * 1.5 + 4 + 0.0625) + 0.5 * m2 * 0.01 + 0.5 * m3 * 0.25;
  sable::Compute* k = d->find_compute("k");
  ASSERT_TRUE(k->scalar_flag);
  EXPECT_NEAR(k->scalar(), want, 1e-12 * want);
  EXPECT_NEAR(d->find_compute("k1")->scalar(), want, 1e-12 * want);
  // Group: only atom 2 (groups made directly; the `group` command is another engineer's).
  const int g = d->groups.find_or_create("two");
  d->atoms.mask[1] |= d->groups.bit(g);
  d("compute k2 two ke");
  EXPECT_NEAR(d->find_compute("k2")->scalar(), 0.5 * m2 * 0.01, 1e-12 * 0.5 * m2 * 0.01);
  // As a thermo column / in an equal-style variable, the same value.
  d("variable e equal c_k");
  double e = 0;
  ASSERT_TRUE(d->variables->numeric("e", e));
  EXPECT_NEAR(e, want, 1e-12 * want);
}

TEST(ComputeKe, HalfstepUsesVelocityHalfAStepAhead) {
  Deck d;
  three_grains(d);
  d("timestep 0.001\ncompute k all ke halfstep");
  const double m[3] = {mass(0.05, 2500), mass(0.1, 1000), mass(0.025, 3000)};
  const sable::Atoms& a = d->atoms;
  double want = 0;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = a.v[3 * i + k] + 0.5 * 0.001 * a.f[3 * i + k] / m[i];  // v(t + dt/2)
      want += 0.5 * m[i] * v * v;
    }
  EXPECT_NEAR(d->find_compute("k")->scalar(), want, 1e-12 * want);
}

TEST(ComputeKe, RecomputedAfterAtomsChangeBetweenRunsAtTheSameStep) {
  Deck d;
  three_grains(d);
  d("compute k all ke\nthermo_style custom step c_k\nrun 0");
  d->atoms.v[3 * d->atoms.index_of(1)] = 0.0;  // as `set` or `velocity` would do between runs
  const double m1 = mass(0.05, 2500), m2 = mass(0.1, 1000), m3 = mass(0.025, 3000);
  const double want = 0.5 * m1 * (4 + 0.0625) + 0.5 * m2 * 0.01 + 0.5 * m3 * 0.25;
  d("run 0");
  EXPECT_NEAR(d->find_compute("k")->scalar(), want, 1e-12 * want);
}

TEST(ComputeKe, BadKeywordIsRejectedAtItsLine) {
  Deck d;
  three_grains(d);
  try {
    d("compute k all ke fullstep");
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("'fullstep' in 'compute k all ke fullstep': expected halfstep"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace test_compute_ke
