// particletemplate/sphere, particledistribution/discrete and insert/pack:
// counts, no overlap, all_in, reproducibility, distribution statistics, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/engine/error.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_insert_pack {

using sable::test::Deck;
using sable::test::error_of;

namespace {

// Box [0, L]^3 (boundary given), two atom types, nve/sphere, no gravity, no contacts.
std::string box(double L, const char* boundary = "f f f") {
  const std::string l = std::to_string(L);
  return std::string("units si\natom_style granular\nboundary ") + boundary + "\nregion box block 0 " + l + " 0 " + l +
         " 0 " + l + " units box\ncreate_box 2 box\nfix integr all nve/sphere\ntimestep 1e-6\n";
}

// All pairs (brute force): smallest d_ij / (r_i + r_j), minimum image on periodic axes.
double min_gap_ratio(const sable::Simulation& s) {
  const auto& a = s.atoms;
  double worst = 1e300;
  for (std::size_t i = 0; i < a.n; ++i)
    for (std::size_t j = i + 1; j < a.n; ++j) {
      double d2 = 0;
      for (int k = 0; k < s.domain.dimension; ++k) {
        double dk = a.x[3 * i + k] - a.x[3 * j + k];
        if (s.domain.periodic[k]) dk -= s.domain.length(k) * std::round(dk / s.domain.length(k));
        d2 += dk * dk;
      }
      worst = std::min(worst, std::sqrt(d2) / (a.radius[i] + a.radius[j]));
    }
  return worst;
}

const char* kOneTemplate =
    R"(fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.0033
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
)";

}  // namespace

// 2000 grains with centres in a 0.1 m cube (30 % nominal volume fraction) inside a
// 0.2 m box: all placed, no two overlap. Overlap tolerance: 1e-12 relative (round-off).
TEST(InsertPack, ReachesCountWithoutOverlap) {
  Deck d;
  d(box(0.2) + kOneTemplate + R"(region ins block 0.05 0.15 0.05 0.15 0.05 0.15 units box
fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once overlapcheck yes particles_in_region 2000 region ins
run 1)");
  const auto& a = d->atoms;
  ASSERT_EQ(a.n, 2000u);
  const double vf = 2000 * 4.0 / 3.0 * std::numbers::pi * std::pow(0.0033, 3) / 1e-3;
  EXPECT_NEAR(vf, 0.30, 0.01);
  EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);
  for (std::size_t i = 0; i < a.n; ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(a.x[3 * i + k], 0.05);
      EXPECT_LE(a.x[3 * i + k], 0.15);
    }
    EXPECT_EQ(a.type[i], 1);
    EXPECT_EQ(a.radius[i], 0.0033);
  }
  // IDs 1..2000, the fix reports them (f_ins[1], f_ins[2] = inserted mass).
  EXPECT_EQ(a.max_id, 2000);
  auto* f = d->find_fix("ins");
  EXPECT_EQ(f->compute_vector(1), 2000.0);
  const double m = 4.0 / 3.0 * std::numbers::pi * std::pow(0.0033, 3) * 2500;
  EXPECT_NEAR(f->compute_vector(2), 2000 * m, 1e-9 * 2000 * m);
}

// LIGGGHTS inserts at step (definition + 1), in the first step of the next run, not at setup.
TEST(InsertPack, InsertsAtTheFirstStepOfTheNextRun) {
  Deck d;
  d(box(0.1) + kOneTemplate +
    "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once particles_in_region 50 "
    "region box\nrun 0");
  EXPECT_EQ(d->atoms.n, 0u);
  d("run 1");
  EXPECT_EQ(d->atoms.n, 50u);
  d("run 5");
  EXPECT_EQ(d->atoms.n, 50u);  // once
}

// insert_every N keeps N grains in the region: after deleting some, the next insertion step refills.
TEST(InsertPack, InsertEveryRefillsTheRegionAndIdsContinue) {
  Deck d;
  d(box(0.1) + kOneTemplate + R"(region half block 0 0.05 0 0.1 0 0.1 units box
fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every 10 particles_in_region 200 region box
run 1)");
  ASSERT_EQ(d->atoms.n, 200u);
  d("delete_atoms region half compress no");
  const std::size_t left = d->atoms.n;
  const long maxid = d->atoms.max_id;
  ASSERT_LT(left, 200u);
  d("run 9");  // steps 2..10: no insertion step yet (next at 11)
  EXPECT_EQ(d->atoms.n, left);
  d("run 1");
  EXPECT_EQ(d->atoms.n, 200u);
  long newest = 0;
  for (std::size_t i = 0; i < d->atoms.n; ++i) newest = std::max(newest, d->atoms.id[i]);
  EXPECT_EQ(newest, maxid + static_cast<long>(200 - left));
  EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);
}

