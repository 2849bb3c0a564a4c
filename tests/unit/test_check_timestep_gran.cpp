// fix check/timestep/gran as in LIGGGHTS 3.8 (src/fix_check_timestep_gran.cpp, its doc and a
// run of tests/decks/stability_liggghts_check_fix.in in `liggghts`): every N steps a WARNING
// per limit exceeded, with LIGGGHTS' texts, and the run goes on; `error yes` stops; `warn no`
// is silent; f_ID[1..3] are dt / Rayleigh time, dt / Hertz time, v_rel dt / skin.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/engine/error.h"
#include "core/engine/fix.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_check_timestep_gran {

using sable::test::Deck;
using sable::test::printed;

namespace {
constexpr double kR = 0.001, kRho = 2500, kNu = 0.3, kE = 1e7, kV = 1.0, kSkin = 0.0005;
double rayleigh_time() {
  return std::numbers::pi * kR * std::sqrt(kRho / (kE / (2 * (1 + kNu)))) / (0.1631 * kNu + 0.8766);
}
// LIGGGHTS' Hertz estimate: a grain hitting itself at v_rel = 2 v_max, m_eff = m (the whole
// grain's mass, as LIGGGHTS writes it), r_eff = r/2, Y_eff = Y / (2 (1 - nu^2)).
double liggghts_hertz_time() {
  const double m = 4.0 / 3.0 * std::numbers::pi * kR * kR * kR * kRho, yeff = kE / (2 * (1 - kNu * kNu));
  return 2.87 * std::pow(m * m / (kR / 2 * yeff * yeff * 2 * kV), 0.2);
}
std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}
// Two grains 10 mm apart moving apart at 1 m/s (no contact): the estimates stay constant.
std::string deck(double dt, const std::string& fix) {
  return R"D(units si
atom_style granular
boundary f f f
region box block -0.05 0.05 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
create_atoms 1 single -0.005 0 0 units box
create_atoms 1 single 0.005 0 0 units box
set atom 1 diameter 0.002 density 2500 vx -1
set atom 2 diameter 0.002 density 2500 vx 1
timestep )D" + num(dt) +
         "\nfix i all nve/sphere\n" + fix + "\nrun 10\n";
}
std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}
}  // namespace

TEST(CheckTimestepGran, HandValues) {
  EXPECT_NEAR(rayleigh_time(), 8.65398e-5, 1e-10);        // pi r sqrt(rho/G) / (0.1631 nu + 0.8766)
  EXPECT_NEAR(liggghts_hertz_time(), 2.34381e-4, 1e-9);   // 2.87 (m^2 / (r/2 Y*^2 2v))^(1/5)
}

TEST(CheckTimestepGran, WarnsAtEveryCheckAsLiggghtsAndRuns) {
  // dt = 21 % of the Rayleigh time, limits 0.2 0.2, checked every 5 steps: LIGGGHTS 3.8 prints
  // "WARNING: time-step is 21.000000 % of rayleigh time" at each check (steps 5 and 10).
  const double dt = 0.21 * rayleigh_time();
  Deck d;
  const std::string out = printed(deck(dt, "fix ts all check/timestep/gran 5 0.2 0.2"), d);
  EXPECT_EQ(count(out, "WARNING: time-step is 21.000000 % of rayleigh time (fix ts check/timestep/gran, step "), 2u)
      << out;
  EXPECT_NE(out.find("of rayleigh time (fix ts check/timestep/gran, step 10)"), std::string::npos) << out;
  EXPECT_EQ(count(out, "% of hertz time"), 0u) << out;  // dt is 7.8 % of LIGGGHTS' Hertz time
  EXPECT_EQ(d->step, 10);
  sable::Fix* f = d->find_fix("ts");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(f->vector_size, 3);
  EXPECT_NEAR(f->compute_vector(1), 0.21, 1e-12);
  const double hf = dt / liggghts_hertz_time();
  EXPECT_NEAR(f->compute_vector(2), hf, 1e-9 * hf);
  EXPECT_NEAR(f->compute_vector(3), 2 * kV * dt / kSkin, 1e-9);
}

