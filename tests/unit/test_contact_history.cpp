// Contact history bookkeeping: named slots, the sign flip when a pair is seen
// as (j, i), survival across neighbour rebuilds and atom sorting, and the two
// reset conventions (sable: at separation; LIGGGHTS 3.8 with
// historyResetAtRebuild on: at the next rebuild). Physics is unchanged by
// rebuilds and sorting, so results must agree with an undisturbed reference
// run to round-off (tolerances 1e-12 relative unless stated).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "contact_models/pair_gran.h"
#include "core/input/style_registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_history {

using sable::test::Deck;
using sable::test::entry_history;

namespace {

std::function<void(sable::Simulation&)> g_probe;
class FixProbe : public sable::Fix {
 public:
  FixProbe(sable::Simulation& s, const sable::Args& a) : Fix(s, a) { hooks = sable::END_OF_STEP; }
  void end_of_step() override {
    if (g_probe) g_probe(sim);
  }
};
SABLE_FIX("test/probe_history", FixProbe);

const char* kHead = R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.7
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.1
timestep 1e-6)";

// Two grains overlapping by 20 um with a sliding relative velocity, frozen in place (no integrator):
// the tangential and rolling springs grow each step, then slip.
void sliding_pair(Deck& d, double x1, double x2) {
  d(kHead);
  d("create_atoms 1 single " + std::to_string(x1) + " 0 0 units box");
  d("create_atoms 1 single " + std::to_string(x2) + " 0.0001 0 units box");
  d("pair_style gran model hertz tangential history rolling_friction epsd2");
  d("pair_coeff * *");
  auto& at = d->atoms;
  for (std::size_t i = 0; i < 2; ++i) {
    at.set_radius_density(i, 0.001, 2500);
    at.v[3 * i + 1] = i ? -0.2 : 0.3;
    at.v[3 * i + 2] = i ? 0.1 : -0.05;
    at.omega[3 * i + 2] = i ? 40.0 : -25.0;
  }
}

// Two grains just touching each other, the floor and the side wall, pressed
// together by gravity, the outer one sliding along y; with `far`, a grain far
// from them created first (id 1).
void pressed_pair(Deck& d, bool far) {
  d(kHead);
  if (far) d("create_atoms 1 single -0.008 0 0.008 units box");
  d("create_atoms 1 single 0.001 0 0.001 units box");
  d("create_atoms 1 single 0.003 0 0.001 units box");
  d("pair_style gran model hertz tangential history rolling_friction epsd2");
  d("pair_coeff * *");
  d("fix floor all wall/gran model hertz tangential history rolling_friction epsd2 primitive type 1 zplane 0.0");
  d("fix side all wall/gran model hertz tangential history rolling_friction epsd2 primitive type 1 xplane 0.0");
  d("fix g all gravity 9.81 vector -1 0 -1");
  d("fix i all nve/sphere");
  auto& at = d->atoms;
  for (std::size_t i = 0; i < at.n; ++i) at.set_radius_density(i, 0.001, 2500);
  at.v[3 * (at.n - 1) + 1] = 0.05;  // the outer grain slides along y
}

double rel(double a, double b) { return std::fabs(a - b) / std::max({std::fabs(a), std::fabs(b), 1e-300}); }

void expect_same_state(Deck& a, Deck& b, double tol) {
  for (long id = 1; id <= static_cast<long>(a->atoms.n); ++id) {
    const std::size_t i = a->atoms.index_of(id), j = b->atoms.index_of(id);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(rel(a->atoms.f[3 * i + k], b->atoms.f[3 * j + k]), tol) << "f of atom " << id << " comp " << k;
      EXPECT_LE(rel(a->atoms.torque[3 * i + k], b->atoms.torque[3 * j + k]), tol) << "torque of atom " << id;
      EXPECT_LE(rel(a->atoms.x[3 * i + k], b->atoms.x[3 * j + k]), tol) << "x of atom " << id;
      EXPECT_LE(rel(a->atoms.v[3 * i + k], b->atoms.v[3 * j + k]), tol) << "v of atom " << id;
    }
  }
}

}  // namespace

TEST(ContactHistory, SlotsAreNamedAndSizedByTheModels) {
  Deck d;
  sliding_pair(d, -0.00099, 0.00099);
  const auto* store = d->pair->history();
  ASSERT_NE(store, nullptr);
  ASSERT_EQ(store->size, 6);
  const char* names[] = {"shearx", "sheary", "shearz", "r_torquex_old", "r_torquey_old", "r_torquez_old"};
  for (int m = 0; m < 6; ++m) {
    EXPECT_EQ(store->slots[m].name, names[m]);
    EXPECT_TRUE(store->slots[m].flip);
  }
  // No history storage at all for a history-free model.
  Deck n;
  n(kHead);
  n("pair_style gran model hertz tangential no_history rolling_friction cdt");
  EXPECT_EQ(n->pair->history(), nullptr);
}

