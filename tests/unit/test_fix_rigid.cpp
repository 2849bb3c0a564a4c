// fix rigid / rigid/small: analytic motions of 3-sphere clumps on an incline,
// force and torque flags, a lid on a bed, array outputs, restarts, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "core/engine/error.h"
#include "core/input/variable.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_fix_rigid {

using sable::test::Deck;
using sable::test::error_of;

namespace {

constexpr double kG = 9.81, kR = 0.002;
const double kSin = 0.5, kCos = std::sqrt(3.0) / 2;  // a 30 degree incline

// One grain type, Hertz-Mindlin, mu 0.3, in the given box.
std::string granular(const std::string& boundary, const std::string& box, const std::string& dt) {
  return "units si\natom_style granular\natom_modify map array\nboundary " + boundary +
         "\nnewton off\ncommunicate single vel yes\nregion box block " + box + " units box\n" + R"(create_box 1 box
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.3
pair_style gran model hertz tangential history
pair_coeff * *
timestep )" + dt + "\n";
}

// A floor at z = 0 tilted by turning gravity 30 degrees towards +x.
std::string incline() {
  char g[160];
  std::snprintf(g, sizeof g, "fix g all gravity %.17g vector %.17g 0 %.17g\n", kG, kSin, -kCos);
  return granular("f f f", "-0.05 0.15 -0.05 0.05 -0.01 0.05", "2e-6") +
         "fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0\n" + g;
}

// Three touching spheres of radius kR resting on the floor: flat triangle or a line along y.
std::string clump(bool line) {
  const double r = kR, h = std::sqrt(3.0) * r;
  char s[400];
  if (line)
    std::snprintf(s, sizeof s,
                  "create_atoms 1 single 0 %.17g %.17g units box\ncreate_atoms 1 single 0 %.17g %.17g units box\n"
                  "create_atoms 1 single 0 %.17g %.17g units box\n",
                  -2 * r, r, 0.0, r, 2 * r, r);
  else
    std::snprintf(s, sizeof s,
                  "create_atoms 1 single 0 0 %.17g units box\ncreate_atoms 1 single %.17g 0 %.17g units box\n"
                  "create_atoms 1 single %.17g %.17g %.17g units box\n",
                  r, 2 * r, r, r, h, r);
  return std::string(s) + "set group all diameter 0.004 density 2500\n";
}

double value(Deck& d, const std::string& formula) {
  d("variable q equal " + formula);
  double v;
  EXPECT_TRUE(d->variables->numeric("q", v));
  return v;
}

}  // namespace

// A flat 3-sphere clump slides down a 30 degree incline at mu = 0.3:
// a = g (sin - mu cos) = 2.3563 m/s^2 (Coulomb sliding of a rigid body; each member
// slides, so the friction sums to mu N whatever the load on each). Measured from the
// centre-of-mass velocity f_rb[1][4] between 0.02 s and 0.05 s, 0.5 %.
TEST(FixRigid, ClumpSlidesDownAnInclineAtCoulombAcceleration) {
  Deck d;
  d(incline() + clump(false) + "fix rb all rigid single\nrun 10000");
  const double v1 = value(d, "f_rb[1][4]");
  d("run 15000");
  const double v2 = value(d, "f_rb[1][4]");
  const double a = (v2 - v1) / 0.03, want = kG * (kSin - 0.3 * kCos);
  EXPECT_NEAR(a, want, 5e-3 * want);
  EXPECT_NEAR(value(d, "f_rb[1][6]"), 0.0, 1e-3);  // it stays on the floor
}

// Three spheres in a line across the slope roll without slipping (mu 0.3 > 2/7 tan 30):
// a = g sin / (1 + I / (m r^2)) = 5/7 g sin (I = 3 x 2/5 m r^2: centres on the axis),
// and the spin is v / r. 0.5 %.
TEST(FixRigid, ClumpRollsDownAnInclineAtFiveSeventhsGSin) {
  Deck d;
  d(incline() + clump(true) + "fix rb all rigid single\nrun 10000");
  const double v1 = value(d, "f_rb[1][4]");
  d("run 15000");
  const double v2 = value(d, "f_rb[1][4]");
  const double a = (v2 - v1) / 0.03, want = 5.0 / 7.0 * kG * kSin;
  EXPECT_NEAR(a, want, 5e-3 * want);
  const auto& at = d->atoms;
  for (std::size_t i = 0; i < at.n; ++i) EXPECT_NEAR(at.omega[3 * i + 1], v2 / kR, 5e-3 * v2 / kR);
}

