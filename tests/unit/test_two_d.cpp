// 2D grains and the reduced contact kernels: the mass and inertia conventions
// (dimension 2 [grains disks|spheres], fix nve/sphere disc), fix nve, and the
// 2D and no-rotation kernels against the full 3D kernel on the same scene
// (contact_kernels full): the terms they leave out are exact zeros there, so
// the trajectories agree bit for bit (compared with ==, which also takes -0 as 0).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "core/engine/error.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_two_d {

using sable::test::Deck;
using sable::test::error_of;

namespace {

constexpr double kPi = std::numbers::pi;

// One grain of diameter 1 (radius 0.5) and density 1 in a 2D box, after `head`.
double mass_after(const std::string& head, const std::string& tail = "set atom 1 diameter 1 density 1\n") {
  Deck d;
  d(head + R"(atom_style granular
atom_modify map array
boundary p p p
region box block 0 10 0 10 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 5 5 0 units box
)" + tail);
  return d->atoms.rmass[0];
}

// A 2D pile with side walls, friction, rolling resistance and a sheared lid:
// 60 grains of two sizes dropped on a floor. `kernels`: auto or full;
// `integrator`: nve/sphere or nve.
std::string pile(const std::string& kernels, const std::string& integrator, const std::string& dim = "2",
                 const std::string& rolling = "epsd2") {
  const bool two = dim == "2";  // 3D: one layer of grains at z = 0 (they stay there: no force has a z part)
  std::string s = "dimension " + dim + "\ncontact_kernels " + kernels + R"(
units si
atom_style granular
atom_modify map array
boundary f f )" + (two ? "p" : "f") + R"(
newton off
region box block 0 0.02 0 0.05 -0.001 0.001 units box
create_box 2 box
neighbor 0.0003 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
fix m5 all property/global coefficientRollingFriction peratomtypepair 2 0.1 0.1 0.1 0.1
pair_style gran model hertz tangential history rolling_friction )" +
                  rolling + R"(
pair_coeff * *
timestep 2e-6
lattice )" + (two ? "sq" : "sc") + R"( 0.0021
region fill block 0.001 0.019 0.001 0.03 -0.0005 0.0005 units box
create_atoms 1 region fill
variable dd atom 0.0014+0.0006*(id*0.6180339887-floor(id*0.6180339887))
variable vvx atom 1.0*((id*0.7548776662-floor(id*0.7548776662))-0.5)
variable vvy atom -0.3-0.3*(id*0.5698402910-floor(id*0.5698402910))
set group all diameter v_dd density 2500
set group all vx v_vvx vy v_vvy
set group all type/fraction 2 0.3 12345
fix floor all wall/gran model hertz tangential history rolling_friction )" +
                  rolling + R"( primitive type 1 yplane 0.0
fix left all wall/gran model hertz tangential history rolling_friction )" +
                  rolling + R"( primitive type 1 xplane 0.0
fix right all wall/gran model hertz tangential history rolling_friction )" +
                  rolling + R"( primitive type 1 xplane 0.02 shear y 0.05
fix g all gravity 9.81 vector 0 -1 0
fix i all )" + integrator + "\n";
  if (two) s += "fix e2d all enforce2d\n";
  return s + "run 10000\n";
}

struct State {
  std::vector<double> x, v, omega, torque;
};
State state_of(Deck& d) {
  const auto& a = d->atoms;
  State s;
  for (long id = 1; id <= static_cast<long>(a.n); ++id) {  // by atom id: the order of the arrays may differ
    const std::size_t i = a.index_of(id);
    for (int k = 0; k < 3; ++k) {
      s.x.push_back(a.x[3 * i + k]);
      s.v.push_back(a.v[3 * i + k]);
      s.omega.push_back(a.omega[3 * i + k]);
      s.torque.push_back(a.torque[3 * i + k]);
    }
  }
  return s;
}

// Number of components where a and b differ (== comparison).
int differing(const std::vector<double>& a, const std::vector<double>& b) {
  int n = 0;
  for (std::size_t k = 0; k < a.size(); ++k) n += a[k] != b[k];
  return n;
}

}  // namespace

