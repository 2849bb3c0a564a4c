// fix wall/gran primitives: force on the wall (f_ID), planes acting on both
// sides, cylinders, shear (planes and spinning cylinders) and wiggle, checked
// against statics and rigid-body mechanics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include "core/engine/compute.h"
#include "core/input/style_registry.h"
#include "fixes/fix_wall_gran.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_wall_gran {

using sable::test::Deck;

namespace {

constexpr double kPi = std::numbers::pi;
const double kR = 0.001, kRho = 2500, kM = 4.0 / 3.0 * kPi * kR * kR * kR * kRho;

std::function<void(sable::Simulation&)> g_probe;
class FixProbe : public sable::Fix {
 public:
  FixProbe(sable::Simulation& s, const sable::Args& a) : Fix(s, a) { hooks = sable::END_OF_STEP; }
  void end_of_step() override {
    if (g_probe) g_probe(sim);
  }
};
SABLE_FIX("test/probe_wall", FixProbe);

const char* kHead = R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6)";

void grains(Deck& d) {
  for (std::size_t i = 0; i < d->atoms.n; ++i) d->atoms.set_radius_density(i, kR, kRho);
}

double fwall(Deck& d, const char* id, int k) { return d->find_fix(id)->compute_vector(k); }

}  // namespace

// Three grains at rest on a floor: the floor carries their weight, f_ID = (0, 0, -3 m g).
TEST(WallGran, ForceOnTheWallBalancesTheWeight) {
  Deck d;
  d(kHead);
  d(R"(create_atoms 1 single -0.004 0 0.001 units box
create_atoms 1 single 0 0 0.001 units box
create_atoms 1 single 0.004 0 0.001 units box
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere)");
  grains(d);
  d("run 20000");
  const double w = 3 * kM * 9.81;
  EXPECT_NEAR(fwall(d, "floor", 3), -w, 1e-3 * w);  // settled: residual oscillation < 0.1 %
  EXPECT_NEAR(fwall(d, "floor", 1), 0.0, 1e-9);
  // Reading f_floor[3] from the deck language works as for any fix vector.
  d("variable fz equal f_floor[3]");
}

// A plane acts on grains on both sides, pushing each away from it.
TEST(WallGran, PlaneActsOnBothSides) {
  Deck d;
  d(kHead);
  d(R"(create_atoms 1 single -0.00099 0 0 units box
create_atoms 1 single 0.0009 0 0.004 units box
fix w all wall/gran model hertz tangential history primitive type 1 xplane 0.0)");
  grains(d);
  d("run 0");
  const std::size_t left = d->atoms.index_of(1), right = d->atoms.index_of(2);
  EXPECT_LT(d->atoms.f[3 * left], 0.0);
  EXPECT_GT(d->atoms.f[3 * right], 0.0);
  // The deeper overlap (1e-4 vs 1e-5) pushes harder: Hertz F ~ dn^1.5, ratio 10^1.5.
  EXPECT_NEAR(d->atoms.f[3 * right] / -d->atoms.f[3 * left], std::pow(10.0, 1.5), 1e-9);
  EXPECT_NEAR(fwall(d, "w", 1), -(d->atoms.f[3 * left] + d->atoms.f[3 * right]), 1e-15);
}

// Gravity along +x presses a grain inside a vertical cylinder against its wall:
// the wall carries m g along +x, and the grain rests at x = R - r + dn.
TEST(WallGran, CylinderHoldsAGrainAgainstSidewaysGravity) {
  Deck d;
  d(kHead);
  d(R"(create_atoms 1 single 0.004 0 0 units box
fix c all wall/gran model hertz tangential history primitive type 1 zcylinder 0.005 0 0
fix g all gravity 9.81 vector 1 0 0
fix i all nve/sphere)");
  grains(d);
  d("run 20000");
  EXPECT_NEAR(fwall(d, "c", 1), kM * 9.81, 1e-3 * kM * 9.81);
  const double ys = 5e7 / (2 * (1 - 0.09));
  const double dn = std::pow(3 * kM * 9.81 / (4 * ys * std::sqrt(kR)), 2.0 / 3.0);  // static Hertz overlap
  EXPECT_NEAR(d->atoms.x[0], 0.005 - kR + dn, 1e-3 * dn);
}