// all_in yes: every grain lies wholly in the region (block, cylinder, sphere); tolerance 1e-12 m.
TEST(InsertPack, AllInKeepsWholeGrainsInsideBlockCylinderAndSphere) {
  struct Case {
    const char* region;
    double (*depth)(const double*);  // distance from the surface, > 0 inside
  } cases[] = {
      {"region ins block 0.02 0.08 0.03 0.07 0.01 0.09 units box",
       [](const double* x) {
         return std::min({x[0] - 0.02, 0.08 - x[0], x[1] - 0.03, 0.07 - x[1], x[2] - 0.01, 0.09 - x[2]});
       }},
      {"region ins cylinder y 0.05 0.05 0.03 0.02 0.08 units box",
       [](const double* x) {
         return std::min({0.03 - std::hypot(x[0] - 0.05, x[2] - 0.05), x[1] - 0.02, 0.08 - x[1]});
       }},
      {"region ins sphere 0.05 0.05 0.05 0.04 units box",
       [](const double* x) {
         return 0.04 - std::sqrt(std::pow(x[0] - 0.05, 2) + std::pow(x[1] - 0.05, 2) + std::pow(x[2] - 0.05, 2));
       }},
  };
  for (const auto& c : cases) {
    Deck d;
    d(box(0.1) + kOneTemplate + c.region +
      "\nfix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once all_in yes "
      "volumefraction_region 0.15 region ins\nrun 1");
    const auto& a = d->atoms;
    ASSERT_GT(a.n, 20u) << c.region;
    for (std::size_t i = 0; i < a.n; ++i) EXPECT_GE(c.depth(&a.x[3 * i]) - a.radius[i], -1e-12) << c.region;
    EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);
  }
}

// volumefraction_region: inserted volume = F * V_region to within one grain (int(x + uniform)).
TEST(InsertPack, VolumeAndMassTargets) {
  const double vg = 4.0 / 3.0 * std::numbers::pi * std::pow(0.0033, 3);
  {
    Deck d;
    d(box(0.1) + kOneTemplate +
      "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once volumefraction_region 0.2 "
      "region box\nrun 1");
    EXPECT_NEAR(d->atoms.n * vg, 0.2 * 1e-3, vg);
  }
  {
    Deck d;
    d(box(0.1) + kOneTemplate +
      "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once mass_in_region 0.5 "
      "region box\nrun 1");
    EXPECT_NEAR(d->atoms.n * vg * 2500, 0.5, vg * 2500);
  }
}

// Same seeds -> bit-identical radii and positions; another seed -> another packing.
TEST(InsertPack, SameSeedGivesIdenticalPacking) {
  auto pack = [](const std::string& seed) {
    Deck d;
    d(box(0.1) +
      "fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius gaussian number 0.003 "
      "0.0003\nfix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0\n"
      "fix ins all insert/pack seed " +
      seed +
      " distributiontemplate pdd1 insert_every once vel uniform 0 0 -1 0.1 0.1 0.1 volumefraction_region 0.25 region "
      "box\n"
      "run 1");
    std::vector<double> out;
    for (std::size_t i = 0; i < d->atoms.n; ++i) {
      out.push_back(static_cast<double>(d->atoms.id[i]));
      out.push_back(d->atoms.radius[i]);
      for (int k = 0; k < 3; ++k) out.push_back(d->atoms.x[3 * i + k]);
      for (int k = 0; k < 3; ++k) out.push_back(d->atoms.v[3 * i + k]);
    }
    return out;
  };
  const auto a = pack("32452867"), b = pack("32452867"), c = pack("49979687");
  ASSERT_GT(a.size(), 100u);
  EXPECT_EQ(a, b);  // exact equality, bit for bit
  EXPECT_NE(a, c);
}