// With all torque flags off and no initial spin, the body never turns: the members keep
// their offsets from each other to round-off, and their spin is exactly zero.
TEST(FixRigid, LockedRotationKeepsTheOrientation) {
  Deck d;
  d(incline() + clump(false) + "fix rb all rigid single torque 1 off off off\nrun 20000");
  const auto& at = d->atoms;
  const std::size_t a = at.index_of(1), b = at.index_of(2), c = at.index_of(3);
  EXPECT_NEAR(at.x[3 * b] - at.x[3 * a], 2 * kR, 1e-15);
  EXPECT_NEAR(at.x[3 * c + 1] - at.x[3 * a + 1], std::sqrt(3.0) * kR, 1e-15);
  for (std::size_t i : {a, b, c})
    for (int k = 0; k < 3; ++k) EXPECT_EQ(at.omega[3 * i + k], 0.0);
  EXPECT_GT(value(d, "f_rb[1][1]"), 0.001);  // it did slide
}

// A flat lid of 16 spheres spanning a periodic cell, `force * off off on`, `torque * off
// off off`, pushed down by `fix addforce` and launched at U along x, settles on a bed of
// 32 grains: it keeps U exactly, and the floor carries the weight of bed and lid plus the
// push (static balance, averaged over the last 0.05 s, 0.5 %).
TEST(FixRigid, FlagLockedLidSettlesAtForceBalanceAndKeepsItsVelocity) {
  Deck d;
  std::string deck = R"(units si
atom_style granular
atom_modify map array
boundary p p f
newton off
communicate single vel yes
region box block 0 0.016 0 0.016 0 0.04 units box
create_box 2 box
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.3 0.3 0.3 0.3
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 5e-6
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
)";
  char s[200];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      for (int k = 0; k < 2; ++k) {
        std::snprintf(s, sizeof s, "create_atoms 1 single %g %g %g units box\n", 0.002 + 0.004 * i + 0.0007 * k,
                      0.002 + 0.004 * j, 0.0025 + 0.0045 * k);
        deck += s;
      }
      std::snprintf(s, sizeof s, "create_atoms 2 single %g %g 0.013 units box\n", 0.002 + 0.004 * i, 0.002 + 0.004 * j);
      deck += s;
    }
  deck += R"(set group all diameter 0.004 density 2500
group bed type 1
group lid type 2
fix g all gravity 9.81 vector 0 0 -1
fix i bed nve/sphere
fix lid lid rigid single force * off off on torque * off off off
fix push lid addforce 0 0 -0.001
velocity lid set 0.01 0 0
run 60000
)";
  d(deck);
  const double u = value(d, "f_lid[1][4]");  // the mass-weighted mean of 0.01: 0.01 to round-off
  EXPECT_NEAR(u, 0.01, 1e-17);
  d("variable fz equal f_floor[3]\nfix avg all ave/time 10 1000 10000 v_fz\nrun 10000");
  const auto& at = d->atoms;
  double mass = 0;
  for (std::size_t i = 0; i < at.n; ++i) mass += at.rmass[i];
  const double fz = d->find_fix("avg")->compute_scalar();
  const double load = mass * 9.81 + 16 * 0.001;  // weight of bed and lid, and the push on the lid's 16 grains
  EXPECT_NEAR(-fz, load, 5e-3 * load);
  for (std::size_t i = 0; i < at.n; ++i)
    if (at.type[i] == 2) {
      EXPECT_EQ(at.v[3 * i], u);
    }
  EXPECT_EQ(value(d, "f_lid[1][4]"), u);
}

