// fix wall/gran ... mesh with fix mesh/surface(/stress) and move/mesh, against
// statics, rigid-body mechanics and the primitive plane wall (a flat mesh is
// a plane: the same kernel gives the same bits up to round-off in the
// closest-point arithmetic).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/engine/compute.h"
#include "core/engine/threads.h"
#include "core/geometry/mesh.h"
#include "core/input/style_registry.h"
#include "fixes/fix_wall_gran_mesh.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_mesh_walls {

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
SABLE_FIX("test/probe_mesh", FixProbe);

// An ASCII STL of the given triangles (9 numbers each) in the test's temp folder.
std::string stl(const std::string& name, const std::vector<double>& xyz) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream f(path);
  f.precision(17);
  f << "solid " << name << "\n";
  for (std::size_t t = 0; t < xyz.size() / 9; ++t) {
    f << "facet normal 0 0 0\nouter loop\n";
    for (int k = 0; k < 3; ++k) f << "vertex " << xyz[9 * t + 3 * k] << " " << xyz[9 * t + 3 * k + 1] << " " << xyz[9 * t + 3 * k + 2] << "\n";
    f << "endloop\nendfacet\n";
  }
  f << "endsolid\n";
  return path;
}

// Square [-h, h]^2 in the plane z = 0, split along its diagonal x = y.
std::vector<double> floor2(double h) { return {-h, -h, 0, h, -h, 0, h, h, 0, -h, -h, 0, h, h, 0, -h, h, 0}; }
// The same square as four triangles around the origin (the inner edges are its diagonals).
std::vector<double> floor4(double h) {
  return {0, 0, 0, -h, -h, 0, h, -h, 0, 0, 0, 0, h, -h, 0, h, h, 0,
          0, 0, 0, h, h, 0, -h, h, 0, 0, 0, 0, -h, h, 0, -h, -h, 0};
}

std::string head(const std::string& boundary = "f f f", const std::string& box = "-0.01 0.01 -0.01 0.01 -0.01 0.01") {
  return "units si\natom_style granular\nboundary " + boundary + "\nregion box block " + box +
         R"( units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
)";
}

void grains(Deck& d) {
  for (std::size_t i = 0; i < d->atoms.n; ++i) d->atoms.set_radius_density(i, kR, kRho);
}

double fv(Deck& d, const char* id, int k) { return d->find_fix(id)->compute_vector(k); }

}  // namespace

// Statics: three grains at rest on a four-triangle floor, one on a face, one
// on an inner (inactive) edge, one on the inner (inactive) corner: the mesh
// carries exactly their weight, f_floor[3] = -3 m g (0.1 %: residual
// oscillation, as WallGran.ForceOnTheWallBalancesTheWeight), each grain once.
TEST(MeshWall, GrainsOnFloorFeelTheirWeight) {
  Deck d;
  d(head());
  d("fix floor all mesh/surface/stress file " + stl("floor4.stl", floor4(0.01)) + " type 1 stress on");
  d(R"(create_atoms 1 single 0.004 -0.001 0.001 units box
create_atoms 1 single 0.003 0.003 0.001 units box
create_atoms 1 single 0 0 0.001 units box
fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere)");
  grains(d);
  d("run 20000");
  const double w = 3 * kM * 9.81;
  std::printf("floor: f_floor[3] = %.9g N, -3 m g = %.9g N (rel. diff %.2e)\n", fv(d, "floor", 3), -w,
              fv(d, "floor", 3) / -w - 1);
  EXPECT_NEAR(fv(d, "floor", 3), -w, 1e-3 * w);
  EXPECT_NEAR(fv(d, "w", 3), -w, 1e-3 * w);
  // Each grain alone: its height is that of a grain on a plane (one contact, not two or six).
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(d->atoms.x[3 * i + 2], d->atoms.x[2], 1e-12);
  EXPECT_NEAR(fv(d, "floor", 1), 0.0, 1e-9 * w);
}