// LIGGGHTS 3.8 in 2D takes `density` per area: a grain of diameter 1 and
// density 1 weighs pi/4 (measured: liggghts prints mass[1] = 0.785398163397448
// after `set atom 1 diameter 1 density 1`, and the same for create_atoms'
// default diameter 1 density 1). `grains spheres` weighs the sphere, pi/6.
TEST(TwoD, MassConventions) {
  EXPECT_DOUBLE_EQ(mass_after("dimension 2\n"), kPi / 4);
  EXPECT_DOUBLE_EQ(mass_after("dimension 2\n", ""), kPi / 4);  // create_atoms' default
  EXPECT_DOUBLE_EQ(mass_after("dimension 2 grains disks\n"), kPi / 4);
  EXPECT_DOUBLE_EQ(mass_after("dimension 2 grains spheres\n"), kPi / 6);
  EXPECT_DOUBLE_EQ(mass_after("dimension 2 grains spheres\n", ""), kPi / 6);
  EXPECT_DOUBLE_EQ(mass_after("dimension 3\n"), kPi / 6);
}

// Rotational energy 1/2 I w^2 of one grain spinning at w = 2 about z: I = 2/5
// m r^2 by default (LIGGGHTS, also in 2D), 1/2 m r^2 for `grains disks` or
// LAMMPS' `fix nve/sphere disc` (exact formulas; 1e-15 relative).
TEST(TwoD, InertiaConventions) {
  auto erotate = [](const std::string& dim, const std::string& integrator) {
    Deck d;
    d(dim + R"(
atom_style granular
boundary p p p
region box block 0 10 0 10 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 5 5 0 units box
set atom 1 diameter 1 density 1 omegaz 2
)" + integrator + R"(
compute rot all erotate/sphere
thermo_style custom step c_rot
run 0)");
    return d->find_compute("rot")->compute_scalar() / (0.5 * d->atoms.rmass[0] * 0.25 * 4);  // I / (m r^2)
  };
  EXPECT_NEAR(erotate("dimension 2", "fix i all nve/sphere"), 0.4, 1e-15);
  EXPECT_NEAR(erotate("dimension 2 grains disks", "fix i all nve/sphere"), 0.5, 1e-15);
  EXPECT_NEAR(erotate("dimension 2", "fix i all nve/sphere disc"), 0.5, 1e-15);
  EXPECT_NEAR(erotate("dimension 2 grains spheres", "fix i all nve/sphere"), 0.4, 1e-15);
}

// A constant torque T about z spins a disk (fix nve/sphere disc) up at T / (1/2 m r^2):
// omega(t) = 2 T t / (m r^2) exactly for velocity Verlet (1e-12 relative).
TEST(TwoD, DiscSpinsUpAtHalfMR2) {
  Deck d;
  d(R"(dimension 2
atom_style granular
boundary p p p
region box block 0 10 0 10 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 5 5 0 units box
set atom 1 diameter 1 density 1
fix i all nve/sphere disc
timestep 0.001
run 0)");
  // No fix applies a torque: the integrator's two half kicks per step are run directly.
  auto& a = d->atoms;
  const double m = a.rmass[0], r = a.radius[0], T = 0.3;
  for (int s = 0; s < 100; ++s) {  // what run does per step for one free grain: two half kicks
    a.torque[2] = T;
    d->find_fix("i")->run_task(sable::INITIAL_INTEGRATE);
    a.torque[2] = T;
    d->find_fix("i")->run_task(sable::FINAL_INTEGRATE);
  }
  const double expect = T * 100 * 0.001 / (0.5 * m * r * r);
  EXPECT_NEAR(a.omega[2], expect, 1e-12 * expect);
}

// In 2D with enforce2d, the 2D kernel (auto) and the full 3D kernel give the
// same trajectories bit for bit: pairs, primitive walls (one of them moving),
// tangential history and epsd2 rolling friction, two types, 10000 steps.
TEST(TwoD, PlaneKernelMatchesFullKernel) {
  Deck full, plane;
  full(pile("full", "nve/sphere"));
  plane(pile("auto", "nve/sphere"));
  EXPECT_FALSE(full->atoms.plane_2d);
  EXPECT_TRUE(plane->atoms.plane_2d);
  EXPECT_TRUE(plane->atoms.rotation);
  const State a = state_of(full), b = state_of(plane);
  ASSERT_EQ(a.x.size(), b.x.size());
  EXPECT_EQ(differing(a.x, b.x), 0);
  EXPECT_EQ(differing(a.v, b.v), 0);
  EXPECT_EQ(differing(a.omega, b.omega), 0);
  double wmax = 0;  // the grains do turn (the comparison is not empty)
  for (double w : b.omega) wmax = std::max(wmax, std::fabs(w));
  EXPECT_GT(wmax, 1.0);
}