// Two bodies from `group 2 a b`, and from an atom-style variable (custom): same bodies, same motion.
TEST(FixRigid, GroupAndCustomBodiesAgree) {
  auto run = [](const std::string& fix) {
    Deck d;
    d(incline() + clump(false) + R"(create_atoms 1 single 0.05 0 0.002 units box
create_atoms 1 single 0.054 0 0.002 units box
set group all diameter 0.004 density 2500
group a id 1 2 3
group b id 4 5
variable body atom (id<=3)+2*(id>3)
)" + fix + "\nrun 2000");
    return std::array<double, 3>{value(d, "f_rb[1][4]"), value(d, "f_rb[2][4]"), value(d, "x[5]")};
  };
  const auto g = run("fix rb all rigid group 2 a b"), c = run("fix rb all rigid/small custom v_body");
  EXPECT_GT(g[0], 0.0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(g[k], c[k]);
}

// A run split by write_restart / read_restart continues bit for bit.
TEST(FixRigid, RestartContinuesBitIdentically) {
  sable::test::TempDir tmp;
  const std::string body = "fix rb all rigid single torque * on on on\n";
  Deck whole;
  whole(incline() + clump(false) + body + "velocity all set 0 0 0.1\nrun 3000\nrun 3000");
  Deck first;
  first(incline() + clump(false) + body + "velocity all set 0 0 0.1\nrun 3000\nwrite_restart " + tmp / "r.bin");
  Deck second;
  second("read_restart " + tmp / "r.bin" + R"(
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.3
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-6
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0.5 0 -0.86602540378443860
)" + body + "run 3000");
  for (long id = 1; id <= 3; ++id) {
    const std::size_t a = whole->atoms.index_of(id), b = second->atoms.index_of(id);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(whole->atoms.x[3 * a + k], second->atoms.x[3 * b + k]);
      EXPECT_EQ(whole->atoms.v[3 * a + k], second->atoms.v[3 * b + k]);
      EXPECT_EQ(whole->atoms.omega[3 * a + k], second->atoms.omega[3 * b + k]);
    }
  }
}

// Bad input names the line and the word.
TEST(FixRigid, BadInputIsNamed) {
  auto err = [](const std::string& extra, const std::string& fix) {
    Deck d;
    d(incline() + clump(false) + extra);
    return error_of(d, fix);
  };
  EXPECT_NE(err("", "fix rb all rigid group 1 nogroup").find("an existing group ID"), std::string::npos);
  EXPECT_NE(err("", "fix rb all rigid single force 1 off maybe on").find("on or off"), std::string::npos);
  EXPECT_NE(err("group one id 1\n", "fix rb one rigid single").find("has 1 grain"), std::string::npos);
  EXPECT_NE(err("", "fix rb all rigid molecule").find("no molecule ID"), std::string::npos);
  EXPECT_NE(err("", "fix rb all rigid single langevin 1 1 1 12345").find("force or torque"), std::string::npos);
  EXPECT_NE(err("", "fix rb all rigid single force 2 off off off").find("bodies within 1..1"), std::string::npos);
  EXPECT_NE(err("fix i all nve/sphere\nfix rb all rigid single\n", "run 1").find("also integrated by fix i"),
            std::string::npos);
  EXPECT_NE(err("fix rb all rigid single\n", "thermo_style custom step f_rb[2][1]").find("within [1..1][1..15]"),
            std::string::npos);
}

// The cavity's lid (kneib2017) in 2D: spheres in the x-y plane, periodic in x, a floor
// wall at y = 0; a lid row of 8 grains with `force * off on off`, `torque * off off off`,
// pushed down by addforce and moving at U along x over a bed of 24 grains, enforce2d last.
// The lid keeps U exactly and the floor carries bed and lid weight plus the push (static
// balance along y, averaged over the last 0.05 s, 0.5 %); nothing leaves the plane.
TEST(FixRigid, LidIn2DKeepsUAndBalancesTheLoad) {
  Deck d;
  std::string deck = R"(units si
atom_style granular
atom_modify map array
dimension 2
boundary p f p
newton off
communicate single vel yes
region box block 0 0.032 0 0.04 -0.003 0.003 units box
create_box 2 box
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.3 0.3 0.3 0.3
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 5e-6
fix floor all wall/gran model hertz tangential history primitive type 1 yplane 0.0
)";
  char s[200];
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < 3; ++k) {
      std::snprintf(s, sizeof s, "create_atoms 1 single %g %g 0 units box\n", 0.002 + 0.004 * i + 0.0007 * (k % 2),
                    0.0025 + 0.0045 * k);
      deck += s;
    }
    std::snprintf(s, sizeof s, "create_atoms 2 single %g 0.018 0 units box\n", 0.002 + 0.004 * i);
    deck += s;
  }
  deck += R"(set group all diameter 0.004 density 2500
