// Forces and motion on groups (LAMMPS syntax): fix addforce, setforce,
// aveforce, move, and displace_atoms. Analytic references: velocity Verlet is
// exact (to round-off) for a constant force, so a grain under constant forces
// is at x0 + v0 t + F t^2 / (2 m); fix move sets positions from its formula.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "core/input/style_registry.h"
#include "core/engine/threads.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_group_motion {

using sable::test::Deck;
using sable::test::error_of;
using sable::test::printed;
using sable::test::TempDir;

namespace {

constexpr double kPi = std::numbers::pi;

// One grain (d 10 mm, 2500 kg/m3) at the origin of a closed box, no contacts.
const char* kOne = R"(units si
atom_style granular
region box block -1 1 -1 1 -1 1 units box
create_box 1 box
create_atoms 1 single 0 0 0 units box
set atom * diameter 0.01 density 2500
group one id 1
timestep 1e-4
)";

double mass_of(sable::Simulation& s, long id) { return s.atoms.rmass[s.atoms.index_of(id)]; }
const double* x_of(sable::Simulation& s, long id) { return &s.atoms.x[3 * s.atoms.index_of(id)]; }
const double* v_of(sable::Simulation& s, long id) { return &s.atoms.v[3 * s.atoms.index_of(id)]; }

// Hertz contacts between grains (for the tests where grains touch).
const char* kContacts = R"(fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
neighbor 0.002 bin
)";

}  // namespace

// ---- fix addforce

// Gravity then addforce (numbers and an equal-style variable) on a free grain:
// x = F t^2 / (2 m), v = F t / m, exact for velocity Verlet to round-off (1e-12
// relative). f_ID[1..3] is the force before the addition (gravity, -m g in z),
// f_ID the field's energy -F.x.
TEST(FixAddforce, ConstantForceGivesTheVerletParabola) {
  Deck d;
  d(kOne)(R"(variable fz equal 5e-4
fix g all gravity 9.81 vector 0 0 -1
fix push one addforce 1e-3 -2e-3 v_fz
fix i all nve/sphere
run 1000)");
  const double m = mass_of(*d, 1), t = 1000 * 1e-4;
  const double F[3] = {1e-3, -2e-3, 5e-4 - m * 9.81};
  for (int k = 0; k < 3; ++k) {
    const double xe = F[k] * t * t / (2 * m), ve = F[k] * t / m;
    EXPECT_NEAR(x_of(*d, 1)[k], xe, 1e-12 * std::fabs(xe)) << k;
    EXPECT_NEAR(v_of(*d, 1)[k], ve, 1e-12 * std::fabs(ve)) << k;
  }
  sable::Fix* f = d->find_fix("push");
  EXPECT_EQ(f->compute_vector(1), 0.0);
  EXPECT_NEAR(f->compute_vector(3), -m * 9.81, 1e-15 * m * 9.81);
  const double* x = x_of(*d, 1);
  const double e = -(1e-3 * x[0] - 2e-3 * x[1] + 5e-4 * x[2]);
  EXPECT_NEAR(f->compute_scalar(), e, 1e-12 * std::fabs(e));
}

// `every 2` adds the force on even steps only: half the impulse of every step.
TEST(FixAddforce, EveryNActsOnThoseStepsOnly) {
  Deck d;
  d(kOne)("fix push one addforce 1e-3 0 0 every 2\nfix i all nve/sphere\nrun 1000");
  // Steps 2, 4, ..., 1000 add F for one full kick each (two half kicks): v = 500 F dt / m.
  const double m = mass_of(*d, 1);
  EXPECT_NEAR(v_of(*d, 1)[0], 500 * 1e-3 * 1e-4 / m, 1e-12);
}

// A region limits the grains that get the force.
TEST(FixAddforce, RegionLimitsTheGrains) {
  Deck d;
  d(kOne)(R"(create_atoms 1 single 0.5 0 0 units box
set atom 2 diameter 0.01 density 2500
region left block -1 0.2 -1 1 -1 1 units box
fix push all addforce 1e-3 0 0 region left
fix i all nve/sphere
run 100)");
  EXPECT_GT(v_of(*d, 1)[0], 0.0);
  EXPECT_EQ(v_of(*d, 2)[0], 0.0);
}