// A grain dropped on a belt (plane shearing at V along x) ends up rolling
// without slip at v = 2/7 V: the friction impulse J gives m v = J and
// I w = -r J, and no slip means v - r w_y = V (rigid-body mechanics).
TEST(WallGran, ShearingPlaneDragsAGrainToTwoSeventhsOfItsSpeed) {
  Deck d;
  d(kHead);
  d(R"(create_atoms 1 single 0 0 0.001 units box
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0 shear x 0.1
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere)");
  grains(d);
  EXPECT_DOUBLE_EQ(d->find_fix("floor")->max_speed(), 0.1);
  d("run 20000");
  std::printf("belt: grain speed %.6f m/s, 2/7 V = %.6f\n", d->atoms.v[0], 0.2 / 7);
  EXPECT_NEAR(d->atoms.v[0], 2.0 / 7.0 * 0.1, 0.01 * 0.2 / 7);
  EXPECT_NEAR(d->atoms.v[0] - kR * d->atoms.omega[1], 0.1, 1e-3 * 0.1);  // contact point moves with the belt
}

// Friction redefined between runs (the drag deck pours at mu 0, turns at mu 0.5):
// a grain launched at V along a frictionless floor keeps V; once the friction
// fix is redefined it ends up rolling at 5/7 V (m v + I w / r conserved about
// the contact point, I = 2/5 m r^2). LIGGGHTS 3.8 does the same (0.0714143 on a
// deck like this one at E 5 MPa, dt 1e-5, as sable).
TEST(WallGran, FrictionRedefinedBetweenRunsTakesEffect) {
  Deck d;
  d(kHead);
  d("fix m4 all property/global coefficientFriction peratomtypepair 1 0.0");
  d(R"(create_atoms 1 single 0 0 0.001 units box
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
velocity all set 0.1 0 0 units box)");
  grains(d);
  d("run 5000");
  EXPECT_DOUBLE_EQ(d->atoms.v[0], 0.1);
  d("fix m4 all property/global coefficientFriction peratomtypepair 1 0.5");
  d("run 20000");
  EXPECT_NEAR(d->atoms.v[0], 5.0 / 7.0 * 0.1, 1e-3 * 0.5 / 7);
}

// A floor moving as z = A sin(2 pi t / P) with A w^2 < g carries a resting
// grain along: z_grain = z_rest + A sin(w t) (to the small change of the
// Hertz overlap with the floor's acceleration, ~1e-8 m here); tolerance 1 % of A.
TEST(WallGran, WigglingPlaneCarriesAGrain) {
  const double A = 1e-4, P = 0.05, w = 2 * kPi / P;
  ASSERT_LT(A * w * w, 9.81);
  Deck d;
  d(kHead);
  d(R"(create_atoms 1 single 0 0 0.001 units box
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere)");
  grains(d);
  d("run 20000");  // settle on the still floor first, then replace it by the wiggling one
  const double z0 = d->atoms.x[2];
  d("fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0 wiggle amplitude 0.0001 period 0.05");
  EXPECT_NEAR(d->find_fix("floor")->max_speed(), A * w, 1e-12);
  double worst = 0;
  const long step0 = d->step;
  g_probe = [&](sable::Simulation& s) {
    const double t = (s.step - step0) * s.dt;
    if (t < 0.005) return;  // the floor starts at full speed A w: a jolt that rings down in ~1 ms
    worst = std::max(worst, std::fabs(s.atoms.x[2] - (z0 + A * std::sin(w * t))));
  };
  d("fix p all test/probe_wall");
  d("run 50000");
  g_probe = nullptr;
  std::printf("wiggle: worst deviation from z0 + A sin(wt): %.3g m (A = %g m)\n", worst, A);
  EXPECT_LT(worst, 0.01 * A);
}