group bed type 1
group lid type 2
fix g all gravity 9.81 vector 0 -1 0
fix i bed nve/sphere
fix lid lid rigid single force * off on off torque * off off off
fix push lid addforce 0 -0.001 0
velocity lid set 0.02 0 0
fix e2d all enforce2d
run 60000
)";
  d(deck);
  const double u = value(d, "f_lid[1][4]");
  d("variable fy equal f_floor[2]\nfix avg all ave/time 10 1000 10000 v_fy\nrun 10000");
  const auto& at = d->atoms;
  double mass = 0;
  for (std::size_t i = 0; i < at.n; ++i) mass += at.rmass[i];
  const double load = mass * 9.81 + 8 * 0.001;
  EXPECT_NEAR(-d->find_fix("avg")->compute_scalar(), load, 5e-3 * load);
  EXPECT_NEAR(u, 0.02, 1e-17);
  for (std::size_t i = 0; i < at.n; ++i) {
    EXPECT_EQ(at.x[3 * i + 2], 0.0);
    if (at.type[i] == 2) {
      EXPECT_EQ(at.v[3 * i], u);
    }
  }
}

// compute unbalanced/force counts a rigid body once, with its summed force, and leaves out the
// contacts inside it (YADE's clumps): two spheres overlapping by a quarter radius, glued, at rest
// on a floor. Their own net forces are the large internal push; the body's is zero at rest, so
// the ratio falls under 1e-3, and the mean contact force is that of the two floor contacts,
// half the weight each (symmetry; 1 %).
TEST(FixRigid, UnbalancedForceCountsABodyOnce) {
  Deck d;
  d(R"(units si
atom_style granular
atom_modify map array
boundary f f f
region box block -0.02 0.02 -0.02 0.02 -0.001 0.02 units box
create_box 1 box
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-6
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
create_atoms 1 single -0.0015 0 0.002 units box
create_atoms 1 single 0.0015 0 0.002 units box
set group all diameter 0.004 density 2500
fix g all gravity 9.81 vector 0 0 -1
fix rb all rigid single
compute ub all unbalanced/force
run 40000)");
  const double weight = 2 * d->atoms.rmass[0] * 9.81;
  EXPECT_LT(value(d, "c_ub"), 1e-3);
  EXPECT_NEAR(value(d, "c_ub[4]"), weight / 2, 0.01 * weight / 2);
}

// Bodies are renumbered in the atoms' (bin) order at each neighbour build for
// speed; the deck's numbers must not move. Six dumbbells, body n (atoms 2n-1, 2n)
// placed so that a bin sort reverses them, fly freely at 0.5 m/s along x through
// several builds: f_rb[n] is still body n, at x_n(0) + 0.5 t exactly (free flight),
// and the dump's mol column still gives atom 2n its body n.
TEST(FixRigid, BodyNumbersStayTheDecksThroughAtomSorts) {
  sable::test::TempDir t;
  std::string atoms;
  auto centre = [](int n, int k) { return (k == 0 ? 0.09 : 0.08) - 0.01 * n; };
  for (int n = 1; n <= 6; ++n) {
    char s[200];
    for (double side : {-kR, kR}) {
      std::snprintf(s, sizeof s, "create_atoms 1 single %.17g %.17g %.17g units box\n", centre(n, 0) + side,
                    centre(n, 1), centre(n, 2));
      atoms += s;
    }
  }
  Deck d;
  d(granular("p f f", "0 0.1 0 0.1 0 0.1", "1e-5") + atoms + "set group all diameter 0.004 density 2500\nvariable b atom floor((id+1)/2)\n"
        "fix rb all rigid/small custom v_b\nvelocity all set 0.5 0 0\n"
        "dump m all custom 2000 " + (t / "m.dump") + " id mol\ndump_modify m sort id\nrun 2000");
  EXPECT_GT(d->neighbor.builds, 5);
  for (int n = 1; n <= 6; ++n) {
    const std::string row = "f_rb[" + std::to_string(n) + "]";
    double x = centre(n, 0) + 0.5 * 2000 * 1e-5;
    x -= 0.1 * std::floor(x / 0.1);  // f_ID gives the centre wrapped into the periodic box
    EXPECT_NEAR(value(d, row + "[1]"), x, 1e-12) << "body " << n;
    EXPECT_NEAR(value(d, row + "[2]"), centre(n, 1), 1e-12) << "body " << n;
    EXPECT_NEAR(value(d, row + "[3]"), centre(n, 2), 1e-12) << "body " << n;
  }
  std::ifstream in(t / "m.dump");
  std::string line;
  while (std::getline(in, line) && line.rfind("ITEM: ATOMS", 0) != 0) {}
  while (std::getline(in, line) && line.rfind("ITEM", 0) != 0) {}  // the step-0 snapshot
  while (std::getline(in, line) && line.rfind("ITEM: ATOMS", 0) != 0) {}
  int checked = 0;
  for (long id, mol; in >> id >> mol; ++checked) EXPECT_EQ(mol, (id + 1) / 2) << "atom " << id;
  EXPECT_EQ(checked, 12);
}