// Grain 1 sits right of grain 2, so sorting by bin puts grain 2 first: the pair
// that was stored as (1, 2) is then seen as (2, 1) and every slot must change
// sign, or the spring would push the wrong way and the force would jump.
TEST(ContactHistory, SignFlipsWhenThePairIsSeenReversed) {
  Deck ref, flip;
  for (Deck* d : {&ref, &flip}) {
    sliding_pair(*d, 0.00099, -0.00099);
    (*d)("atom_modify sort 0 0");
    (*d)("run 8");
    ASSERT_EQ((*d)->atoms.index_of(1), 0u);  // unsorted: creation order
  }
  const std::vector<double> before = entry_history(*ref->pair->history());
  flip("atom_modify sort 1 0.001");
  ref("run 8");
  flip("run 8");
  ASSERT_EQ(flip->atoms.index_of(1), 1u) << "the sort should have reversed the pair";
  const auto& hr = entry_history(*ref->pair->history());
  const auto& hf = entry_history(*flip->pair->history());
  ASSERT_EQ(hr.size(), 6u);
  ASSERT_EQ(hf.size(), 6u);
  int moving = 0;
  for (int m = 0; m < 6; ++m) {
    moving += before[m] != hr[m];
    EXPECT_LE(rel(hf[m], -hr[m]), 1e-12) << "slot " << m;
  }
  EXPECT_GE(moving, 3) << "the springs should have moved on during the second run";
  expect_same_state(ref, flip, 1e-12);
}

// Two grains in a corner (floor + side wall), pushed together by tilted
// gravity; the outer one slides along y against the inner one, so their
// tangential and rolling springs stay loaded. The list is rebuilt (and atoms
// re-sorted) every step in one run and never in the other.
TEST(ContactHistory, SurvivesNeighbourRebuildsDuringASlidingContact) {
  Deck never, every;
  for (Deck* d : {&never, &every}) {
    pressed_pair(*d, false);
    (*d)("fix p all test/probe_history");
  }
  never("neighbor 0.005 bin");
  every("neigh_modify every 1 check no");
  long touching_steps = 0;
  g_probe = [&](sable::Simulation& s) { touching_steps += (s.pair->history()->history(0) != nullptr); };
  every("run 2000");
  EXPECT_GT(touching_steps, 1500) << "the grains should stay in contact";
  touching_steps = 0;
  never("run 2000");
  g_probe = nullptr;
  EXPECT_GT(touching_steps, 1500);
  EXPECT_GT(every->neighbor.builds, 1900);
  EXPECT_LE(never->neighbor.builds, 1);
  EXPECT_GT(std::fabs(entry_history(*every->pair->history())[1]), 1e-9) << "a loaded tangential spring";
  expect_same_state(never, every, 1e-9);  // round-off growth over 2000 steps only
}

// Wall history is kept by grain id (core's HistoryStore), so it follows the
// atoms when the neighbour build sorts them.
TEST(ContactHistory, WallHistorySurvivesAtomSorting) {
  Deck sorted, unsorted;
  for (Deck* d : {&sorted, &unsorted}) {
    (*d)(kHead);
    // Created right to left: sorting by bin reverses the order.
    for (int k = 4; k >= 0; --k) (*d)("create_atoms 1 single " + std::to_string(-0.008 + 0.004 * k) + " 0 0.00099 units box");
    (*d)("pair_style gran model hertz tangential history rolling_friction epsd2");
    (*d)("pair_coeff * *");
    (*d)("fix w all wall/gran model hertz tangential history rolling_friction epsd2 primitive type 1 zplane 0.0");
    (*d)("fix g all gravity 9.81 vector 0 0 -1");
    (*d)("fix i all nve/sphere");
    (*d)("neigh_modify every 1 check no");
    auto& at = (*d)->atoms;
    for (std::size_t i = 0; i < at.n; ++i) {
      at.set_radius_density(i, 0.001, 2500);
      at.v[3 * i] = 0.02 * (1 + static_cast<double>(i));  // each grain slides (then rolls) on the floor
      at.omega[3 * i + 2] = 10.0 * static_cast<double>(i);
    }
  }
  unsorted("atom_modify sort 0 0");
  sorted("run 3000");
  unsorted("run 3000");
  EXPECT_EQ(unsorted->atoms.index_of(1), 0u);
  EXPECT_EQ(sorted->atoms.index_of(1), 4u) << "sorting should have reversed the atoms";
  expect_same_state(sorted, unsorted, 1e-12);
}