// ---- fix setforce

// setforce NULL 0 NULL under gravity along (0, -1, -1): vy keeps its initial
// value exactly, x and z follow their own forces; f_ID is the force before.
TEST(FixSetforce, ZeroComponentKeepsThatVelocity) {
  Deck d;
  d(kOne)(R"(set atom 1 vx 0.1 vy 0.3
variable fx equal 1e-3
fix g all gravity 9.81 vector 0 -1 -1
fix hold one setforce v_fx 0 NULL
fix i all nve/sphere
run 1000)");
  const double m = mass_of(*d, 1), t = 0.1, gz = -9.81 / std::sqrt(2.0);
  EXPECT_EQ(v_of(*d, 1)[1], 0.3);
  EXPECT_NEAR(x_of(*d, 1)[1], 0.3 * t, 1e-15);
  EXPECT_NEAR(v_of(*d, 1)[0], 0.1 + 1e-3 / m * t, 1e-12);
  EXPECT_NEAR(v_of(*d, 1)[2], gz * t, 1e-12 * std::fabs(gz * t));
  EXPECT_NEAR(x_of(*d, 1)[2], gz * t * t / 2, 1e-12 * std::fabs(gz * t * t / 2));
  sable::Fix* f = d->find_fix("hold");
  EXPECT_NEAR(f->compute_vector(2), m * gz, 1e-15);
  EXPECT_NEAR(f->compute_vector(3), m * gz, 1e-15);
  EXPECT_EQ(f->compute_vector(1), 0.0);
}

// ---- fix aveforce

namespace {
// Three touching grains in a bent chain (overlaps 0.5 mm), gravity along -z.
std::string chain(const std::string& ave) {
  return std::string(kOne) + kContacts + R"(create_atoms 1 single 0.0095 0 0 units box
create_atoms 1 single 0.0162 0.0067 0 units box
set group all diameter 0.01 density 2500
group chain id 1:3
timestep 1e-5
fix g all gravity 9.81 vector 0 0 -1
)" + ave + "\nfix i all nve/sphere\nrun 1000";
}
}  // namespace

// Every grain gets the group's average force plus the value: the chain moves as
// one (the same velocity bits for each grain) with the acceleration (sum F + N f) / M
// (N grains of mass m, M = N m; the contact forces cancel in the sum up to round-off,
// 1e-10 of the applied force).
TEST(FixAveforce, TouchingGrainsMoveAsOne) {
  Deck d;
  d(chain("fix ave chain aveforce 1e-3 2e-4 0"));
  const double m = mass_of(*d, 1), t = 0.01;
  for (long id : {2, 3})
    for (int k = 0; k < 3; ++k) EXPECT_EQ(v_of(*d, id)[k], v_of(*d, 1)[k]) << id << " " << k;
  EXPECT_NEAR(v_of(*d, 1)[0], 3 * 1e-3 / (3 * m) * t, 1e-10 * 1e-3 / m * t);
  EXPECT_NEAR(v_of(*d, 1)[1], 3 * 2e-4 / (3 * m) * t, 1e-10 * 2e-4 / m * t);
  EXPECT_NEAR(v_of(*d, 1)[2], -9.81 * t, 1e-12 * 9.81 * t);
  // The chain kept its shape: overlaps still 0.5 mm, so its contacts still push.
  const double dx = x_of(*d, 2)[0] - x_of(*d, 1)[0];
  EXPECT_NEAR(dx, 0.0095, 1e-12);
  sable::Fix* f = d->find_fix("ave");
  EXPECT_NEAR(f->compute_vector(3), -3 * m * 9.81, 1e-12 * 3 * m * 9.81);
  EXPECT_NEAR(f->compute_vector(1), 0.0, 1e-12);  // internal forces only
}

