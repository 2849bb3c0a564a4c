// fix insert/rate/region: grains per insertion from the rate (LIGGGHTS 3.8:
// int(R K dt + u)), the stop at nparticles / mass, start, placement without
// overlap inside the region, velocities, restart continuity and bad input.
// The expected counts follow from the documented formula; the LIGGGHTS runs
// that confirmed it are quoted where used.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>

#include "core/engine/error.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_insert_rate_region {

using sable::test::Deck;
using sable::test::error_of;

namespace {

// Box [0, 0.1]^3, one grain kind (r = 1 mm, 2500 kg/m^3), no contacts, no
// gravity: inserted grains stay where they were put.
const char* kBox = R"(units si
atom_style granular
boundary f f f
region box block 0 0.1 0 0.1 0 0.1 units box
create_box 1 box
fix integr all nve/sphere
timestep 1e-4
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.001
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
region ins block 0 0.1 0 0.1 0 0.1 units box
)";

const double kGrainMass = 4.0 / 3.0 * std::numbers::pi * 1e-9 * 2500;

double count(Deck& d) { return d->find_fix("ins")->compute_vector(1); }

// Smallest d_ij / (r_i + r_j) over all pairs (brute force).
double min_gap_ratio(const sable::Simulation& s) {
  const auto& a = s.atoms;
  double worst = 1e300;
  for (std::size_t i = 0; i < a.n; ++i)
    for (std::size_t j = i + 1; j < a.n; ++j) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(a.x[3 * i + k] - a.x[3 * j + k], 2);
      worst = std::min(worst, std::sqrt(d2) / (a.radius[i] + a.radius[j]));
    }
  return worst;
}

}  // namespace

// R K dt = 1000 * 100 * 1e-4 = 10 grains at steps 1, 101, ..., 901, then stop at
// 100 (LIGGGHTS 3.8 with this deck: 10 at each of those steps, 100 in all).
TEST(InsertRateRegion, WholeNumberPerInsertionUntilTheTotal) {
  Deck d;
  d(kBox)(
      "fix ins all insert/rate/region seed 49979687 distributiontemplate pdd nparticles 100 particlerate 1000 "
      "insert_every 100 region ins");
  d("run 1");
  EXPECT_EQ(d->atoms.n, 10u);
  d("run 99");
  EXPECT_EQ(d->atoms.n, 10u);  // nothing between insertions
  d("run 1");
  EXPECT_EQ(d->atoms.n, 20u);
  d("run 1000");
  EXPECT_EQ(d->atoms.n, 100u);
  EXPECT_EQ(count(d), 100.0);
  EXPECT_NEAR(d->find_fix("ins")->compute_vector(2), 100 * kGrainMass, 1e-12 * 100 * kGrainMass);
  EXPECT_EQ(d->atoms.max_id, 100);
  EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);  // overlapcheck yes is the default
}

// R K dt = 12.34: each insertion is 12 or 13 grains (int(12.34 + u)), 12.34 on
// average; the last one is cut to what is left of the total.
TEST(InsertRateRegion, FractionalRateRoundsAtRandomAndTheLastIsCut) {
  Deck d;
  d(kBox)(
      "fix ins all insert/rate/region seed 49979687 distributiontemplate pdd nparticles 2000 particlerate 1234 "
      "insert_every 100 region ins");
  std::vector<long> per;
  long before = 0;
  for (int k = 0; k < 200 && before < 2000; ++k) {
    d("run 100");
    per.push_back(static_cast<long>(d->atoms.n) - before);
    before = static_cast<long>(d->atoms.n);
  }
  ASSERT_EQ(d->atoms.n, 2000u);
  EXPECT_EQ(d->find_fix("ins")->compute_vector(1), 2000.0);
  double sum = 0;
  for (std::size_t k = 0; k + 1 < per.size(); ++k) {
    EXPECT_TRUE(per[k] == 12 || per[k] == 13) << k << ": " << per[k];
    sum += per[k];
  }
  EXPECT_GE(per.back(), 1);
  EXPECT_LE(per.back(), 13);
  const double n = static_cast<double>(per.size() - 1);  // about 2000 / 12.34 = 162 full insertions
  EXPECT_NEAR(n, 2000 / 12.34, 2);
  // Mean of n draws of 12 + Bernoulli(0.34): sd of the mean 0.474 / sqrt(162) = 0.037; 4 sd.
  EXPECT_NEAR(sum / n, 12.34, 4 * 0.037);
}