// The same with cdt rolling friction (a different rolling sub-model's 2D path).
TEST(TwoD, PlaneKernelMatchesFullKernelCdt) {
  Deck full, plane;
  full(pile("full", "nve/sphere", "2", "cdt"));
  plane(pile("auto", "nve/sphere", "2", "cdt"));
  const State a = state_of(full), b = state_of(plane);
  EXPECT_EQ(differing(a.x, b.x), 0);
  EXPECT_EQ(differing(a.omega, b.omega), 0);
}

// A mesh floor (two triangles spanning z) in place of the primitive one: the
// 2D kernel on mesh contacts agrees bit for bit too.
TEST(TwoD, PlaneKernelMatchesFullKernelOnMesh) {
  sable::test::TempDir tmp;
  const std::string stl = (tmp.dir / "floor.stl").string();
  {
    std::FILE* f = std::fopen(stl.c_str(), "w");
    std::fputs("solid floor\n"
               "facet normal 0 1 0\nouter loop\nvertex -0.01 0 -0.002\nvertex -0.01 0 0.002\nvertex 0.03 0 0.002\n"
               "endloop\nendfacet\n"
               "facet normal 0 1 0\nouter loop\nvertex -0.01 0 -0.002\nvertex 0.03 0 0.002\nvertex 0.03 0 -0.002\n"
               "endloop\nendfacet\nendsolid floor\n",
               f);
    std::fclose(f);
  }
  auto deck = [&](const std::string& kernels) {
    std::string s = pile(kernels, "nve/sphere");
    const std::string prim = "fix floor all wall/gran model hertz tangential history rolling_friction epsd2 primitive type 1 yplane 0.0";
    s.replace(s.find(prim), prim.size(),
              "fix mesh all mesh/surface file " + stl + " type 1\nfix floor all wall/gran model hertz tangential history "
              "rolling_friction epsd2 mesh n_meshes 1 meshes mesh");
    return s;
  };
  Deck full, plane;
  full(deck("full"));
  plane(deck("auto"));
  EXPECT_LT(plane->find_fix("floor")->compute_vector(1), 0.0);  // grains press on the mesh (f_floor[2])
  const State a = state_of(full), b = state_of(plane);
  EXPECT_EQ(differing(a.x, b.x), 0);
  EXPECT_EQ(differing(a.v, b.v), 0);
  EXPECT_EQ(differing(a.omega, b.omega), 0);
}

// fix nve (translation only): the no-rotation kernel (auto) gives the same
// trajectories bit for bit as the full kernel whose torques nothing
// integrates; omega stays exactly 0 in both, and the reduced run makes no torque.
TEST(TwoD, FrozenKernelMatchesFullKernel) {
  for (const char* dim : {"2", "3"}) {
    Deck full, frozen;
    full(pile("full", "nve", dim));
    frozen(pile("auto", "nve", dim));
    EXPECT_TRUE(full->atoms.rotation);
    EXPECT_FALSE(frozen->atoms.rotation);
    const State a = state_of(full), b = state_of(frozen);
    EXPECT_EQ(differing(a.x, b.x), 0) << "dimension " << dim;
    EXPECT_EQ(differing(a.v, b.v), 0) << "dimension " << dim;
    for (std::size_t k = 0; k < a.omega.size(); ++k) {
      ASSERT_EQ(a.omega[k], 0.0);
      ASSERT_EQ(b.omega[k], 0.0);
      ASSERT_EQ(b.torque[k], 0.0);
    }
    double tmax = 0;  // the full kernel did make torques (friction acts)
    for (double t : a.torque) tmax = std::max(tmax, std::fabs(t));
    EXPECT_GT(tmax, 0.0) << "dimension " << dim;
  }
}

