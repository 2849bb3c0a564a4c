// fix heat/gran (LIGGGHTS 3.8 heat conduction through contacts), fix property/atom,
// set ... property/atom, f_ID per-atom values in compute reduce.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "contact_models/heat_conduction.h"
#include "core/engine/error.h"
#include "core/engine/threads.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_heat_gran {

using sable::test::Deck;
using sable::test::error_of;

namespace {

constexpr double kPi = std::numbers::pi;

// Two resting grains of different types (radius 4 and 3 mm, 8000 and 4000 kg/m^3,
// conductivity 100 and 20 W/(m K), capacity 10 and 30 J/(kg K)) overlapping by 0.2 mm,
// at 300 and 800 K. No integrator: they do not move.
const char* kTwoGrains = R"(units si
atom_style granular
atom_modify map array
boundary f f f
newton off
region reg block -0.05 0.05 -0.05 0.05 -0.05 0.05 units box
create_box 2 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.7 0.7 0.7 0.7
fix m4 all property/global coefficientFriction peratomtypepair 2 0.05 0.05 0.05 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.000025
fix ftco all property/global thermalConductivity peratomtype 100. 20.
fix ftca all property/global thermalCapacity peratomtype 10. 30.
create_atoms 1 single 0 0 0 units box
create_atoms 2 single 0.0068 0 0 units box
set atom 1 diameter 0.008 density 8000
set atom 2 diameter 0.006 density 4000
)";
constexpr double kR = 0.0068, kRi = 0.004, kRj = 0.003, kDt = 0.000025;
constexpr double kKi = 100, kKj = 20, kCi = 10, kCj = 30;
const double kMi = 4.0 / 3.0 * kPi * kRi * kRi * kRi * 8000, kMj = 4.0 / 3.0 * kPi * kRj * kRj * kRj * 4000;

// The contact conductance from the geometry alone: the spheres meet on a circle at
// distance x from i's centre, radius a^2 = ri^2 - x^2 (Chaudhuri et al. 2006 as in
// LIGGGHTS' doc: h_c = 4 ki kj / (ki + kj) sqrt(A), A = pi a^2).
double conductance() {
  const double x = (kR * kR + kRi * kRi - kRj * kRj) / (2 * kR);
  const double area = kPi * (kRi * kRi - x * x);
  return 4 * kKi * kKj / (kKi + kKj) * std::sqrt(area);
}

double column(Deck& d, const char* name, long id) {
  const auto& at = d->atoms;
  return at.column(at.find_column(name))[at.index_of(id)];
}

}  // namespace

// The area formula of the law agrees with the intersection circle (1e-12 relative), the
// other modes are LIGGGHTS' (projection: the larger grain's cross-section).
TEST(HeatGran, ContactAreaModes) {
  using H = sable::HeatConduction;
  const double x = (kR * kR + kRi * kRi - kRj * kRj) / (2 * kR);
  const double a = kPi * (kRi * kRi - x * x);
  EXPECT_NEAR(H::contact_area(kR, kRi, kRj, H::Area::Overlap, 0), a, 1e-12 * a);
  EXPECT_NEAR(H::contact_area(kR, kRj, kRi, H::Area::Overlap, 0), a, 1e-12 * a);  // symmetric
  EXPECT_DOUBLE_EQ(H::contact_area(kR, kRi, kRj, H::Area::Projection, 0), kPi * kRi * kRi);
  EXPECT_EQ(H::contact_area(kR, kRi, kRj, H::Area::Constant, 2e-6), 2e-6);
  EXPECT_EQ(H::conductance(0.0, 20, a), 0.0);  // a non-conducting type stops the flow
}

// One step: the flow into the cold grain is h_c (T_j - T_i) from the geometry (1e-12
// relative), the hot grain loses exactly as much, and each temperature moves by
// Q dt / (m c) (1e-12 relative).
TEST(HeatGran, TwoGrainsExchangeAtTheFormulaRate) {
  Deck d;
  d(std::string(kTwoGrains) + R"(fix heattransfer all heat/gran initial_temperature 300.
set atom 2 property/atom Temp 800.
run 1)");
  const double q = conductance() * 500.0;
  EXPECT_NEAR(column(d, "f_heatFlux", 1), q, 1e-12 * q);
  EXPECT_EQ(column(d, "f_heatFlux", 2), -column(d, "f_heatFlux", 1));
  EXPECT_NEAR(column(d, "f_Temp", 1), 300 + q * kDt / (kMi * kCi), 1e-12 * 300);
  EXPECT_NEAR(column(d, "f_Temp", 2), 800 - q * kDt / (kMj * kCj), 1e-12 * 800);
}