// mass M: N = int(M / grain mass) (LIGGGHTS: mass 0.0007 with 1.047e-5 kg grains
// inserted 66); massrate MR: R = MR / grain mass.
TEST(InsertRateRegion, MassAndMassRate) {
  Deck d;
  d(kBox)(
      "fix ins all insert/rate/region seed 49979687 distributiontemplate pdd mass 0.0007 massrate 0.01 "
      "insert_every 100 region ins");
  d("run 3000");
  EXPECT_EQ(d->atoms.n, static_cast<std::size_t>(0.0007 / kGrainMass));
  Deck e;
  e(kBox)(
      "fix ins all insert/rate/region seed 49979687 distributiontemplate pdd nparticles INF massrate 0.01 "
      "insert_every 100 region ins");
  e("run 1");
  const double per = 0.01 / kGrainMass * 100 * 1e-4;  // 9.55
  EXPECT_TRUE(e->atoms.n == std::floor(per) || e->atoms.n == std::ceil(per)) << e->atoms.n;
  e("run 4000");  // INF: it goes on inserting
  EXPECT_NEAR(static_cast<double>(e->atoms.n), 41 * per, 4 * std::sqrt(41 * 0.25));
}

TEST(InsertRateRegion, StartStepAndVelocity) {
  Deck d;
  d(kBox)(
      "fix ins all insert/rate/region seed 49979687 distributiontemplate pdd nparticles 30 particlerate 1000 "
      "insert_every 100 start 50 vel constant 0.1 -0.2 0.3 region ins");
  d("run 49");
  EXPECT_EQ(d->atoms.n, 0u);
  d("run 1");
  ASSERT_EQ(d->atoms.n, 10u);
  for (std::size_t i = 0; i < d->atoms.n; ++i) {
    EXPECT_EQ(d->atoms.v[3 * i + 0], 0.1);
    EXPECT_EQ(d->atoms.v[3 * i + 1], -0.2);
    EXPECT_EQ(d->atoms.v[3 * i + 2], 0.3);
  }
}

// all_in yes keeps whole grains inside a cylinder; none overlaps a grain already there.
TEST(InsertRateRegion, AllInCylinderWithoutOverlap) {
  Deck d;
  d(kBox)(R"(region cyl cylinder z 0.05 0.05 0.02 0.02 0.06 units box
fix ins all insert/rate/region seed 49979687 distributiontemplate pdd nparticles 600 particlerate 2000 insert_every 100 all_in yes region cyl
run 3100)");
  const auto& a = d->atoms;
  ASSERT_EQ(a.n, 600u);
  EXPECT_GE(min_gap_ratio(*d), 1.0 - 1e-12);
  for (std::size_t i = 0; i < a.n; ++i) {
    const double rho = std::hypot(a.x[3 * i] - 0.05, a.x[3 * i + 1] - 0.05);
    EXPECT_LE(rho + a.radius[i], 0.02 + 1e-12);
    EXPECT_GE(a.x[3 * i + 2] - a.radius[i], 0.02 - 1e-12);
    EXPECT_LE(a.x[3 * i + 2] + a.radius[i], 0.06 + 1e-12);
  }
}