namespace {

// Runs `steps` of one grain on a floor (mesh or primitive), recording the wall force and the grain state each step.
struct Track {
  std::vector<double> fx, fz, x, vx, wy;
};
Track slide(const std::string& boundary, const std::string& wall, const std::string& setv, long steps,
            const std::string& box = "-0.01 0.01 -0.01 0.01 -0.01 0.01", const std::string& start = "0 0 0.00099") {
  Deck d;
  d(head(boundary, box));
  d("create_atoms 1 single " + start + " units box");
  d(wall);
  // Gravity tilted 20 deg towards +x: a rolling grain needs a static friction
  // force (2/7 m g sin 20), carried by the tangential spring (history).
  d("fix g all gravity 9.81 vector 0.34202014332566873 0 -0.93969262078590832\nfix i all nve/sphere\nfix p all test/probe_mesh");
  grains(d);
  d("set atom 1 " + setv);
  Track t;
  g_probe = [&](sable::Simulation& s) {
    t.fx.push_back(s.find_fix("w")->compute_vector(1));
    t.fz.push_back(s.find_fix("w")->compute_vector(3));
    const std::size_t i = s.atoms.index_of(1);
    t.x.push_back(s.atoms.x[3 * i]);
    t.vx.push_back(s.atoms.v[3 * i]);
    t.wy.push_back(s.atoms.omega[3 * i + 1]);
  };
  d("run " + std::to_string(steps));
  g_probe = nullptr;
  return t;
}

double max_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) m = std::max(m, std::fabs(a[k] - b[k]));
  return m;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}

}  // namespace

// A grain rolling down a flat two-triangle floor under gravity tilted 20 deg
// across the triangles' shared diagonal (a coplanar, inactive edge): the
// static friction that keeps it rolling sits in the tangential spring; carried
// to the new triangle, the grain moves exactly as on a plane (primitive
// zplane, the same kernel): the wall force equals it each step to 1e-9 of
// its size, so no jump at the edge. (Losing the spring at the edge changes the
// friction force by its whole size.)
TEST(MeshWall, CrossingACoplanarEdgeKeepsTheForceContinuous) {
  const std::string mesh = "fix floor all mesh/surface file " + stl("floor2.stl", floor2(0.01)) +
                           " type 1\nfix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor";
  const std::string prim = "fix w all wall/gran model hertz tangential history primitive type 1 zplane 0.0";
  // From (-0.002, 0) along +x: crosses the diagonal x = y at x = 0 after about 9 ms.
  const std::string box = "-0.01 0.01 -0.01 0.01 -0.01 0.01", start = "-0.002 0 0.0009998", v = "vx 0.2 omegay 200";
  const Track m = slide("f f f", mesh, v, 12000, box, start);
  const Track p = slide("f f f", prim, v, 12000, box, start);
  ASSERT_EQ(m.fx.size(), p.fx.size());
  ASSERT_LT(m.x.front(), 0.0);
  ASSERT_GT(m.x.back(), 0.0);  // it crossed
  const double fscale = max_abs(p.fx), zscale = max_abs(p.fz);
  ASSERT_GT(fscale, 0.0);
  std::printf("coplanar edge: max |f_mesh - f_plane| / max |f| = %.2e (x), %.2e (z) over %zu steps\n",
              max_diff(m.fx, p.fx) / fscale, max_diff(m.fz, p.fz) / zscale, m.fx.size());
  for (std::size_t s = 0; s < m.fx.size(); ++s) {
    ASSERT_NEAR(m.fx[s], p.fx[s], 1e-9 * fscale) << "step " << s + 1;
    ASSERT_NEAR(m.fz[s], p.fz[s], 1e-9 * zscale) << "step " << s + 1;
  }
  EXPECT_NEAR(m.x.back(), p.x.back(), 1e-12);
  EXPECT_NEAR(m.wy.back(), p.wy.back(), 1e-9 * std::fabs(p.wy.back()));
}