// NULL leaves that component alone: the chain's contacts push its grains
// apart in y, so their y velocities differ, while x stays common.
TEST(FixAveforce, NullComponentIsLeftToEachGrain) {
  Deck d;
  d(chain("fix ave chain aveforce 1e-3 NULL 0"));
  EXPECT_EQ(v_of(*d, 2)[0], v_of(*d, 1)[0]);
  EXPECT_NE(v_of(*d, 3)[1], v_of(*d, 1)[1]);
}

// ---- fix move

// linear with a NULL y under gravity along -y: x and z exact at t (also after
// a second run: the time origin is the definition), y integrated like fix nve.
TEST(FixMove, LinearPositionsExactAndNullIntegrated) {
  Deck d;
  d(kOne)(R"(fix g all gravity 9.81 vector 0 -1 0
fix mv one move linear 0.1 NULL -0.05
run 500
run 500)");
  const double t = 0.1;
  const double* x = x_of(*d, 1);
  const double* v = v_of(*d, 1);
  EXPECT_NEAR(x[0], 0.1 * t, 1e-15);
  EXPECT_NEAR(x[2], -0.05 * t, 1e-15);
  EXPECT_EQ(v[0], 0.1);
  EXPECT_EQ(v[2], -0.05);
  EXPECT_NEAR(x[1], -9.81 * t * t / 2, 1e-12 * 9.81 * t * t / 2);
  EXPECT_NEAR(v[1], -9.81 * t, 1e-12 * 9.81 * t);
}

// Defined after a first run: X0 is where the grain is then, t counts from then.
TEST(FixMove, OriginIsWhereTheFixIsDefined) {
  Deck d;
  d(kOne)(R"(set atom 1 vx 0.2
fix i all nve/sphere
run 100
unfix i
fix mv one move linear 0 0.1 0
run 300)");
  const double* x = x_of(*d, 1);
  EXPECT_NEAR(x[0], 0.2 * 0.01, 1e-15);
  EXPECT_NEAR(x[1], 0.1 * 0.03, 1e-15);
  EXPECT_EQ(v_of(*d, 1)[0], 0.0);  // linear sets every velocity component it names
}

// wiggle: X0 + A sin(w t), v = A w cos(w t); a zero amplitude holds z still.
TEST(FixMove, WiggleFollowsTheSine) {
  Deck d;
  d(kOne)("set atom 1 vy 0.1\nfix mv one move wiggle 0.02 NULL 0 0.05\n");
  const double w = 2 * kPi / 0.05;
  for (int chunk = 1; chunk <= 3; ++chunk) {
    d("run 137");
    const double t = chunk * 137 * 1e-4;
    EXPECT_NEAR(x_of(*d, 1)[0], 0.02 * std::sin(w * t), 1e-14);
    EXPECT_NEAR(v_of(*d, 1)[0], 0.02 * w * std::cos(w * t), 1e-12);
    EXPECT_NEAR(x_of(*d, 1)[1], 0.1 * t, 1e-15);
    EXPECT_EQ(x_of(*d, 1)[2], 0.0);
    EXPECT_EQ(v_of(*d, 1)[2], 0.0);
  }
}