TEST(CheckTimestepGran, HertzSkinAndRadiusWarnings) {
  // A step of 1.2e-4 s (1.39 Rayleigh times, 51.2 % of LIGGGHTS' Hertz time): grains at 2 m/s
  // relative travel 2.4e-4 m per step, within the skin 5e-4 m and the radius; with skin 1e-4 m
  // the skin warning comes, with 1e-3 s per step also the radius one (2e-3 m > r). accept: the
  // setup guard would stop these steps.
  Deck d;
  const std::string out = printed(deck(1.2e-4, "fix ts all check/timestep/gran 5 2 0.5\ntimestep_check accept"), d);
  EXPECT_EQ(count(out, "WARNING: time-step is 51.1"), 2u) << out;
  EXPECT_EQ(count(out, "% of hertz time (fix ts"), 2u) << out;
  EXPECT_EQ(count(out, "rayleigh time"), 0u) << out;
  EXPECT_EQ(count(out, "skin too small"), 0u) << out;
  Deck s;
  const std::string skin = printed(
      deck(1.2e-4, "fix ts all check/timestep/gran 5 2 2\ntimestep_check accept\nneighbor 1e-4 bin"), s);
  EXPECT_NE(skin.find("WARNING: time step too large or skin too small - particles may relatively travel a distance of "
                      "0.000240 per time-step, but skin is 0.000100 (fix ts check/timestep/gran, step 5)"),
            std::string::npos)
      << skin;
  EXPECT_EQ(count(skin, "minimum radius"), 0u) << skin;
  Deck r;
  const std::string radius = printed(deck(1e-3, "fix ts all check/timestep/gran 5 20 20\ntimestep_check accept"), r);
  EXPECT_NE(radius.find("WARNING: time step way too large - particles relatively move further than the minimum radius "
                        "in one step (fix ts"),
            std::string::npos)
      << radius;
}

TEST(CheckTimestepGran, ErrorYesStopsAtTheFirstCheck) {
  Deck d;
  try {
    d(deck(0.21 * rayleigh_time(), "fix ts all check/timestep/gran 5 0.2 0.2 error yes"));
    FAIL() << "error yes must stop the run";
  } catch (const sable::SableError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("test:19: 'fix ts all check/timestep/gran 5 0.2 0.2 error yes': time-step is 21.000000 % of "
                     "rayleigh time; stopped because of 'error yes' (fix ts check/timestep/gran, step 5)"),
              std::string::npos)
        << m;
  }
  EXPECT_EQ(d->step, 5);
}

TEST(CheckTimestepGran, WarnNoIsSilent) {
  Deck d;
  const std::string out = printed(deck(0.21 * rayleigh_time(), "fix ts all check/timestep/gran 5 0.2 0.2 warn no"), d);
  EXPECT_EQ(count(out, "% of rayleigh time"), 0u) << out;
  EXPECT_EQ(d->step, 10);
  EXPECT_NEAR(d->find_fix("ts")->compute_vector(1), 0.21, 1e-12);  // still computed (LIGGGHTS too)
}

TEST(CheckTimestepGran, VmaxRaisesTheSpeedOfTheHertzEstimate) {
  // vmax 32 m/s over grains at 1 m/s: v_rel = 64 m/s, the Hertz time (64/2)^(1/5) = 2 times shorter.
  Deck d;
  d(deck(1e-6, "fix ts all check/timestep/gran 5 1 1 vmax 32"));
  const double hf = 1e-6 / (liggghts_hertz_time() / 2);
  EXPECT_NEAR(d->find_fix("ts")->compute_vector(2), hf, 1e-9 * hf);
}

TEST(CheckTimestepGran, NeedsYoungsModulusAndPoissonsRatio) {
  Deck d;
  try {
    d(R"D(units si
atom_style granular
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
fix m1 all property/global kn peratomtypepair 1 2000
fix m2 all property/global kt peratomtypepair 1 1000
fix m3 all property/global gamman_abs peratomtypepair 1 0.02
fix m4 all property/global gammat_abs peratomtypepair 1 0.01
fix m5 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hooke/stiffness tangential history absolute_damping on
pair_coeff * *
create_atoms 1 single 0 0 0 units box
set atom 1 diameter 0.002 density 2500
timestep 1e-6
fix i all nve/sphere
fix ts all check/timestep/gran 5 0.2 0.2
run 10
)D");
    FAIL() << "LIGGGHTS refuses the fix without youngsModulus and poissonsRatio; sable too";
  } catch (const sable::SableError& e) {
    EXPECT_NE(std::string(e.what()).find("test:16: 'fix ts all check/timestep/gran 5 0.2 0.2': fix check/timestep/gran "
                                         "only works with pair_style gran and the properties youngsModulus"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace test_check_timestep_gran