// Rigid-body mechanics: the torque of the grains on a spinning plate about its
// (turning) reference point equals the sum of (contact point - reference) x (minus the
// force on the grain) over the contacts that compute wall/gran/local lists,
// to round-off (1e-12 of the largest term), and the force their sum. `run 0`
// evaluates both at the same state (no history update, as the compute).
TEST(MeshWall, TorqueOnASpinningMeshIsTheSumOfRCrossF) {
  Deck d;
  d(head("f f f", "-0.03 0.03 -0.03 0.03 -0.01 0.01"));
  d("fix plate all mesh/surface/stress file " + stl("plate.stl", floor2(0.02)) +
    " type 1 reference_point 0.001 -0.002 0.0005");
  d(R"(fix spin all move/mesh mesh plate rotate origin 0 0 0 axis 0 0 1 period 0.5
fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate
create_atoms 1 single 0.01 0 0.001 units box
create_atoms 1 single -0.005 0.008 0.001 units box
create_atoms 1 single 0 -0.012 0.001 units box
create_atoms 1 single 0.012 0.012 0.001 units box
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
compute c all wall/gran/local pos force)");
  grains(d);
  d("run 3000");
  d("run 0");
  sable::Compute* c = d->find_compute("c");
  c->local_now();
  ASSERT_EQ(c->local_rows(), 4u);
  ASSERT_EQ(c->local_cols, 9);  // pos: wall point, grain centre; force
  const auto& names = c->local_names;
  auto col = [&](const std::string& n) { return static_cast<int>(std::find(names.begin(), names.end(), n) - names.begin()); };
  const int px = col("x1"), fx = col("fx");
  ASSERT_LT(px, c->local_cols);
  ASSERT_LT(fx, c->local_cols);
  // The reference point turns with the mesh (as LIGGGHTS 3.8: checked, f_ID[7..9]).
  const double ref[3] = {fv(d, "plate", 7), fv(d, "plate", 8), fv(d, "plate", 9)};
  double f[3] = {0, 0, 0}, t[3] = {0, 0, 0}, scale = 0;
  for (std::size_t r = 0; r < c->local_rows(); ++r) {
    const double* row = &c->local[r * c->local_cols];
    const double p[3] = {row[px] - ref[0], row[px + 1] - ref[1], row[px + 2] - ref[2]};
    const double F[3] = {-row[fx], -row[fx + 1], -row[fx + 2]};
    const double tc[3] = {p[1] * F[2] - p[2] * F[1], p[2] * F[0] - p[0] * F[2], p[0] * F[1] - p[1] * F[0]};
    for (int k = 0; k < 3; ++k) f[k] += F[k], t[k] += tc[k], scale = std::max(scale, std::fabs(tc[k]));
  }
  ASSERT_GT(scale, 0.0);
  std::printf("spinning plate: f_plate[4..6] = (%.6g, %.6g, %.6g) N m, sum r x F = (%.6g, %.6g, %.6g) N m\n",
              fv(d, "plate", 4), fv(d, "plate", 5), fv(d, "plate", 6), t[0], t[1], t[2]);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(fv(d, "plate", 4 + k), t[k], 1e-12 * scale) << "torque " << k;
    EXPECT_NEAR(fv(d, "plate", 1 + k), f[k], 1e-12 * 4 * kM * 9.81) << "force " << k;
  }
  // The plate has turned by 2 pi t / T: its reference point with it.
  const double ang = 2 * kPi * 3000 * 1e-6 / 0.5;
  EXPECT_NEAR(fv(d, "plate", 7), 0.001 * std::cos(ang) + 0.002 * std::sin(ang), 1e-12);
  // id columns of a mesh contact: (wall index, triangle, grain id).
  d("compute ids all wall/gran/local id");
  sable::Compute* ci = d->find_compute("ids");
  ci->local_now();
  ASSERT_EQ(ci->local_rows(), 4u);
  for (std::size_t r = 0; r < 4; ++r) {
    const double* row = &ci->local[r * 3];
    EXPECT_EQ(row[0], 0.0);
    EXPECT_TRUE(row[1] == 0.0 || row[1] == 1.0) << row[1];  // one of the plate's two triangles
    EXPECT_EQ(row[2], static_cast<double>(r + 1));          // in grain id order
  }
  // The grains are dragged along the rotation (counter-clockwise about +z).
  const std::size_t i = d->atoms.index_of(1);
  EXPECT_GT(d->atoms.v[3 * i + 1], 0.0);
}

// A grain rolling along a mesh floor that spans a periodic box (tilted
// gravity, as above) crosses the boundary as on a plane: equal to the
// primitive zplane each step (1e-9 of the force's size): no jump where its
// image sees the floor's far edge (glued to the near one), history kept.
TEST(MeshWall, PeriodicBoundaryCrossingWithoutAJump) {
  const std::string box = "-0.005 0.005 -0.01 0.01 -0.01 0.01", start = "0.003 0 0.0009998", v = "vx 0.2 omegay 200";
  const std::string mesh = "fix floor all mesh/surface file " +
                           stl("pfloor.stl", {-0.005, -0.01, 0, 0.005, -0.01, 0, 0.005, 0.01, 0, -0.005, -0.01, 0,
                                              0.005, 0.01, 0, -0.005, 0.01, 0}) +
                           " type 1\nfix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor";
  const std::string prim = "fix w all wall/gran model hertz tangential history primitive type 1 zplane 0.0";
  const Track m = slide("p f f", mesh, v, 12000, box, start);
  const Track p = slide("p f f", prim, v, 12000, box, start);
  ASSERT_LT(m.x.back(), m.x.front());  // wrapped through x = 0.005
  const double fscale = max_abs(p.fx), zscale = max_abs(p.fz);
  std::printf("periodic crossing: max |f_mesh - f_plane| / max |f| = %.2e (x), %.2e (z) over %zu steps\n",
              max_diff(m.fx, p.fx) / fscale, max_diff(m.fz, p.fz) / zscale, m.fx.size());
  for (std::size_t s = 0; s < m.fx.size(); ++s) {
    ASSERT_NEAR(m.fx[s], p.fx[s], 1e-9 * fscale) << "step " << s + 1;
    ASSERT_NEAR(m.fz[s], p.fz[s], 1e-9 * zscale) << "step " << s + 1;
  }
  EXPECT_NEAR(m.vx.back(), p.vx.back(), 1e-9 * std::fabs(p.vx.back()));
}