// rotate about z through (0.1, 0, 0) and about a tilted axis: the positions of
// Rodrigues' formula at t, v = w R x r, the spin set to w R.
TEST(FixMove, RotateFollowsTheCircle) {
  Deck d;
  d(kOne)(R"(create_atoms 1 single 0.3 0.2 -0.1 units box
set atom 2 diameter 0.01 density 2500
group two id 2
fix r1 one move rotate 0.1 0 0 0 0 1 0.2
fix r2 two move rotate 0 0 0 1 2 2 0.3
run 777)");
  const double t = 777 * 1e-4;
  {
    const double th = 2 * kPi / 0.2 * t, w = 2 * kPi / 0.2;
    const double* x = x_of(*d, 1);
    EXPECT_NEAR(x[0], 0.1 - 0.1 * std::cos(th), 1e-12);
    EXPECT_NEAR(x[1], -0.1 * std::sin(th), 1e-12);
    EXPECT_EQ(x[2], 0.0);
    const double* v = v_of(*d, 1);
    EXPECT_NEAR(v[0], -w * x[1], 1e-12);
    EXPECT_NEAR(v[1], w * (x[0] - 0.1), 1e-12);
    EXPECT_EQ(d->atoms.omega[3 * d->atoms.index_of(1) + 2], w);
  }
  {
    const double r[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3}, x0[3] = {0.3, 0.2, -0.1};
    const double th = 2 * kPi / 0.3 * t, c = std::cos(th), s = std::sin(th);
    const double rx = r[0] * x0[0] + r[1] * x0[1] + r[2] * x0[2];
    const double cross[3] = {r[1] * x0[2] - r[2] * x0[1], r[2] * x0[0] - r[0] * x0[2], r[0] * x0[1] - r[1] * x0[0]};
    for (int k = 0; k < 3; ++k) {
      const double xe = x0[k] * c + cross[k] * s + r[k] * rx * (1 - c);  // Rodrigues
      EXPECT_NEAR(x_of(*d, 2)[k], xe, 1e-12) << k;
      EXPECT_NEAR(d->atoms.omega[3 * d->atoms.index_of(2) + k], 2 * kPi / 0.3 * r[k], 1e-12) << k;
    }
  }
}

// variable: v_dx with v_vx set both; v_dy alone leaves vy alone; v_vz alone
// moves z with that velocity. LAMMPS' four cases.
TEST(FixMove, VariableStyleFollowsTheFormulas) {
  Deck d;
  d(kOne)(R"(set atom 1 vy 0.7
variable dx equal 0.02*sin(3*time)
variable vx equal 0.06*cos(3*time)
variable dy equal 0.01*time
variable vz equal -0.05
fix mv one move variable v_dx v_dy NULL v_vx NULL v_vz
run 1000)");
  const double t = 0.1;
  const double* x = x_of(*d, 1);
  const double* v = v_of(*d, 1);
  EXPECT_NEAR(x[0], 0.02 * std::sin(3 * t), 1e-14);
  EXPECT_NEAR(v[0], 0.06 * std::cos(3 * t), 1e-14);
  EXPECT_NEAR(x[1], 0.01 * t, 1e-15);
  EXPECT_EQ(v[1], 0.7);
  EXPECT_NEAR(x[2], -0.05 * t, 1e-15);
  EXPECT_EQ(v[2], -0.05);
}

// Grains also in nve/sphere's group: both update them, with a warning (LAMMPS).
TEST(FixMove, OverlapWithAnIntegratorIsWarnedAbout) {
  Deck d;
  const std::string out = printed(std::string(kOne) + "fix i all nve/sphere\nfix mv one move linear 0.1 0 0\nrun 10", d);
  EXPECT_NE(out.find("also integrated by fix nve/sphere"), std::string::npos) << out;
  EXPECT_NEAR(x_of(*d, 1)[0], 0.1 * 10 * 1e-4, 1e-15);  // fix move comes last and sets x
}

TEST(FixMove, BadInputNamesTheWord) {
  Deck d;
  d(kOne);
  EXPECT_NE(error_of(d, "fix mv one move spin 1 2 3").find("linear, wiggle, rotate or variable"), std::string::npos);
  EXPECT_NE(error_of(d, "fix mv one move linear 1 2").find("velocity component"), std::string::npos);
  EXPECT_NE(error_of(d, "fix mv one move linear 1 2 3 units lattice").find("box units only"), std::string::npos);
  EXPECT_NE(error_of(d, "fix mv one move wiggle 1 0 0 0").find("period"), std::string::npos);
  EXPECT_NE(error_of(d, "fix mv one move rotate 0 0 0 0 0 0 1").find("non-zero rotation axis"), std::string::npos);
  EXPECT_NE(error_of(d, "fix mv one move variable v_a NULL NULL NULL NULL 3").find("v_name or NULL"),
            std::string::npos);
  d("fix mv one move variable v_nope NULL NULL NULL NULL NULL");
  EXPECT_NE(error_of(d, "run 1").find("'nope' is not defined"), std::string::npos);
}