// Two templates 30/70 by number: LIGGGHTS `random_distribute exact` makes the counts
// floor(n w) or ceil(n w), i.e. within 1 of 0.3 n -- far inside the binomial
// 3 sd = 3 sqrt(2000 * 0.3 * 0.7) = 61 a multinomial draw would allow.
TEST(ParticleDistribution, NumberFractionsAreStratified) {
  Deck d;
  d(box(0.2) + R"(fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.002
fix pts2 all particletemplate/sphere 15485867 atom_type 2 density constant 2500 radius constant 0.003
fix pdd1 all particledistribution/discrete/numberbased 32452843 2 pts1 0.3 pts2 0.7
fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once particles_in_region 2000 region box
run 1)");
  ASSERT_EQ(d->atoms.n, 2000u);
  long n1 = 0;
  for (std::size_t i = 0; i < d->atoms.n; ++i) {
    n1 += d->atoms.type[i] == 1;
    EXPECT_EQ(d->atoms.radius[i], d->atoms.type[i] == 1 ? 0.002 : 0.003);
  }
  EXPECT_LE(std::abs(n1 - 600), 1);
  EXPECT_LT(std::abs(n1 - 600), 3 * std::sqrt(2000 * 0.3 * 0.7));
  EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);
}

// Mass-based weights (the default style) turn into number fractions w_t/m_t, normalised:
// 30/70 by mass of d = 4 and 6 mm gives 59.124 % / 40.876 % by number (liggghts 3.8 prints
// the same); 300 grains -> 177 or 178 small ones.
TEST(ParticleDistribution, MassWeightsBecomeNumberFractions) {
  Deck d;
  d(box(0.1) + R"(fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.002
fix pts2 all particletemplate/sphere 15485867 atom_type 2 density constant 2500 radius constant 0.003
fix pdd1 all particledistribution/discrete 32452843 2 pts1 0.3 pts2 0.7
fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once particles_in_region 300 region box
run 1)");
  long n1 = 0;
  for (std::size_t i = 0; i < d->atoms.n; ++i) n1 += d->atoms.type[i] == 1;
  EXPECT_TRUE(n1 == 177 || n1 == 178) << n1;
}

// radius gaussian number MU SIGMA, truncated at +-3 sigma like LIGGGHTS. 5000 grains:
// truncated-normal sd = 0.98658 sigma; standard errors sigma/sqrt(N) = 2.8e-6 m (mean) and
// sigma/sqrt(2N) = 2.0e-6 m (sd); accept 4 standard errors.
TEST(ParticleTemplate, GaussianRadiusMeanAndSpread) {
  Deck d;
  d(box(0.25) +
    R"(fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius gaussian number 0.002 0.0002
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once overlapcheck no particles_in_region 5000 region box
run 1)");
  const auto& a = d->atoms;
  ASSERT_EQ(a.n, 5000u);
  double s = 0, s2 = 0, lo = 1, hi = 0;
  for (std::size_t i = 0; i < a.n; ++i) {
    s += a.radius[i];
    s2 += a.radius[i] * a.radius[i];
    lo = std::min(lo, a.radius[i]);
    hi = std::max(hi, a.radius[i]);
    const double m = 4.0 / 3.0 * std::numbers::pi * std::pow(a.radius[i], 3) * 2500;
    EXPECT_NEAR(a.rmass[i], m, 1e-12 * m);
  }
  const double mean = s / a.n, sd = std::sqrt(s2 / a.n - mean * mean);
  EXPECT_NEAR(mean, 0.002, 4 * 0.0002 / std::sqrt(5000.0));
  EXPECT_NEAR(sd, 0.98658 * 0.0002, 4 * 0.0002 / std::sqrt(2 * 5000.0));
  EXPECT_GE(lo, 0.002 - 3 * 0.0002);
  EXPECT_LE(hi, 0.002 + 3 * 0.0002);
}