// 2D (dimension 2, grains in z = 0, spheres' mass kM): a grain set down on a mesh floor y = 0
// (two triangles spanning z) comes to rest carrying its weight, as on the
// primitive yplane (equal to 1e-9), f_floor[2] = -m g to 0.1 %.
TEST(MeshWall, MeshFloorIn2D) {
  auto run = [](const std::string& wall) {
    Deck d;
    d(R"(units si
atom_style granular
dimension 2 grains spheres
boundary f f p
region box block -0.01 0.01 -0.01 0.01 -0.002 0.002 units box
create_box 1 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
create_atoms 1 single 0.001 0.001 0 units box)");
    d(wall);
    d("fix g all gravity 9.81 vector 0 -1 0\nfix i all nve/sphere\nfix e all enforce2d");
    grains(d);
    d("set atom 1 vx 0.05");
    d("run 30000");
    return std::vector<double>{d->find_fix("w")->compute_vector(2), d->atoms.x[0], d->atoms.x[1], d->atoms.v[0]};
  };
  const std::string y0 = stl("floor2d.stl", {-0.01, 0, -0.002, -0.01, 0, 0.002, 0.01, 0, 0.002, -0.01, 0, -0.002, 0.01, 0,
                                             0.002, 0.01, 0, -0.002});
  const auto m = run("fix floor all mesh/surface file " + y0 +
                     " type 1\nfix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor");
  const auto p = run("fix w all wall/gran model hertz tangential history primitive type 1 yplane 0.0");
  const double w = kM * 9.81;
  std::printf("2D: f_floor[2] = %.9g N, -m g = %.9g N; mesh - plane: x %.2e m, vx %.2e m/s\n", m[0], -w, m[1] - p[1],
              m[3] - p[3]);
  EXPECT_NEAR(m[0], -w, 1e-3 * w);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(m[k], p[k], 1e-9 * std::max(std::fabs(p[k]), 1e-6)) << k;
}