// ---- restart

namespace {
// A grain pushed by a moving one (fix move linear, NULL z under gravity) on a floor.
const char* kMoveHead = R"(units si
atom_style granular
boundary f f f
region box block -0.05 0.05 -0.05 0.05 0 0.05 units box
create_box 1 box
create_atoms 1 single 0 0 0.005 units box
create_atoms 1 single 0.0105 0.001 0.005 units box
set group all diameter 0.01 density 2500
group mover id 1
group free id 2
)";
const char* kMoveBody = R"(fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
neighbor 0.002 bin
timestep 1e-5
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix i free nve/sphere
)";
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b, std::size_t n) {
  return std::memcmp(a.data(), b.data(), n * sizeof(T)) == 0;
}
}  // namespace

// The move is defined at step 200 (its origin), the run is split by a restart
// at step 1200: the continuation has the bits of the uninterrupted run.
TEST(FixMove, RestartContinuesBitIdentically) {
  TempDir tmp;
  const std::string move = "fix mv mover move linear 0.2 0.01 NULL\n";
  Deck a;
  a(kMoveHead)(kMoveBody)("run 200")(move)("run 1000")("run 1000");
  Deck b;
  b(kMoveHead)(kMoveBody)("run 200")(move)("run 1000")("write_restart " + (tmp / "m.restart"));
  Deck c;
  c("units si\natom_style granular\nread_restart " + (tmp / "m.restart"))(kMoveBody)(move)("run 1000");
  const std::size_t n = a->atoms.n;
  ASSERT_EQ(c->atoms.n, n);
  EXPECT_TRUE(same_bits(a->atoms.x, c->atoms.x, 3 * n));
  EXPECT_TRUE(same_bits(a->atoms.v, c->atoms.v, 3 * n));
  EXPECT_TRUE(same_bits(a->atoms.omega, c->atoms.omega, 3 * n));
  // The mover pushed the free grain (contacts were active across the restart).
  EXPECT_GT(v_of(*a, 2)[0], 0.01);
  EXPECT_NEAR(x_of(*c, 1)[0], 0.2 * 2000 * 1e-5, 1e-15);
}

// ---- displace_atoms

TEST(DisplaceAtoms, MoveShiftsExactlyAndWrapsPeriodicAxes) {
  Deck d;
  d(R"(units si
atom_style granular
boundary p f f
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.9 0.5 0.5 units box
create_atoms 1 single 0.1 0.5 0.5 units box
set group all diameter 0.01 density 2500
group a id 1
displace_atoms a move 0.3 0.1 -0.2 units box)");
  const std::size_t i = d->atoms.index_of(1);
  EXPECT_NEAR(d->atoms.x[3 * i], 0.2, 1e-15);
  EXPECT_EQ(d->atoms.image[3 * i], 1);
  EXPECT_EQ(d->atoms.x[3 * i + 1], 0.5 + 0.1);
  EXPECT_EQ(d->atoms.x[3 * i + 2], 0.5 - 0.2);
  EXPECT_EQ(x_of(*d, 2)[0], 0.1);  // not in the group
  d("displace_atoms a move -0.5 0 0");
  EXPECT_NEAR(d->atoms.x[3 * i], 0.7, 1e-15);
  EXPECT_EQ(d->atoms.image[3 * i], 0);
}

TEST(DisplaceAtoms, RampAndRotate) {
  Deck d;
  d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.2 0.5 units box
create_atoms 1 single 0.5 0.5 0.5 units box
create_atoms 1 single 0.5 0.8 0.5 units box
set group all diameter 0.01 density 2500
displace_atoms all ramp x 0.0 0.1 y 0.3 0.7)");
  EXPECT_EQ(x_of(*d, 1)[0], 0.5);
  EXPECT_NEAR(x_of(*d, 2)[0], 0.55, 1e-15);
  EXPECT_NEAR(x_of(*d, 3)[0], 0.6, 1e-15);
  d("displace_atoms all rotate 0.5 0.5 0 0 0 1 90");
  EXPECT_NEAR(x_of(*d, 2)[0], 0.5, 1e-15);
  EXPECT_NEAR(x_of(*d, 2)[1], 0.55, 1e-15);
  EXPECT_EQ(x_of(*d, 2)[2], 0.5);
}