// Which runs may skip rotation: not with nve/sphere, nor with fix nve when a
// grain already spins, nor with fix move rotate, nor with a free rigid body;
// yes with fix nve and no spin, and with a body whose rotation is locked.
TEST(TwoD, RotationIsSkippedOnlyWhenNoGrainTurns) {
  auto rotation = [](const std::string& lines) {
    Deck d;
    d(R"(dimension 2
atom_style granular
boundary p p p
region box block 0 10 0 10 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 5 5 0 units box
create_atoms 1 single 7 5 0 units box
set group all diameter 1 density 1
pair_style gran model hertz tangential history
pair_coeff * *
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
timestep 1e-4
timestep_check accept
)" + lines + "\nrun 1");
    return d->atoms.rotation;
  };
  EXPECT_TRUE(rotation("fix i all nve/sphere"));
  EXPECT_FALSE(rotation("fix i all nve"));
  EXPECT_TRUE(rotation("set atom 1 omegaz 1\nfix i all nve"));
  EXPECT_TRUE(rotation("group one id 1\ngroup other id 2\nfix i other nve\nfix mv one move rotate 5 5 0 0 0 1 10"));
  EXPECT_FALSE(rotation("group one id 1\ngroup other id 2\nfix i other nve\nfix mv one move linear 1 0 0"));
  EXPECT_TRUE(rotation("fix rb all rigid single"));
  EXPECT_FALSE(rotation("fix rb all rigid single torque * off off off"));
}

// 2D runs with z periodic or fixed; a grain dropped on a floor wall settles on
// it at the Hertz overlap of its weight, m g = 4/3 E* sqrt(r) d^1.5 with
// E* = E / (2 (1 - nu^2)) (LIGGGHTS' wall of the same material) and the 2D
// mass m = pi r^2 rho (3e-3 relative: the grain is still settling, 1.1e-3 off).
TEST(TwoD, BoundaryZPeriodicOrFixed) {
  for (const char* bz : {"p", "f"}) {
    Deck d;
    d(std::string("dimension 2\natom_style granular\nboundary p f ") + bz + R"(
region box block 0 0.01 0 0.01 -0.001 0.001 units box
create_box 1 box
create_atoms 1 single 0.005 0.002 0 units box
set atom 1 diameter 0.002 density 2500
pair_style gran model hertz tangential history
pair_coeff * *
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix floor all wall/gran model hertz tangential history primitive type 1 yplane 0.0
fix g all gravity 9.81 vector 0 -1 0
fix i all nve/sphere
fix e2d all enforce2d
timestep 1e-6
run 100000)");
    const auto& a = d->atoms;
    const double m = kPi * 1e-6 * 2500, estar = 1e7 / (2 * (1 - 0.09));
    const double overlap = std::pow(m * 9.81 / (4.0 / 3.0 * estar * std::sqrt(0.001)), 2.0 / 3.0);
    EXPECT_NEAR(0.001 - a.x[1], overlap, 3e-3 * overlap) << "boundary z " << bz;  // measured 1.1e-3
    EXPECT_NEAR(a.v[1], 0.0, 1e-4) << "boundary z " << bz;
    EXPECT_EQ(a.x[2], 0.0);
  }
}

// A restart keeps the grain convention (mass and inertia of later grains).
TEST(TwoD, RestartKeepsGrainConvention) {
  sable::test::TempDir tmp;
  const std::string file = (tmp.dir / "g.restart").string();
  {
    Deck d;
    d(R"(dimension 2 grains spheres
atom_style granular
boundary p p p
region box block 0 10 0 10 -0.5 0.5 units box
create_box 1 box
create_atoms 1 single 5 5 0 units box
fix i all nve/sphere disc
run 0
write_restart )" + file);
  }
  Deck d;
  d("read_restart " + file + "\ncreate_atoms 1 single 2 2 0 units box\nset atom 2 diameter 1 density 1");
  EXPECT_FALSE(d->atoms.area_density);
  EXPECT_EQ(d->atoms.inertia_factor, 0.5);
  EXPECT_DOUBLE_EQ(d->atoms.rmass[d->atoms.index_of(2)], kPi / 6);
}

TEST(TwoD, BadInput) {
  Deck d;
  EXPECT_NE(error_of(d, "dimension 3 grains disks").find("nothing after 'dimension 3'"), std::string::npos);
  Deck d2;
  EXPECT_NE(error_of(d2, "dimension 2 grains cubes").find("disks or spheres"), std::string::npos);
  Deck d3;
  EXPECT_NE(error_of(d3, "contact_kernels some").find("auto or full"), std::string::npos);
  Deck d4;
  d4(R"(atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box)");
  EXPECT_NE(error_of(d4, "fix i all nve/sphere disc").find("a 2D simulation for 'disc'"), std::string::npos);
  EXPECT_NE(error_of(d4, "fix j all nve update").find("nothing after 'nve'"), std::string::npos);
}

}  // namespace test_two_d