// Bad input names the word.
TEST(MeshWall, ErrorsNameTheWord) {
  Deck d;
  d(head());
  const std::string f = stl("err.stl", floor2(0.01));
  auto error = [&](const std::string& line) {
    try {
      d(line);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(error("fix a all mesh/surface file " + f + " type 1 temperature 300").find("temperature"), std::string::npos);
  EXPECT_NE(error("fix a all mesh/surface file nowhere.stl type 1").find("nowhere.stl"), std::string::npos);
  EXPECT_NE(error("fix a all mesh/surface file " + f).find("type"), std::string::npos);
  d("fix a all mesh/surface file " + f + " type 1");
  EXPECT_NE(error("fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes b").find("'b'"),
            std::string::npos);
  EXPECT_NE(error("fix mv all move/mesh mesh a wiggle amplitude 1 0 0 period 1").find("wiggle"), std::string::npos);
  d("fix belt all mesh/surface file " + f + " type 1 surface_vel 0.1 0 0");
  EXPECT_NE(error("fix mv all move/mesh mesh belt linear 1 0 0").find("surface_vel"), std::string::npos);
}

// dump mesh/stl writes the moved triangles: read back, the plate turned a
// quarter turn about z (period 0.004 s, 1000 steps of 1e-6 s) has its corner
// (h, -h) at (h, h) (1e-12: the STL's 15 digits), and two move/mesh on one
// mesh superpose (the linear one shifts it by v t).
TEST(MeshWall, DumpMeshStlWritesTheMovedMesh) {
  Deck d;
  d(head());
  const std::string out = ::testing::TempDir() + "mesh_dump_*.stl";
  d("fix plate all mesh/surface file " + stl("dplate.stl", {0.005, -0.005, 0, 0.006, -0.005, 0, 0.005, -0.004, 0}) +
    " type 1");
  d(R"(fix spin all move/mesh mesh plate rotate origin 0 0 0 axis 0 0 1 period 0.004
fix lift all move/mesh mesh plate linear 0 0 0.5
dump d all mesh/stl 1000 )" + out + " plate\nrun 1000");
  sable::TriMesh m = sable::TriMesh::read_stl(::testing::TempDir() + "mesh_dump_1000.stl");
  m.build(0.256235);
  ASSERT_EQ(m.ntri(), 1u);
  EXPECT_NEAR(m.vert[0], 0.005, 1e-12);
  EXPECT_NEAR(m.vert[1], 0.005, 1e-12);
  EXPECT_NEAR(m.vert[2], 0.5 * 1e-3, 1e-12);
}

// A run split by write_restart / read_restart continues bit for bit: the
// mesh's pose (turned by move/mesh), its wear and the contacts' tangential history
// come back with fix mesh/surface and fix wall/gran defined again.
TEST(MeshWall, RestartContinuesBitIdentically) {
  const std::string file = ::testing::TempDir() + "mesh.restart";
  const std::string plate = stl("rplate.stl", floor2(0.02));
  const std::string atoms = head("f f f", "-0.03 0.03 -0.03 0.03 -0.01 0.01") + R"(create_atoms 1 single 0.01 0 0.001 units box
create_atoms 1 single -0.005 0.008 0.001 units box
create_atoms 1 single 0 -0.012 0.001 units box)";
  const std::string body = "timestep 1e-6\nfix kf all property/global k_finnie peratomtypepair 1 1.0\n"
                           "fix plate all mesh/surface/stress file " + plate + " type 1 wear finnie" + R"(
fix spin all move/mesh mesh plate rotate origin 0 0 0 axis 0 0 1 period 0.5
fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere)";
  Deck a;
  a(atoms);
  grains(a);
  a(body)("run 2000")("run 2000");
  Deck b;
  b(atoms);
  grains(b);
  b(body)("run 2000")("write_restart " + file);
  Deck c;
  c("units si\natom_style granular\nread_restart " + file);
  c(R"(fix m1 all property/global youngsModulus peratomtype 5e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
neighbor 0.0005 bin)");
  c(body)("run 2000");
  ASSERT_EQ(c->step, 4000);
  for (std::size_t k = 0; k < 9; ++k) {
    EXPECT_EQ(a->atoms.x[k], c->atoms.x[k]) << k;
    EXPECT_EQ(a->atoms.v[k], c->atoms.v[k]) << k;
  }
  for (int k = 1; k <= 9; ++k) EXPECT_EQ(fv(a, "plate", k), fv(c, "plate", k)) << k;
  // The mesh's Finnie wear goes on from the restart (grains sliding on the turning plate wear it).
  auto wear = [](Deck& d) { return dynamic_cast<sable::MeshHolder*>(d->find_fix("plate"))->mesh().wear; };
  ASSERT_EQ(wear(a).size(), 2u);
  EXPECT_GT(wear(a)[0] + wear(a)[1], 0.0);
  EXPECT_EQ(wear(a), wear(c));
}

// dump mesh/vtk: legacy VTK POLYDATA with the moved triangles (3 points each),
// their polygons and per-triangle cell data (mesh index, material type).
TEST(MeshWall, DumpMeshVtkWritesPolydata) {
  Deck d;
  d(head());
  const std::string out = ::testing::TempDir() + "mesh_vtk_*.vtk";
  d("fix plate all mesh/surface file " + stl("vplate.stl", floor2(0.005)) + " type 1 move 0 0 0.001");
  d("dump v all mesh/vtk 5 " + out + "\nrun 5");
  std::ifstream f(::testing::TempDir() + "mesh_vtk_5.vtk");
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("DATASET POLYDATA\nPOINTS 6 double\n-0.005 -0.005 0.001\n"), std::string::npos) << text;
  EXPECT_NE(text.find("POLYGONS 2 8\n3 0 1 2\n3 3 4 5\n"), std::string::npos) << text;
  EXPECT_NE(text.find("CELL_DATA 2\nSCALARS mesh int 1\nLOOKUP_TABLE default\n0\n0\nSCALARS type int 1"), std::string::npos)
      << text;
}