// The next run sees the new positions: a grain moved into contact is pushed out.
TEST(DisplaceAtoms, NextRunRebuildsTheNeighbourList) {
  Deck d;
  d(std::string(kOne) + kContacts + R"(create_atoms 1 single 0.03 0 0 units box
set group all diameter 0.01 density 2500
fix i all nve/sphere
run 10
displace_atoms one move 0.021 0 0
run 10)");
  EXPECT_LT(v_of(*d, 1)[0], 0.0);
  EXPECT_GT(v_of(*d, 2)[0], 0.0);
}

TEST(DisplaceAtoms, BadInputNamesTheWord) {
  Deck d;
  d(kOne);
  EXPECT_NE(error_of(d, "displace_atoms nope move 1 0 0").find("existing group"), std::string::npos);
  EXPECT_NE(error_of(d, "displace_atoms one shove 1 0 0").find("move, ramp or rotate"), std::string::npos);
  EXPECT_NE(error_of(d, "displace_atoms one move 1 0").find("displacement"), std::string::npos);
  EXPECT_NE(error_of(d, "displace_atoms one move 1 0 0 units lattice").find("box units only"), std::string::npos);
  EXPECT_NE(error_of(d, "displace_atoms one ramp w 0 1 y 0 1").find("x, y or z"), std::string::npos);
}

// ---- force fixes: errors, and the same bits for any thread count

TEST(GroupForces, BadInputNamesTheWord) {
  Deck d;
  d(kOne);
  EXPECT_NE(error_of(d, "fix a one addforce 1 NULL 0").find("NULL is not allowed"), std::string::npos);
  EXPECT_NE(error_of(d, "fix a one addforce 1 0").find("three force components"), std::string::npos);
  EXPECT_NE(error_of(d, "fix a one addforce 1 0 0 energy v_e").find("minimisation"), std::string::npos);
  EXPECT_NE(error_of(d, "fix a one setforce 1 0 0 region nope").find("existing region"), std::string::npos);
  EXPECT_NE(error_of(d, "fix a one aveforce 1 0 0 every 2").find("region"), std::string::npos);
  EXPECT_NE(error_of(d, "fix a nope aveforce 1 0 0").find("existing group"), std::string::npos);
  d("variable pa atom 2*x\nfix a one aveforce v_pa 0 0");
  EXPECT_NE(error_of(d, "run 1").find("equal-style"), std::string::npos);
}

namespace {
// Grains on a floor in a periodic box: addforce (a variable), setforce and
// aveforce on three groups, gravity last (folded on quiet steps).
const char* kThreadsDeck = R"(units si
atom_style granular
boundary p p f
region box block 0 0.012 0 0.012 0 0.03 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 4e-6
lattice sc 0.00105
region fill block 0 0.012 0 0.012 0.0006 0.008 units box
create_atoms 1 region fill
variable dd atom 0.0008+0.0002*(id*0.6180339887-floor(id*0.6180339887))
set group all diameter v_dd density 2500
group a id 1:100000:3
group b id 2:100000:3
group c id 3:100000:7
variable push equal 1e-6*sin(time*300)
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix add a addforce v_push 0 1e-6
fix set b setforce NULL 0 NULL
fix ave c aveforce NULL 1e-6 NULL
fix grav all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
run 600
)";

struct Result {
  std::vector<double> x, v, fids;
  long fused_steps = 0;
};