// On steps that nobody observes, the members' velocities are left to the next
// step's placing pass (Simulation::velocities_unread). A clump rolling and bouncing
// down the incline with thermo every step (no such step) and every 1000: every grain's
// position, velocity and spin agree bit for bit after 5000 steps.
TEST(FixRigid, UnobservedStepsChangeNoBit) {
  Deck every, rare;
  const std::string deck = incline() + clump(false) + "velocity all set 0.05 0 0.2\nfix rb all rigid single\n";
  every(deck + "thermo 1\nrun 5000");
  rare(deck + "thermo 1000\nrun 5000");
  const auto &a = every->atoms, &b = rare->atoms;
  ASSERT_EQ(a.n, b.n);
  for (std::size_t i = 0; i < 3 * a.n; ++i) {
    EXPECT_EQ(a.x[i], b.x[i]);
    EXPECT_EQ(a.v[i], b.v[i]);
    EXPECT_EQ(a.omega[i], b.omega[i]);
  }
  EXPECT_NE(a.omega[0], 0.0);  // it turned
}

// Torque-free spin about a principal axis: omega stays L / I_z and the body turns
// by omega t (analytic). A planar 2D body spinning about z takes the exact turn
// (rigid_body_set.cpp turns_about_z) in place of Richardson's iteration, whose
// error here (2e-9 rad after 3 rad: 4e-12 m) a bound of 1e-12 of the offset catches.
// The three disks of radius kR touch; omega 20 rad/s about their centre, 0.2 s.
TEST(FixRigid, PlanarBodyTurnsExactlyAboutZ) {
  const double r = kR, h = std::sqrt(3.0) * r, w = 20.0, cx = r, cy = h / 3;
  char atoms[400];
  std::snprintf(atoms, sizeof atoms,
                "create_atoms 1 single 0 0 0 units box\ncreate_atoms 1 single %.17g 0 0 units box\n"
                "create_atoms 1 single %.17g %.17g 0 units box\n",
                2 * r, r, h);
  char vel[300];
  std::snprintf(vel, sizeof vel,
                "variable vx atom %.17g*(%.17g-y)\nvariable vy atom %.17g*(x-%.17g)\n"
                "velocity all set v_vx v_vy 0\n",
                w, cy, w, cx);
  Deck d;
  d("dimension 2\n" + granular("p p p", "-0.05 0.05 -0.05 0.05 -0.002 0.002", "1e-5") + atoms +
    "set group all diameter 0.004 density 2500\n" + vel + "fix rb all rigid single\nthermo 0\nrun 100");
  const auto& at = d->atoms;
  const double w0 = at.omega[2], x0 = value(d, "f_rb[1][1]"), y0 = value(d, "f_rb[1][2]");
  std::size_t i = at.index_of(2);
  const double dx0 = at.x[3 * i] - x0, dy0 = at.x[3 * i + 1] - y0;
  d("run 20000");
  const double x1 = value(d, "f_rb[1][1]"), y1 = value(d, "f_rb[1][2]");
  i = at.index_of(2);  // the atoms were sorted since
  EXPECT_NEAR(at.omega[2], w0, 1e-14 * w0);
  EXPECT_LT(w0, w);  // the members' own inertia counts: L = sum m d^2 w < I_z w
  const double a = w0 * 0.2, dx = at.x[3 * i] - x1, dy = at.x[3 * i + 1] - y1;
  EXPECT_NEAR(dx, std::cos(a) * dx0 - std::sin(a) * dy0, 1e-12 * r);
  EXPECT_NEAR(dy, std::sin(a) * dx0 + std::cos(a) * dy0, 1e-12 * r);
  EXPECT_EQ(at.x[3 * i + 2], 0.0);
}