// dump mesh/vtk's LIGGGHTS identifiers: a grain resting on triangle 0 of a two-triangle
// floor (h 5 mm, area 2 h^2 each) loads it with its weight: normal_stress_average m g / A
// (LIGGGHTS 3.8 writes |f.n| / A), no shear, stress components (0, 0, -m g / A);
// triangle 1 carries nothing (0.1 %: residual oscillation, as GrainsOnFloorFeelTheirWeight).
TEST(MeshWall, DumpMeshVtkStressOfARestingGrain) {
  Deck d;
  d(head());
  d("fix plate all mesh/surface file " + stl("splate.stl", floor2(0.005)) + " type 1");
  d(R"(create_atoms 1 single 0.003 -0.002 0.001 units box
fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere)");
  grains(d);
  const std::string out = ::testing::TempDir() + "mesh_stress_*.vtk";
  d("dump v all mesh/vtk 20000 " + out + " output face id stress stresscomponents vel area plate\nrun 20000");
  std::ifstream f(::testing::TempDir() + "mesh_stress_20000.vtk");
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  auto after = [&](const std::string& head, int n) {
    std::vector<double> v;
    const auto at = text.find(head);
    if (at == std::string::npos) return v;
    std::istringstream is(text.substr(at + head.size()));
    for (double x; v.size() < static_cast<std::size_t>(n) && is >> x;) v.push_back(x);
    return v;
  };
  const double A = 2 * 0.005 * 0.005, s = kM * 9.81 / A;
  EXPECT_EQ(after("SCALARS id int 1\nLOOKUP_TABLE default\n", 2), (std::vector<double>{0, 1})) << text;
  const auto area = after("SCALARS area double 1\nLOOKUP_TABLE default\n", 2);
  ASSERT_EQ(area.size(), 2u) << text;
  EXPECT_NEAR(area[0], A, 1e-15);
  const auto sn = after("SCALARS normal_stress_average double 1\nLOOKUP_TABLE default\n", 2);
  ASSERT_EQ(sn.size(), 2u) << text;
  EXPECT_NEAR(sn[0], s, 1e-3 * s);
  EXPECT_EQ(sn[1], 0.0);
  const auto st = after("SCALARS shear_stress_average double 1\nLOOKUP_TABLE default\n", 2);
  ASSERT_EQ(st.size(), 2u) << text;
  EXPECT_NEAR(st[0], 0.0, 1e-3 * s);
  const auto sc = after("VECTORS stress double\n", 6);
  ASSERT_EQ(sc.size(), 6u) << text;
  EXPECT_NEAR(sc[2], -s, 1e-3 * s);
  EXPECT_EQ(sc[5], 0.0);
  const auto v = after("VECTORS velocity double\n", 6);
  ASSERT_EQ(v.size(), 6u) << text;
  for (double x : v) EXPECT_EQ(x, 0.0);
}

// Identifiers sable does not write are refused at the dump line; wear finnie
// without its k_finnie property is refused at the run.
TEST(MeshWall, DumpMeshVtkRefusesOwner) {
  Deck d;
  d(head());
  d("fix plate all mesh/surface file " + stl("wplate.stl", floor2(0.005)) + " type 1");
  EXPECT_NE(sable::test::error_of(d, "dump v all mesh/vtk 10 x.vtk owner plate\n").find("'owner' is not supported"),
            std::string::npos);
  d("fix plate2 all mesh/surface/stress file " + stl("wplate2.stl", floor2(0.005)) + " type 1 wear finnie");
  d("fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate2");
  EXPECT_NE(sable::test::error_of(d, "run 1\n").find("k_finnie"), std::string::npos);
}

// Finnie wear (fix mesh/surface/stress ... wear finnie) of one grain (d 10 mm, 2500
// kg/m^3, E 5 MPa, e 0.5, k_finnie 1) hitting a two-triangle plate obliquely at
// (vx, 0, -vz), against LIGGGHTS 3.8 (the same deck, dump mesh/gran/VTK ... wear, its
// triangle's value after the bounce): with and without friction and across both
// branches of f(gamma). A plate moving with the grain's tangential velocity wears nothing
// (the velocity is relative to the wall; LIGGGHTS: 1.6e-33).
TEST(MeshWall, FinnieWearMatchesLiggghts) {
  struct Case { double vx, vz, mu, liggghts; };
  const Case cases[] = {{1, 1, 0, 0.13466061625}, {1, 1, 0.5, 0.10674340948}, {3, 1, 0, 0.34121948025},
                        {3, 1, 0.5, 0.39550601854}, {0.3, 1, 0, 0.028419959625}};
  const std::string plate = stl("fplate.stl", floor2(0.05));
  auto run = [&](const Case& c, const std::string& move) {
    Deck d;
    d("units si\natom_style granular\nboundary f f f\nregion box block -0.1 0.1 -0.1 0.1 -0.05 0.1 units box\n"
      "create_box 1 box\nneighbor 0.001 bin\nneigh_modify delay 0\n"
      "fix m1 all property/global youngsModulus peratomtype 5e6\n"
      "fix m2 all property/global poissonsRatio peratomtype 0.45\n"
      "fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n"
      "fix m4 all property/global coefficientFriction peratomtypepair 1 " + std::to_string(c.mu) + "\n"
      "fix m5 all property/global k_finnie peratomtypepair 1 1.0\n"
      "pair_style gran model hertz tangential history\npair_coeff * *\ntimestep 1e-6\n"
      "fix cad all mesh/surface/stress file " + plate + " type 1 wear finnie\n" + move +
      "fix walls all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad\n"
      "create_atoms 1 single -0.01 0 0.0052 units box\nset atom 1 diameter 0.01 density 2500\n"
      "velocity all set " + std::to_string(c.vx) + " 0 " + std::to_string(-c.vz) + " units box\n"
      "fix integr all nve/sphere\ndump dw all mesh/gran/VTK 4000 " + ::testing::TempDir() + "wear_*.vtk stress wear cad\n"
      "run 4000");
    auto* m = dynamic_cast<sable::MeshHolder*>(d->find_fix("cad"));
    return m->mesh().wear;
  };
  for (const Case& c : cases) {
    const std::vector<double> w = run(c, "");
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w[0], 0.0);
    EXPECT_NEAR(w[1] / c.liggghts, 1, 1e-7) << c.vx << " " << c.mu;
    std::ifstream f(::testing::TempDir() + "wear_4000.vtk");
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const std::string head = "SCALARS wear double 1\nLOOKUP_TABLE default\n";
    const auto at = text.find(head);
    ASSERT_NE(at, std::string::npos) << text;
    std::istringstream is(text.substr(at + head.size()));
    double w0 = -1, w1 = -1;
    is >> w0 >> w1;
    EXPECT_EQ(w0, 0.0);
    EXPECT_NEAR(w1, w[1], 1e-14 * w[1]);
  }
  const std::vector<double> w = run(cases[0], "fix mv all move/mesh mesh cad linear 1.0 0 0\n");
  EXPECT_NEAR(w[1], 0, 1e-12 * cases[0].liggghts);
}