// The wall looks only at grains near it, chosen at each neighbour rebuild. A
// grain at rest never triggers one, so a wiggling plane that starts 2 skins
// below it (amplitude 4 skins) must find it through the amplitude in the reach.
TEST(WallGran, WigglingPlaneReachesAGrainThatNeverMoved) {
  Deck d;
  d(kHead);
  d("create_atoms 1 single 0 0 0 units box");
  grains(d);
  d->atoms.x[2] = kR + 2 * 0.0005;  // bottom two skins above the plane's centre position
  const double z0 = d->atoms.x[2];
  d(R"(fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0 wiggle amplitude 0.002 period 0.01
fix i all nve/sphere
run 800)");  // the plane reaches z = 0.001 at t = 0.01 asin(1/2) / (2 pi) = 0.83 ms
  EXPECT_EQ(d->neighbor.builds, 1) << "the grain moved before the plane reached it";
  EXPECT_EQ(d->atoms.x[2], z0);
  d("run 2200");
  EXPECT_GT(d->atoms.x[2], z0 + 1e-4) << "the plane passed through the grain";
}

// A spinning cylinder (shear x V on a zcylinder) moves at V e_z x r_radial at
// the contact, r_radial the grain centre's radial vector (LIGGGHTS' code: V is
// an angular velocity there, despite its documentation). Read back through
// compute wall/gran/local's velocity columns.
TEST(WallGran, SpinningCylinderWallVelocity) {
  Deck d;
  d(kHead);
  d(R"(create_atoms 1 single 0.00401 0.0 0 units box
fix c all wall/gran model hertz tangential history primitive type 1 zcylinder 0.005 0 0 shear x 2.0
compute wl all wall/gran/local pos vel id force delta)");
  grains(d);
  EXPECT_DOUBLE_EQ(d->find_fix("c")->max_speed(), 2.0 * 0.005);
  d("run 0");
  sable::Compute* c = d->find_compute("wl");
  c->local_now();
  ASSERT_EQ(c->local_rows(), 1u);
  const std::vector<std::string> names = {"x1", "y1", "z1", "x2", "y2", "z2", "vx1", "vy1", "vz1", "vx2", "vy2", "vz2",
                                          "id1", "id2", "periodic", "fx", "fy", "fz", "delta"};
  EXPECT_EQ(c->local_names, names);
  const double* row = c->local.data();
  EXPECT_NEAR(row[0], 0.005, 1e-15);  // wall point
  EXPECT_NEAR(row[6], 0.0, 1e-15);
  EXPECT_NEAR(row[7], 2.0 * 0.00401, 1e-15);  // V e_z x (x, 0, 0)
  EXPECT_NEAR(row[14], 1.0, 0);               // grain id
  EXPECT_NEAR(row[18], 1e-5, 1e-15);          // overlap
  EXPECT_NEAR(row[15], d->atoms.f[0], 1e-15);
}