// Grains poured into a run with a rigid body (fix insert/pack, on a later step)
// get their own mass as the contact mass, the members their body's: the fix
// keeps its pre_force look when an insertion fix is defined. Without one the
// step plan zeroes the forces in the integrator (cleared_steps; Threads tests).
TEST(FixRigid, GrainsInsertedMidRunGetTheirOwnContactMass) {
  Deck d;
  d(granular("f f f", "-0.05 0.05 -0.05 0.05 0 0.1", "1e-6") + clump(false) +
    R"(fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
group body id 1:3
fix rb body rigid single
group poured subtract all body
fix integr poured nve/sphere
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.002
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
region ins block -0.03 0.03 -0.03 0.03 0.02 0.06 units box
run 10
fix ins all insert/pack seed 32452867 distributiontemplate pdd1 insert_every once overlapcheck yes particles_in_region 40 region ins
run 20)");
  const sable::Atoms& a = d->atoms;
  ASSERT_EQ(a.n, 43u);
  const int col = a.find_column("rigid:contact_mass");
  ASSERT_GE(col, 0);
  const auto& m = a.column(col);
  const double body = 3 * a.rmass[0];
  for (std::size_t i = 0; i < a.n; ++i) {
    if (a.id[i] <= 3)
      EXPECT_DOUBLE_EQ(m[i], body) << "member " << a.id[i];
    else
      EXPECT_EQ(m[i], a.rmass[i]) << "poured grain " << a.id[i];
  }
  EXPECT_EQ(d->cleared_steps, 0);  // two integrators: separate passes
}

// fix damping/cundall on rigid members damps the body, as YADE damps a clump:
// its summed force against its own velocity, not each member's force against
// the member's. Two glued overlapping spheres pulled apart by equal and
// opposite forces along their axis, coasting along it at 0.01 m/s: the net
// force is zero, so the body coasts on unchanged (damping member by member
// shrank the force along the motion and grew the one against it: a net drag
// of 2 alpha F, a dry friction that stopped the body).
TEST(FixRigid, CundallDampingActsOnTheBodyNotItsMembers) {
  Deck d;
  d(granular("f f f", "-0.02 0.02 -0.02 0.02 -0.02 0.02", "1e-6") + R"(create_atoms 1 single -0.001 0 0 units box
create_atoms 1 single 0.001 0 0 units box
set group all diameter 0.004 density 2500
group a1 id 1
group a2 id 2
fix p1 a1 addforce -0.01 0 0
fix p2 a2 addforce 0.01 0 0
fix damp all damping/cundall 0.7
fix rb all rigid single
velocity all set 0.01 0 0
run 2000)");
  EXPECT_NEAR(value(d, "f_rb[1][4]"), 0.01, 1e-15);
  EXPECT_NEAR(value(d, "f_rb[1][1]"), 0.002 * 0.01, 1e-15);
}

// petit2017's clumps (3 disks overlapping, beta 0.62) settling on a floor under
// a downward force with damping/cundall 0.7 (the Mohr deck's relaxation): the
// pile comes to rest in balance, the floor carrying the whole load. Damped
// member by member, the bodies hung on the damping as on dry friction: the
// unbalanced-force ratio stayed at 0.76 and the floor carried 84 % of the load.
TEST(FixRigid, CundallDampedClumpPileComesToBalance) {
  Deck d;
  d(R"(units si
atom_style granular
atom_modify map array
dimension 2 grains disks
boundary p f p
region box block 0 0.025 0 0.04 -0.001 0.001 units box
create_box 1 box
neighbor 0.0002 bin
neigh_modify delay 0
fix pt all particletemplate/sphere 15485863 density constant 5.3 radius gaussian number 0.001 0.0005 cut 1
fix bp all property/atom bodyid scalar no no no 0
ballistic_deposit 20 pt seed 32452843 clump beta 0.62 body bp
variable b atom f_bp
fix m1 all property/global youngsModulus peratomtype 1e8
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.3
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
fix fw all wall/gran model hertz tangential history primitive type 1 yplane 0.0
fix g all addforce 0 -0.01 0
fix d all damping/cundall 0.7
fix i all rigid/small custom v_b
fix e2 all enforce2d
compute ub all unbalanced/force
run 40000)");
  const double load = 0.01 * static_cast<double>(d->atoms.n);
  EXPECT_LT(value(d, "c_ub"), 1e-3);
  EXPECT_NEAR(-value(d, "f_fw[2]"), load, 1e-3 * load);
}

}  // namespace test_fix_rigid