// unfix of a move/mesh stops that motion; the mesh stays where it got to:
// the reference point turned by 2 pi (1000 dt) / T, then not further.
TEST(MeshWall, UnfixMoveMeshStopsTheMotion) {
  Deck d;
  d(head());
  d("fix plate all mesh/surface file " + stl("uplate.stl", floor2(0.005)) + " type 1 reference_point 0.004 0 0");
  d("fix spin all move/mesh mesh plate rotate origin 0 0 0 axis 0 0 1 period 0.01\nrun 1000\nunfix spin\nrun 1000");
  const double a = 2 * kPi * 1000 * 1e-6 / 0.01;
  EXPECT_NEAR(fv(d, "plate", 7), 0.004 * std::cos(a), 1e-15);
  EXPECT_NEAR(fv(d, "plate", 8), 0.004 * std::sin(a), 1e-15);
}

// The mesh forces are summed by core's AtomSum (atom order, fixed blocks): 80
// grains thrown onto the bottom of the turning drum of tests/decks/mesh_drum.in
// give the same bits on 1 and 2 threads (positions, velocities, the drum's
// force and torque).
TEST(MeshWall, DrumIsBitIdenticalOnOneAndTwoThreads) {
  const std::string deck = head("f f f", "-0.035 0.035 -0.015 0.015 -0.035 0.035") +
                           "fix drum all mesh/surface/stress file " + SABLE_SOURCE_DIR + "/tests/decks/mesh_drum.stl" +
                           R"( type 1 curvature 1
fix turn all move/mesh mesh drum rotate origin 0 0 0 axis 0 1 0 period 2
fix walls all wall/gran model hertz tangential history mesh n_meshes 1 meshes drum
group grains initialize
region ins block -0.006 0.006 -0.008 0.008 -0.028 -0.018 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.0012
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins grains insert/pack seed 32452867 distributiontemplate pdd insert_every once overlapcheck yes all_in yes vel constant 0 0 -1 particles_in_region 80 region ins
fix grav all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
run 4000)";
  auto run = [&](int threads) {
    sable::ThreadSettings& ts = sable::thread_settings();
    const sable::ThreadSettings saved = ts;
    ts.pair_atoms = ts.pair_entries = ts.loop_work = 0;  // every loop threaded
#ifdef _OPENMP
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
#endif
    Deck d;
    d(deck);
    ts = saved;
#ifdef _OPENMP
    omp_set_num_threads(before);
#endif
    std::vector<double> out(d->atoms.x.begin(), d->atoms.x.begin() + 3 * d->atoms.n);
    out.insert(out.end(), d->atoms.v.begin(), d->atoms.v.begin() + 3 * d->atoms.n);
    for (int k = 1; k <= 6; ++k) out.push_back(fv(d, "drum", k));
    return out;
  };
  const std::vector<double> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(double)));
  EXPECT_LT(one[one.size() - 4], 0.0);  // the grains press on the drum: f_drum[3] < 0
}