// New grains join "all", the insert fix's group and the template's and distribution's groups.
TEST(InsertPack, InsertedAtomsJoinTheFixGroups) {
  Deck d;
  d(box(0.1) + R"(group grains initialize
group tgroup initialize
group other initialize
fix pts1 tgroup particletemplate/sphere 15485863 atom_type 2 density constant 2500 radius constant 0.003
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
fix ins grains insert/pack seed 32452867 distributiontemplate pdd1 insert_every once particles_in_region 20 region box
run 1)");
  ASSERT_EQ(d->atoms.n, 20u);
  for (const char* g : {"all", "grains", "tgroup"})
    for (std::size_t i = 0; i < d->atoms.n; ++i) EXPECT_TRUE(d->atoms.mask[i] & d->groups.bit(d->groups.find(g))) << g;
  for (std::size_t i = 0; i < d->atoms.n; ++i) {
    EXPECT_FALSE(d->atoms.mask[i] & d->groups.bit(d->groups.find("other")));
    EXPECT_EQ(d->atoms.type[i], 2);
  }
}

// Periodic x: overlaps are checked through the periodic face (minimum image), tolerance 1e-12.
TEST(InsertPack, PeriodicImagesDoNotOverlap) {
  Deck d;
  d(box(0.05, "p p f") + kOneTemplate +
    "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once "
    "check_dist_from_subdomain_border no volumefraction_region 0.3 region box\nrun 1");
  ASSERT_GT(d->atoms.n, 50u);
  EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);
  // with the LIGGGHTS default (border check on), no grain crosses a box face
  Deck e;
  e(box(0.05, "p p f") + kOneTemplate +
    "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once volumefraction_region 0.2 "
    "region box\nrun 1");
  for (std::size_t i = 0; i < e->atoms.n; ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(e->atoms.x[3 * i + k], 0.0033);
      EXPECT_LE(e->atoms.x[3 * i + k], 0.05 - 0.0033);
    }
}

// sable extension: 2D insertion puts discs at z = 0, mass pi r^2 rho, area fraction.
TEST(InsertPack, TwoDimensionalDiscs) {
  Deck d;
  d(R"(units si
atom_style granular
dimension 2
boundary f f p
region box block 0 0.1 0 0.1 -0.01 0.01 units box
create_box 1 box
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2000 radius constant 0.002
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once volumefraction_region 0.4 region box
fix integr all nve/sphere
fix e2d all enforce2d
run 1)");
  const auto& a = d->atoms;
  const double area = std::numbers::pi * 0.002 * 0.002;
  EXPECT_NEAR(a.n * area, 0.4 * 0.01, area);
  for (std::size_t i = 0; i < a.n; ++i) {
    EXPECT_EQ(a.x[3 * i + 2], 0.0);
    EXPECT_NEAR(a.rmass[i], area * 2000, 1e-12 * area * 2000);
  }
  EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);
}

// 20 000 grains with the overlap check (the cell grid's path): all placed, none
// overlapping. Its speed is a benchmark, input_scripts/bench/insert_pack.sh.
TEST(InsertPack, TwentyThousandGrainsWithoutOverlap) {
  Deck d;
  d(box(0.1) + R"(fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.0013
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once particles_in_region 20000 region box
run 1)");
  EXPECT_EQ(d->atoms.n, 20000u);
  EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);
}

// Fewer than requested when the region is too full: a warning says how many were placed.
TEST(InsertPack, WarnsWhenTheRegionIsTooFull) {
  Deck d;
  const std::string out = sable::test::printed(
      box(0.02) + kOneTemplate +
          "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once particles_in_region 500 "
          "region box\nrun 1",
      d);
  EXPECT_LT(d->atoms.n, 500u);
  EXPECT_NE(out.find("Less insertions than requested"), std::string::npos) << out;
  EXPECT_NE(out.find("of 500 grains"), std::string::npos) << out;
}

// A target far beyond what the region could ever hold (the 1-h fuzz's 2^31) draws no
// more grains than twice what would fill the region packed solid: the run goes on at
// once with the region full and the shortfall warned about, against the full target.
TEST(InsertPack, AbsurdTargetDrawsOnlyWhatCouldFit) {
  Deck d;
  const std::string out = sable::test::printed(
      box(0.02) + kOneTemplate +
          "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once particles_in_region "
          "2147483648 region box\nrun 1",
      d);
  EXPECT_GT(d->atoms.n, 0u);
  EXPECT_NE(out.find("of 2147483648 grains"), std::string::npos) << out;
}