// 4000 steps (0.1 s): the difference decays as (1 - lambda dt)^n, lambda = h_c (1/(mi ci) +
// 1/(mj cj)) (forward Euler, 1e-9 relative), which is the exponential exp(-lambda t) to
// within n (lambda dt)^2 / 2 = 1.7e-4 relative (bound 5e-4). The total heat sum c m T
// (f_ID) stays the same to round-off (1e-12 relative). LIGGGHTS 3.8 on this same deck
// (dump of f_Temp[0] at step 4000, /tmp two-grain run, 17 digits) gave 433.53021648533627
// and 588.9892875293491 K: equal to 1e-9 relative.
TEST(HeatGran, TemperaturesRelaxAsTheExponential) {
  Deck d;
  d(std::string(kTwoGrains) + R"(fix heattransfer all heat/gran initial_temperature 300.
set atom 2 property/atom Temp 800.
run 0)");
  const double e0 = d->find_fix("heattransfer")->compute_scalar();
  EXPECT_NEAR(e0, kCi * kMi * 300 + kCj * kMj * 800, 1e-12 * e0);
  d("run 4000");
  const double lambda = conductance() * (1 / (kMi * kCi) + 1 / (kMj * kCj));
  const double t1 = column(d, "f_Temp", 1), t2 = column(d, "f_Temp", 2);
  const double euler = 500 * std::pow(1 - lambda * kDt, 4000);
  EXPECT_NEAR(t2 - t1, euler, 1e-9 * 500);
  const double exact = 500 * std::exp(-lambda * 4000 * kDt);
  EXPECT_NEAR(t2 - t1, exact, 5e-4 * exact);
  EXPECT_NEAR(d->find_fix("heattransfer")->compute_scalar(), e0, 1e-12 * e0);
  EXPECT_NEAR(t1, 433.53021648533627, 1e-9 * 433.5);
  EXPECT_NEAR(t2, 588.9892875293491, 1e-9 * 589.0);
}

// A heat source Q alone raises T by Q dt / (m c) per step: 1.5 W for 1000 steps.
TEST(HeatGran, HeatSourceHeatsLinearly) {
  Deck d;
  d(std::string(kTwoGrains) + R"(set atom 2 x 0.02
fix heattransfer all heat/gran initial_temperature 300.
set atom 1 property/atom heatSource 1.5
run 1000)");
  EXPECT_NEAR(column(d, "f_Temp", 1), 300 + 1.5 * 1000 * kDt / (kMi * kCi), 1e-12 * 300);
  EXPECT_EQ(column(d, "f_Temp", 2), 300.0);
}

// Grains outside the fix's group keep their temperature but still conduct to grains in
// it (LIGGGHTS' rule); the fix's scalar counts every grain.
TEST(HeatGran, GrainsOutsideTheGroupKeepTheirTemperature) {
  Deck d;
  d(std::string(kTwoGrains) + R"(group hot id 2
fix heattransfer hot heat/gran initial_temperature 300.
set atom 2 property/atom Temp 800.
run 1)");
  const double q = conductance() * 500.0;
  EXPECT_EQ(column(d, "f_Temp", 1), 300.0);
  EXPECT_NEAR(column(d, "f_Temp", 2), 800 - q * kDt / (kMj * kCj), 1e-12 * 800);
}

// Grains created after the fix start at T0; f_Temp feeds compute reduce and dumps;
// fix property/atom values start at their default and are set by `set`.
TEST(HeatGran, PerAtomValuesInComputesAndSet) {
  Deck d;
  d(std::string(kTwoGrains) + R"(fix heattransfer all heat/gran initial_temperature 350.
create_atoms 1 single 0.03 0 0 units box
set atom 3 diameter 0.008 density 8000
set atom 2 property/atom Temp 800.
compute tm all reduce ave f_Temp[0]
compute tx all reduce max f_Temp
fix tag all property/atom tag scalar yes no no 7.
fix vec all property/atom vec vector yes no no 0. 0.
set atom 1 property/atom tag 3. property/atom vec 1. 2.
compute ts all reduce sum f_tag f_vec[2]
run 0)");
  EXPECT_NEAR(d->find_compute("tm")->compute_scalar(), (350 + 800 + 350) / 3.0, 1e-12 * 500);
  EXPECT_EQ(d->find_compute("tx")->compute_scalar(), 800.0);
  EXPECT_EQ(d->find_compute("ts")->compute_vector(1), 3.0 + 7.0 + 7.0);
  EXPECT_EQ(d->find_compute("ts")->compute_vector(2), 2.0);
}