// The mesh's candidate triangles are found at neighbour builds and refreshed
// when the mesh has moved half a skin. A plate rising at 2 m/s (one skin per
// 250 steps) onto a grain that never moves (no integrator: no rebuild after
// set-up) touches it at exactly the step where it reaches the grain.
TEST(MeshWall, MovingMeshFasterThanTheSkinIsStillCaught) {
  Deck d;
  d(head());
  d("fix plate all mesh/surface file " + stl("rise.stl", floor2(0.005)) + " type 1");
  d("create_atoms 1 single 0.001 0.0005 0.004 units box\n"
    "fix lift all move/mesh mesh plate linear 0 0 2\n"
    "fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate");
  grains(d);
  long builds = -1, touching = 0;
  g_probe = [&](sable::Simulation& s) {
    if (builds < 0) builds = s.neighbor.builds;
    const double overlap = dynamic_cast<sable::MeshHolder*>(s.find_fix("plate"))->mesh().T[2] - 0.003;
    const double fz = s.find_fix("w")->compute_vector(3);
    if (overlap > 1e-12) {
      EXPECT_LT(fz, 0.0) << "overlap " << overlap;
    } else if (overlap < -1e-12) {
      EXPECT_EQ(fz, 0.0) << "overlap " << overlap;
    }
    touching += fz != 0.0;
  };
  d("fix p all test/probe_mesh\nrun 1700");
  g_probe = nullptr;
  EXPECT_EQ(builds, d->neighbor.builds);  // the grain's list was never rebuilt
  EXPECT_GE(touching, 199);
  EXPECT_LE(touching, 201);
}

// Every step the contacts found among the candidates are those of a brute-force
// search over all triangles: grains thrown into a drum turning 40 times faster
// than in DrumIsBitIdenticalOnOneAndTwoThreads (the mesh refreshes its lists
// every ~60 steps), checked every 5 steps. A grain is in contact iff some
// triangle lies within its radius (brute force), and each contact's triangle does.
TEST(MeshWall, CandidatesFindWhatABruteForceSearchFinds) {
  Deck d;
  d(head("f f f", "-0.035 0.035 -0.015 0.015 -0.035 0.035") + "fix drum all mesh/surface/stress file " +
    SABLE_SOURCE_DIR + "/tests/decks/mesh_drum.stl" +
    R"( type 1 curvature 1
fix turn all move/mesh mesh drum rotate origin 0 0 0 axis 0 1 0 period 0.05
fix walls all wall/gran model hertz tangential history mesh n_meshes 1 meshes drum
group grains initialize
region ins block -0.006 0.006 -0.008 0.008 -0.028 -0.018 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.0012
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins grains insert/pack seed 32452867 distributiontemplate pdd insert_every once overlapcheck yes all_in yes vel constant 0 0 -1 particles_in_region 80 region ins
fix grav all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere)");
  auto* walls = dynamic_cast<sable::FixWallGranMesh*>(d->find_fix("walls"));
  ASSERT_NE(walls, nullptr);
  long checks = 0, contacts = 0;
  g_probe = [&](sable::Simulation& s) {
    if (s.step % 5) return;
    const sable::TriMesh& mesh = dynamic_cast<sable::MeshHolder*>(s.find_fix("drum"))->mesh();
    sable::ContactRecords recs;
    walls->records(~0u, recs);
    std::vector<char> found(s.atoms.n, 0);
    for (const sable::ContactRecord& r : recs.rows) {
      found[r.i] = 1;
      const double* x = &s.atoms.x[3 * r.i];
      const double rad = s.atoms.radius[r.i];
      EXPECT_LT(mesh.closest(walls->element(r.shift), mesh.to_body({x[0], x[1], x[2]})).dist2, rad * rad);
    }
    for (std::size_t i = 0; i < s.atoms.n; ++i) {
      const double* x = &s.atoms.x[3 * i];
      const sable::Vec3d xb = mesh.to_body({x[0], x[1], x[2]});
      bool touch = false;
      for (std::size_t t = 0; t < mesh.ntri() && !touch; ++t) {
        const double d2 = mesh.closest(static_cast<int>(t), xb).dist2;
        touch = d2 < s.atoms.radius[i] * s.atoms.radius[i] && d2 > 0;
      }
      EXPECT_EQ(touch, found[i] != 0) << "grain " << s.atoms.id[i] << " step " << s.step;
      contacts += touch;
    }
    ++checks;
  };
  d("fix p all test/probe_mesh\nrun 4000");
  g_probe = nullptr;
  EXPECT_EQ(checks, 800);
  EXPECT_GT(contacts, 1000);  // the grains reached the drum
}

}  // namespace test_mesh_walls