// The wall's tangential spring of a grain is forgotten when the grain leaves
// the wall: at a step with a neighbour rebuild (the atoms just sorted), and
// when the deck moves it away between runs; it follows the grain when
// delete_atoms renumbers the grains.
TEST(WallGran, SpringForgottenWhenTheGrainLeaves) {
  Deck d;
  d(kHead);
  // At the static Hertz overlap on the floor (2e-7 m: (3 m g / (4 Y* sqrt(r)))^(2/3), Y* = E / (2 (1 - nu^2))).
  d(R"(create_atoms 1 single 0.004 0 0.0009998 units box
create_atoms 1 single -0.004 0 0.0009998 units box
create_atoms 1 single 0 0.004 0.0009998 units box
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
neigh_modify every 1 check no)");  // a rebuild (and sort) every step
  grains(d);
  sable::Atoms& at = d->atoms;
  for (std::size_t i = 0; i < at.n; ++i) at.v[3 * i] = 0.05;  // sliding: the spring loads
  d("run 200");
  auto* floor = dynamic_cast<sable::FixWallGran*>(d->find_fix("floor"));
  ASSERT_TRUE(floor);
  auto spring = [&](long id) {  // 0 when the wall keeps no contact of grain id
    const sable::HistoryStore& kept = floor->history();
    for (std::size_t r = 0; r < kept.count(); ++r)
      if (kept.key(r).tag == id) {
        const double* h = kept.row(r);
        return std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
      }
    return 0.0;
  };
  for (long id = 1; id <= 3; ++id) ASSERT_GT(spring(id), 0.0) << "grain " << id << " loads no spring";
  at.v[3 * at.index_of(2) + 2] = 2.0;  // leaves the floor within the next step
  d("run 3");
  EXPECT_EQ(spring(2), 0.0) << "the spring of a grain that left the floor survived a rebuild step";
  EXPECT_GT(spring(1), 0.0);
  // delete_atoms renumbers the grains (compress yes): the springs follow them.
  const double s1 = spring(1), s3 = spring(3);
  d("group first id 1\ndelete_atoms group first compress yes");
  EXPECT_EQ(spring(2), s3) << "grain 3, now 2, lost its spring";
  EXPECT_EQ(spring(1), 0.0) << "grain 2 (left the floor), now 1";
  EXPECT_EQ(spring(3), 0.0) << "no grain 3 any more";
  ASSERT_GT(s1, 0.0);
  ASSERT_GT(s3, 0.0);
  d("set atom 2 z 0.008");  // moved away between runs: no longer near the floor
  d("run 1");
  EXPECT_EQ(spring(2), 0.0) << "the spring of a grain moved away between runs survived";
}

// The wall keeps its history by near-list place between rebuilds and by grain
// id across them: reading it mid-run (a restart file, a compute, a test)
// between two rebuilds must not change the run. Before the fix, a read reset
// the "store is behind" mark, so the next rebuild restored the read's old rows.
TEST(WallGran, HistoryReadMidRunChangesNothing) {
  Deck read, plain;
  for (Deck* d : {&read, &plain}) {
    (*d)(kHead);
    (*d)(R"(create_atoms 1 single 0.004 0 0.0009998 units box
create_atoms 1 single -0.004 0 0.0009998 units box
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
fix p all test/probe_wall
neighbor 0.005 bin)");  // a skin so wide that only each run's set-up rebuilds
    grains(*d);
    for (std::size_t i = 0; i < (*d)->atoms.n; ++i) (*d)->atoms.v[3 * i] = 0.05 * (i + 1);  // sliding: springs load
  }
  auto* floor = dynamic_cast<sable::FixWallGran*>(read->find_fix("floor"));
  ASSERT_TRUE(floor);
  double read_spring = 0.0;
  g_probe = [&](sable::Simulation& s) {
    if (s.step == 100) read_spring = std::fabs(floor->history().row(0)[0]);
  };
  read("run 300");
  g_probe = nullptr;
  plain("run 300");
  EXPECT_EQ(read->neighbor.builds, 1) << "no rebuild expected within the run";
  ASSERT_GT(read_spring, 0.0);
  read("run 200");  // its set-up rebuilds: the places go by grain id and back
  plain("run 200");
  const sable::Atoms &a = read->atoms, &b = plain->atoms;
  for (std::size_t i = 0; i < a.n; ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(a.x[3 * i + k], b.x[3 * i + k]) << "grain " << a.id[i];
      EXPECT_EQ(a.f[3 * i + k], b.f[3 * i + k]) << "grain " << a.id[i];
    }
}

}  // namespace test_wall_gran