// A region too small for the rate: each insertion still asks for R K dt grains
// (no carry-over of what did not fit) and warns, until the total is in or never
// (LIGGGHTS 3.8 in a 5 mm cube: 10, 8, 2, 0, 0, ... with warnings).
TEST(InsertRateRegion, ShortfallIsNotCarriedOver) {
  Deck d;
  d(kBox)("region small block 0.04 0.045 0.04 0.045 0.04 0.045 units box");
  const std::string out = sable::test::printed(
      "fix ins all insert/rate/region seed 49979687 distributiontemplate pdd nparticles 30 particlerate 1000 "
      "insert_every 100 region small\nrun 1000",
      d);
  EXPECT_LT(d->atoms.n, 30u);
  EXPECT_NE(out.find("Less insertions than requested"), std::string::npos) << out;
  EXPECT_NE(out.find("placed 0 of 10 grains"), std::string::npos) << out;
}

// Same seed, same grains; a run split by write_restart/read_restart continues
// the insertion exactly (next step, counters, random streams).
TEST(InsertRateRegion, SameSeedSameGrainsAndRestartContinues) {
  const std::string fix =
      "fix ins all insert/rate/region seed 49979687 distributiontemplate pdd nparticles 200 particlerate 1234 "
      "insert_every 100 vel uniform 0 0 0 0.001 0.001 0.001 region ins\n";
  Deck a, b;
  a(kBox)(fix)("run 1000")("run 1000");
  b(kBox)(fix)("run 1000")("run 1000");
  ASSERT_EQ(a->atoms.n, 200u);
  EXPECT_EQ(0, std::memcmp(a->atoms.x.data(), b->atoms.x.data(), 3 * a->atoms.n * sizeof(double)));

  const auto file = std::filesystem::temp_directory_path() / ("sable_rate_" + std::to_string(::getpid()) + ".restart");
  Deck c;
  c(kBox)(fix)("run 1000")("write_restart " + file.string());
  ASSERT_LT(c->atoms.n, 200u);
  Deck r;
  r("units si\natom_style granular\nread_restart " + file.string());
  std::filesystem::remove(file);
  r(R"(fix integr all nve/sphere
timestep 1e-4
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.001
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
region ins block 0 0.1 0 0.1 0 0.1 units box
)")(fix)("run 1000");
  ASSERT_EQ(r->atoms.n, a->atoms.n);
  EXPECT_EQ(0, std::memcmp(a->atoms.x.data(), r->atoms.x.data(), 3 * a->atoms.n * sizeof(double)));
  EXPECT_EQ(0, std::memcmp(a->atoms.v.data(), r->atoms.v.data(), 3 * a->atoms.n * sizeof(double)));
  EXPECT_EQ(r->find_fix("ins")->compute_vector(1), 200.0);
}

// The LIGGGHTS 3.8 rules (its messages: 'insert_every' = once not allowed,
// must define 'insert_every', either 'nparticles' or 'mass', either 'massrate'
// or 'particlerate', not both).
TEST(InsertRateRegion, Errors) {
  Deck d;
  d(kBox);
  const std::string ok = "fix ins all insert/rate/region seed 49979687 distributiontemplate pdd region ins ";
  auto has = [&](const std::string& tail, const std::string& text) {
    const std::string e = error_of(d, ok + tail);
    EXPECT_NE(e.find(text), std::string::npos) << tail << " -> " << e;
    EXPECT_NE(e.find("test:1"), std::string::npos) << e;
  };
  has("nparticles 10 particlerate 10 insert_every once", "not 'once'");
  has("nparticles 10 particlerate 10", "'insert_every N'");
  has("particlerate 10 insert_every 10", "exactly one of 'nparticles N|INF' and 'mass M|INF'");
  has("nparticles 10 mass 1 particlerate 10 insert_every 10", "exactly one of 'nparticles");
  has("nparticles 10 insert_every 10", "exactly one of 'particlerate R' and 'massrate MR'");
  has("nparticles 10 particlerate 10 massrate 1 insert_every 10", "exactly one of 'particlerate");
  has("nparticles 0 particlerate 10 insert_every 10", "a number of particles >= 1 or INF");
  has("nparticles 10 particlerate -1 insert_every 10", "a rate > 0");
  has("nparticles 10 particlerate 10 insert_every 10 volumefraction_region 0.3", "an insert/rate/region keyword");
}

}  // namespace test_insert_rate_region