Result run_threads(int threads, const std::string& deck, bool fusion = true) {
  sable::ThreadSettings& ts = sable::thread_settings();
  const sable::ThreadSettings saved = ts;
  ts.pair_atoms = ts.pair_entries = ts.loop_work = 0;  // every loop threaded
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
#endif
  Deck d;
  d->plan_rewrites = fusion ? sable::kAllRewrites : 0u;
  d(deck);
  ts = saved;
#ifdef _OPENMP
  omp_set_num_threads(before);
#endif
  Result r;
  const sable::Atoms& a = d->atoms;
  r.x.assign(a.x.begin(), a.x.begin() + 3 * a.n);
  r.v.assign(a.v.begin(), a.v.begin() + 3 * a.n);
  for (const char* id : {"add", "set", "ave"})
    if (sable::Fix* f = d->find_fix(id))
      for (int k = 1; k <= 3; ++k) r.fids.push_back(f->compute_vector(k));
  r.fids.push_back(d->find_fix("add")->compute_scalar());
  r.fused_steps = d->fused_steps;
  return r;
}
}  // namespace

// addforce and setforce run inside the force pass (pipelined step), aveforce
// after it (two passes): the bits of 1 thread for 2 and 3, and of separate passes.
TEST(GroupForces, SameBitsForAnyThreadCount) {
  const Result one = run_threads(1, kThreadsDeck);
  ASSERT_GT(one.x.size(), 3000u);
  EXPECT_NE(one.fids[2], 0.0);
  const Result separate = run_threads(1, kThreadsDeck, false);
  EXPECT_TRUE(same_bits(one.x, separate.x, one.x.size())) << "step fusion changes x";
  EXPECT_TRUE(same_bits(one.v, separate.v, one.v.size())) << "step fusion changes v";
#ifdef _OPENMP
  for (int t : {2, 3}) {
    const Result r = run_threads(t, kThreadsDeck);
    EXPECT_TRUE(same_bits(one.x, r.x, one.x.size())) << t << " threads: x differs";
    EXPECT_TRUE(same_bits(one.v, r.v, one.v.size())) << t << " threads: v differs";
    EXPECT_TRUE(same_bits(one.fids, r.fids, one.fids.size())) << t << " threads: f_ID differs";
  }
#endif
}

// Without aveforce every post-force fix is a per-atom task: addforce and
// setforce run on each thread's atoms inside the force pass (the pipelined
// step); the same bits for 1, 2 and 3 threads and as separate passes.
TEST(GroupForces, PipelinedStepSameBits) {
  std::string deck = kThreadsDeck;
  const std::string ave = "fix ave c aveforce NULL 1e-6 NULL\n";
  deck.erase(deck.find(ave), ave.size());
  const Result one = run_threads(1, deck);
  ASSERT_GT(one.fused_steps, 500);  // pipelined and fused
  const Result separate = run_threads(1, deck, false);
  EXPECT_TRUE(same_bits(one.x, separate.x, one.x.size())) << "step fusion changes x";
  EXPECT_TRUE(same_bits(one.fids, separate.fids, one.fids.size())) << "step fusion changes f_ID";
#ifdef _OPENMP
  for (int t : {2, 3}) {
    const Result r = run_threads(t, deck);
    EXPECT_TRUE(same_bits(one.x, r.x, one.x.size())) << t << " threads: x differs";
    EXPECT_TRUE(same_bits(one.v, r.v, one.v.size())) << t << " threads: v differs";
    EXPECT_TRUE(same_bits(one.fids, r.fids, one.fids.size())) << t << " threads: f_ID differs";
  }
#endif
}

// fix move with fix nve/sphere on the other grains: the same bits for any thread count.
TEST(FixMove, SameBitsForAnyThreadCount) {
  std::string deck = kThreadsDeck;
  deck.replace(deck.find("fix integr all nve/sphere"), 25,
               "group rest subtract all c\nfix mv c move wiggle 0.0005 NULL 0.0002 0.01\nfix integr rest nve/sphere");
  const Result one = run_threads(1, deck);
#ifdef _OPENMP
  const Result two = run_threads(2, deck);
  EXPECT_TRUE(same_bits(one.x, two.x, one.x.size()));
  EXPECT_TRUE(same_bits(one.v, two.v, one.v.size()));
#endif
}

}  // namespace test_group_motion