// delete_atoms with compress yes renumbers the grains between runs: the pair's
// and the walls' springs follow the new ids, so the run goes on as with
// compress no (same grains, other ids). Before the history store was keyed by
// (grain, partner, element) with renumbering, the pair spring was lost here.
TEST(ContactHistory, FollowsGrainsRenumberedByDeleteAtoms) {
  Deck kept, compressed;
  for (Deck* d : {&kept, &compressed}) {
    pressed_pair(*d, true);
    (*d)("run 1000");
    (*d)("group far id 1");
  }
  const sable::ContactStore& store = *kept->pair->history();
  ASSERT_EQ(store.contacts(), 1u) << "the two grains should touch";
  kept("delete_atoms group far compress no");
  compressed("delete_atoms group far compress yes");
  ASSERT_EQ(compressed->atoms.index_of(3), sable::Atoms::npos) << "compress yes should renumber 2, 3 to 1, 2";
  kept("run 1000");
  compressed("run 1000");
  EXPECT_GT(std::fabs(entry_history(*compressed->pair->history())[1]), 1e-9) << "a loaded tangential spring";
  for (long id = 2; id <= 3; ++id) {
    const std::size_t i = kept->atoms.index_of(id), j = compressed->atoms.index_of(id - 1);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(rel(kept->atoms.x[3 * i + k], compressed->atoms.x[3 * j + k]), 1e-12) << "x of grain " << id;
      EXPECT_LE(rel(kept->atoms.f[3 * i + k], compressed->atoms.f[3 * j + k]), 1e-12) << "f of grain " << id;
      EXPECT_LE(rel(kept->atoms.torque[3 * i + k], compressed->atoms.torque[3 * j + k]), 1e-12) << "torque of " << id;
    }
  }
}

// A grain hops off a fixed grain and lands again within the skin (no rebuild in
// between). sable forgets the spring at separation; LIGGGHTS 3.8 (and sable
// with historyResetAtRebuild on) keeps it until the next rebuild.
TEST(ContactHistory, ResetAtSeparationOrAtRebuild) {
  auto hop = [](const std::string& keyword, std::vector<double>& shear_y, std::vector<int>& touching,
                std::vector<long>& builds) {
    Deck d;
    d(kHead);
    // Grain 2 rests on grain 1 at the static Hertz overlap (R* = r/2, only grain 2 feels gravity).
    const double m = 4.0 / 3.0 * 3.141592653589793 * 1e-9 * 2500, ys = 5e7 / (2 * (1 - 0.09));
    const double d0 = std::pow(3 * m * 9.81 / (4 * ys * std::sqrt(0.0005)), 2.0 / 3.0);
    d("create_atoms 1 single 0 0 0 units box");
    d("create_atoms 1 single 0 0 " + std::to_string(0.002 - d0) + " units box");
    d("pair_style gran model hertz tangential history " + keyword);
    d("pair_coeff * *");
    d("group top id 2");
    d("fix g top gravity 9.81 vector 0 0 -1");
    d("fix i top nve/sphere");
    d("fix p all test/probe_history");
    auto& at = d->atoms;
    for (std::size_t i = 0; i < 2; ++i) at.set_radius_density(i, 0.001, 2500);
    at.v[3] = 0.01;   // sliding ...
    at.v[5] = 0.02;   // ... and hopping off
    g_probe = [&](sable::Simulation& s) {
      const auto& h = entry_history(*s.pair->history());
      shear_y.push_back(std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]));
      const std::size_t a = s.atoms.index_of(1), b = s.atoms.index_of(2);
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(s.atoms.x[3 * a + k] - s.atoms.x[3 * b + k], 2);
      touching.push_back(d2 < 0.002 * 0.002);
      builds.push_back(s.neighbor.builds);
    };
    d("run 8000");
    g_probe = nullptr;
  };
  std::vector<double> sable_y, lig_y;
  std::vector<int> t1, t2;
  std::vector<long> b1, b2;
  hop("", sable_y, t1, b1);
  hop("historyResetAtRebuild on", lig_y, t2, b2);
  // Find the flight: last contact step, then the first step touching again.
  std::size_t off = 0, on = 0;
  for (std::size_t k = 1; k < t1.size(); ++k) {
    if (t1[k - 1] && !t1[k] && !off) off = k;
    if (off && !t1[k - 1] && t1[k]) {
      on = k;
      break;
    }
  }
  ASSERT_GT(off, 0u);
  ASSERT_GT(on, off);
  ASSERT_EQ(b1[off - 1], b1[on]) << "no neighbour rebuild during the flight";
  for (std::size_t k = 0; k < off; ++k) ASSERT_EQ(t1[k], t2[k]);
  EXPECT_EQ(sable_y[off], 0.0) << "sable zeroes the spring when the grains separate";
  EXPECT_NE(lig_y[off], 0.0) << "LIGGGHTS keeps it while the pair stays in the list";
  EXPECT_EQ(lig_y[on - 1], lig_y[off]) << "and leaves it untouched during the flight";
  EXPECT_NE(sable_y[on], lig_y[on]) << "so the landing starts from a different spring";
}

}  // namespace test_contact_history