// Wrong inputs name the word and what was expected.
TEST(HeatGran, BadInputs) {
  {
    Deck d;
    d(kTwoGrains);
    EXPECT_NE(error_of(d, "fix h all heat/gran 300").find("initial_temperature"), std::string::npos);
  }
  {
    Deck d;
    d(kTwoGrains);
    EXPECT_NE(error_of(d, "fix h all heat/gran initial_temperature 300 contact_area sphere").find("overlap, projection or constant"),
              std::string::npos);
  }
  {
    Deck d;
    d(kTwoGrains);
    EXPECT_NE(error_of(d, "fix h all heat/gran initial_temperature 300 area_correction yes").find("area_correction"),
              std::string::npos);
  }
  {
    Deck d;
    d(kTwoGrains);
    d("fix h all heat/gran initial_temperature 300");
    EXPECT_NE(error_of(d, "set atom 1 property/atom Tmp 800").find("no 'Tmp'"), std::string::npos);
    EXPECT_NE(error_of(d, "compute c all reduce ave f_Tmp").find("no fix 'Tmp'"), std::string::npos);
  }
  {
    Deck d;
    d(std::string(kTwoGrains) + "unfix ftco\nfix h all heat/gran initial_temperature 300");
    EXPECT_NE(error_of(d, "run 1").find("thermalConductivity"), std::string::npos);
  }
}

namespace {

// A settling bed of 150 grains, half of it then set hot (tests/decks/heat_bed.in, shorter).
const char* kBed = R"(atom_style granular
atom_modify map array
boundary m m m
newton off
units si
region reg block -0.05 0.05 -0.05 0.05 0. 0.06 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.7
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.000025
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zwalls1 all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix cylwalls all wall/gran model hertz tangential history primitive type 1 zcylinder 0.03 0. 0.
fix ftco all property/global thermalConductivity peratomtype 100.
fix ftca all property/global thermalCapacity peratomtype 10.
fix heattransfer all heat/gran initial_temperature 300.
region bc cylinder z 0. 0. 0.025 0.00 0.06 units box
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 8000 radius constant 0.004
fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 vel constant 0. 0. -0.3 insert_every once overlapcheck yes all_in yes particles_in_region 150 region bc
fix integr all nve/sphere
run 1
unfix ins
run 3000
region halfbed block 0 INF INF INF INF INF units box
set region halfbed property/atom Temp 800.
run 2000
)";

std::map<long, double> bed_temperatures(int threads) {
  sable::ThreadSettings& ts = sable::thread_settings();
  const sable::ThreadSettings saved = ts;
  ts.pair_atoms = ts.pair_entries = ts.loop_work = 0;  // every loop threaded, the heat pass too
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
#endif
  Deck d;
  d(kBed);
  ts = saved;
#ifdef _OPENMP
  omp_set_num_threads(before);
#endif
  std::map<long, double> t;
  const auto& at = d->atoms;
  const auto& col = at.column(at.find_column("f_Temp"));
  for (std::size_t i = 0; i < at.n; ++i) t[at.id[i]] = col[i];
  return t;
}

}  // namespace

// The heat pass runs on the contact loop's threads: every grain's temperature has the
// same bits for 1, 2 and 3 threads (memcmp), and conduction did happen.
TEST(HeatGran, SameBitsForAnyThreadCount) {
  const auto one = bed_temperatures(1);
  bool moved = false;
  for (auto& [id, t] : one) moved = moved || (t != 300.0 && t != 800.0);
  EXPECT_TRUE(moved);
  for (int threads : {2, 3}) {
    const auto other = bed_temperatures(threads);
    ASSERT_EQ(one.size(), other.size());
    for (auto& [id, t] : one)
      EXPECT_EQ(std::memcmp(&t, &other.at(id), sizeof t), 0) << "atom " << id << " with " << threads << " threads";
  }
}

// Conduction during impacts and rolling contacts against LIGGGHTS 3.8: a grain at 800 K
// rests on the floor, a second falls onto it from 2 cm, a third rolls into the pair;
// after 12000 steps (0.3 s) LIGGGHTS 3.8 (same deck, dump f_Temp[0] at %.17g) gives
// 777.66346631588567, 321.79977351570005, 300.5367601684145 K: equal to 1e-12 relative
// (sable differs in the last digit or not at all).
TEST(HeatGran, ImpactsMatchLiggghts) {
  Deck d;
  d(R"(atom_style granular
atom_modify map array
boundary f f f
newton off
units si
region reg block -0.05 0.05 -0.05 0.05 0. 0.15 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.7
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.000025
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zwalls1 all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix ftco all property/global thermalConductivity peratomtype 100.
fix ftca all property/global thermalCapacity peratomtype 10.
fix heattransfer all heat/gran initial_temperature 300.
create_atoms 1 single 0 0 0.004 units box
create_atoms 1 single 0.003 0.001 0.02 units box
create_atoms 1 single 0.03 0.0 0.004 units box
set atom * diameter 0.008 density 8000
velocity all set 0 0 0 units box
set atom 3 vx -0.2
fix integr all nve/sphere
run 0
set atom 1 property/atom Temp 800.
run 12000)");
  EXPECT_NEAR(column(d, "f_Temp", 1), 777.66346631588567, 1e-12 * 800);
  EXPECT_NEAR(column(d, "f_Temp", 2), 321.79977351570005, 1e-12 * 800);
  EXPECT_NEAR(column(d, "f_Temp", 3), 300.5367601684145, 1e-12 * 800);
}

}  // namespace test_heat_gran