TEST(ParticleTemplate, SeedsAndSyntaxErrors) {
  Deck d;
  d(box(0.1));
  EXPECT_NE(error_of(d, "fix p all particletemplate/sphere 12345 density constant 2500 radius constant 0.001")
                .find("prime number > 10000"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix p all particletemplate/sphere 10007 radius constant 0.001").find("density constant RHO"),
            std::string::npos);
  EXPECT_NE(
      error_of(d, "fix p all particletemplate/sphere 10007 density constant 2500 radius gaussian mass 0.001 0.0001")
          .find("mass-based radius distributions are not implemented"),
      std::string::npos);
  EXPECT_NE(
      error_of(d, "fix p all particletemplate/sphere 10007 density constant 2500 radius gaussian number 0.001 0.001")
          .find("mu - 3 sigma >= 0"),
      std::string::npos);
  EXPECT_NE(
      error_of(d, "fix p all particletemplate/sphere 10007 density constant 2500 radius constant 0.001 atom_type 3")
          .find("between 1 and 2"),
      std::string::npos);
  EXPECT_NE(error_of(d, "fix p all particletemplate/sphere 10007 density constant 2500 radius lognormal 1 2")
                .find("a radius style"),
            std::string::npos);
}

TEST(ParticleDistribution, Errors) {
  Deck d;
  d(box(0.1) + "fix pts1 all particletemplate/sphere 15485863 density constant 2500 radius constant 0.001\n");
  EXPECT_NE(error_of(d, "fix pdd all particledistribution/discrete 32452843 1 nothere 1.0")
                .find("particletemplate/sphere defined earlier"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix pdd all particledistribution/discrete 32452843 2 pts1 1.0").find("2 pairs"),
            std::string::npos);
  EXPECT_NE(
      error_of(d, "fix pdd all particledistribution/discrete 32452843 2 pts1 0.5 pts1 0.5").find("template twice"),
      std::string::npos);
  EXPECT_NE(error_of(d, "fix pdd all particledistribution/discrete 100 1 pts1 1.0").find("prime number > 10000"),
            std::string::npos);
  const std::string warned = sable::test::printed("fix pdd all particledistribution/discrete 32452843 1 pts1 2.0", d);
  EXPECT_NE(warned.find("normalizing distribution"), std::string::npos);
}

TEST(InsertPack, Errors) {
  Deck d;
  d(box(0.1) + kOneTemplate);
  const std::string ok = "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once ";
  EXPECT_NE(error_of(d, ok + "particles_in_region 10 region nowhere").find("an existing region ID"), std::string::npos);
  EXPECT_NE(error_of(d, ok + "particles_in_region 10").find("'region ID'"), std::string::npos);
  EXPECT_NE(error_of(d, ok + "region box").find("exactly one of"), std::string::npos);
  EXPECT_NE(error_of(d, ok + "region box particles_in_region 10 volumefraction_region 0.1").find("exactly one of"),
            std::string::npos);
  EXPECT_NE(
      error_of(d, "fix ins all insert/pack seed 32452867 distributiontemplate pdd1 particles_in_region 10 region box")
          .find("insert_every"),
      std::string::npos);
  EXPECT_NE(error_of(d,
                     "fix ins all insert/pack seed 32452867 distributiontemplate nodist insert_every once region box "
                     "particles_in_region 1")
                .find("particledistribution/discrete defined earlier"),
            std::string::npos);
  EXPECT_NE(error_of(d,
                     "fix ins all insert/pack seed 32452843 distributiontemplate pdd1 insert_every once region box "
                     "particles_in_region 1")
                .find("differ"),
            std::string::npos);
  EXPECT_NE(error_of(d, ok + "region box particles_in_region 10 colour red").find("an insert/pack keyword"),
            std::string::npos);
  EXPECT_NE(error_of(d, ok + "region box volumefraction_region 1.5").find("between 0 and 1"), std::string::npos);
  // the region must outlive the fix (LIGGGHTS: "regions used by this command must not be deleted")
  d("region r2 block 0 0.05 0 0.05 0 0.05 units box\n" + ok + "particles_in_region 10 region r2\nregion r2 delete");
  EXPECT_NE(error_of(d, "run 1").find("region 'r2' was deleted"), std::string::npos);
}

}  // namespace test_insert_pack
