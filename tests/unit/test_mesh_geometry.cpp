// core/mesh: STL reading (ASCII and binary), welding and active edges,
// closest-point classification and the bin search, against hand-computed
// values and brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "core/geometry/mesh.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_mesh_geometry {

using sable::TriMesh;
using sable::Vec3d;

namespace {

// Two triangles of the unit square z = 0, normals +z, sharing the diagonal (0,0,0)-(1,1,0).
const std::vector<double> kSquare = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};

std::string temp_path(const char* name) { return std::string(::testing::TempDir()) + name; }

void write_ascii(const std::string& path, const std::vector<double>& xyz) {
  std::ofstream f(path);
  f << "solid test\n";
  for (std::size_t t = 0; t < xyz.size() / 9; ++t) {
    f << "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k) f << "      vertex " << xyz[9 * t + 3 * k] << " " << xyz[9 * t + 3 * k + 1] << " " << xyz[9 * t + 3 * k + 2] << "\n";
    f << "    endloop\n  endfacet\n";
  }
  f << "endsolid test\n";
}

void write_binary(const std::string& path, const std::vector<double>& xyz) {
  std::ofstream f(path, std::ios::binary);
  char header[80] = "solid binary written by the test (starts like ASCII on purpose)";
  f.write(header, 80);
  const std::uint32_t n = static_cast<std::uint32_t>(xyz.size() / 9);
  f.write(reinterpret_cast<const char*>(&n), 4);
  for (std::uint32_t t = 0; t < n; ++t) {
    float rec[12] = {0, 0, 0};
    for (int k = 0; k < 9; ++k) rec[3 + k] = static_cast<float>(xyz[9 * t + k]);
    f.write(reinterpret_cast<const char*>(rec), 48);
    const std::uint16_t attr = 0;
    f.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

// Closed unit cube [0,1]^3, 12 triangles, outward normals.
std::vector<double> cube() {
  std::vector<double> out;
  auto quad = [&](Vec3d a, Vec3d b, Vec3d c, Vec3d d) {  // a b c d counter-clockwise seen from outside
    for (Vec3d p : {a, b, c, a, c, d}) out.insert(out.end(), p.begin(), p.end());
  };
  quad({0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0});  // z = 0, normal -z
  quad({0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1});  // z = 1
  quad({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1});  // y = 0
  quad({0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0});  // y = 1
  quad({0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0});  // x = 0
  quad({1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1});  // x = 1
  return out;
}

int edge_between(const TriMesh& m, int t, int u) {
  for (int k = 0; k < 3; ++k)
    if (m.nbr[3 * t + k] == u) return k;
  return -1;
}

}  // namespace

TEST(MeshGeometry, AsciiAndBinaryStlReadEqual) {
  const std::string a = temp_path("mesh_square_ascii.stl"), b = temp_path("mesh_square_binary.stl");
  write_ascii(a, kSquare);
  write_binary(b, kSquare);
  TriMesh ma = TriMesh::read_stl(a), mb = TriMesh::read_stl(b);
  ma.build(0.256235);
  mb.build(0.256235);
  ASSERT_EQ(ma.ntri(), 2u);
  ASSERT_EQ(mb.ntri(), 2u);
  EXPECT_EQ(ma.vert.size(), 12u);  // 6 corners welded to 4 vertices
  EXPECT_EQ(ma.tri, mb.tri);
  ASSERT_EQ(ma.vert.size(), mb.vert.size());
  for (std::size_t i = 0; i < ma.vert.size(); ++i) EXPECT_EQ(ma.vert[i], mb.vert[i]);  // exact in float32
}

TEST(MeshGeometry, BadStlNamesTheFile) {
  const std::string p = temp_path("mesh_bad.stl");
  std::ofstream(p) << "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0\n";
  try {
    TriMesh::read_stl(p);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("line 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(TriMesh::read_stl(temp_path("no_such_file.stl")), std::runtime_error);
}

// Hand-computed: triangle (0,0,0) (1,0,0) (0,1,0).
TEST(MeshGeometry, ClosestPointRegions) {
  TriMesh m = TriMesh::from_triangles({0, 0, 0, 1, 0, 0, 0, 1, 0});
  m.build(0.256235);
  auto c = m.closest(0, {0.25, 0.25, 0.5});
  EXPECT_EQ(c.region, TriMesh::Region::Face);
  EXPECT_DOUBLE_EQ(c.p[0], 0.25);
  EXPECT_DOUBLE_EQ(c.p[1], 0.25);
  EXPECT_DOUBLE_EQ(c.dist2, 0.25);
  c = m.closest(0, {0.5, -1, 0});  // below edge 0 (corner 0 -> 1)
  EXPECT_EQ(c.region, TriMesh::Region::Edge);
  EXPECT_EQ(c.k, 0);
  EXPECT_DOUBLE_EQ(c.p[0], 0.5);
  EXPECT_DOUBLE_EQ(c.dist2, 1.0);
  c = m.closest(0, {1, 1, 0});  // beyond the hypotenuse, edge 1 (corner 1 -> 2): closest (0.5, 0.5, 0)
  EXPECT_EQ(c.region, TriMesh::Region::Edge);
  EXPECT_EQ(c.k, 1);
  EXPECT_DOUBLE_EQ(c.p[0], 0.5);
  EXPECT_DOUBLE_EQ(c.dist2, 0.5);
  c = m.closest(0, {-1, 0.5, 1});  // edge 2 (corner 2 -> 0), x = 0
  EXPECT_EQ(c.region, TriMesh::Region::Edge);
  EXPECT_EQ(c.k, 2);
  EXPECT_DOUBLE_EQ(c.p[1], 0.5);
  EXPECT_DOUBLE_EQ(c.dist2, 2.0);
  c = m.closest(0, {-1, -1, 0});
  EXPECT_EQ(c.region, TriMesh::Region::Corner);
  EXPECT_EQ(c.k, 0);
  c = m.closest(0, {2, -0.5, 0});
  EXPECT_EQ(c.region, TriMesh::Region::Corner);
  EXPECT_EQ(c.k, 1);
  EXPECT_DOUBLE_EQ(c.dist2, 1.25);
  c = m.closest(0, {-0.5, 2, 3});
  EXPECT_EQ(c.region, TriMesh::Region::Corner);
  EXPECT_EQ(c.k, 2);
  EXPECT_DOUBLE_EQ(c.dist2, 0.25 + 1 + 9);
}

TEST(MeshGeometry, CoplanarEdgeInactiveRightAngleActive) {
  TriMesh sq = TriMesh::from_triangles(kSquare);
  sq.build(0.256235);
  const int k = edge_between(sq, 0, 1);
  ASSERT_GE(k, 0);
  EXPECT_FALSE(sq.edge_active[k]);
  EXPECT_TRUE(sq.same_surface(0, 1));
  // The outer edges bound the mesh: active, as are all four corners.
  for (int q = 0; q < 3; ++q)
    if (q != k) {
      EXPECT_TRUE(sq.edge_active[q]);
    }

  TriMesh box = TriMesh::from_triangles(cube());
  box.build(0.256235);
  EXPECT_EQ(box.vert.size(), 24u);  // 8 vertices
  int inactive = 0, active = 0;
  for (std::size_t t = 0; t < box.ntri(); ++t)
    for (int q = 0; q < 3; ++q) {
      ASSERT_GE(box.nbr[3 * t + q], 0);  // closed: every edge has a neighbour
      (box.edge_active[3 * t + q] ? active : inactive)++;
    }
  EXPECT_EQ(inactive, 12);  // 6 face diagonals, seen from both sides
  EXPECT_EQ(active, 24);    // 12 cube edges (90 deg), seen from both sides
  EXPECT_FALSE(box.same_surface(0, 2));  // floor and top
  EXPECT_TRUE(box.same_surface(0, 1));

  // A triangle stored with the other winding (normal -z) is still one surface with its neighbour.
  std::vector<double> flipped = kSquare;
  std::swap_ranges(flipped.begin() + 12, flipped.begin() + 15, flipped.begin() + 15);  // swap its last two corners
  TriMesh fl = TriMesh::from_triangles(flipped);
  fl.build(0.256235);
  EXPECT_LT(fl.normal[5], 0.0);
  EXPECT_TRUE(fl.same_surface(0, 1));

  // A fold of 0.2 deg is one surface at the default curvature, not at 0.1 deg.
  const double s = std::sin(0.2 * M_PI / 180), c = std::cos(0.2 * M_PI / 180);
  const std::vector<double> fold = {0, 0, 0, 0, 1, 0, -1, 0, 0, 0, 1, 0, 0, 0, 0, c, 0, s};  // hinge: the y axis
  TriMesh f1 = TriMesh::from_triangles(fold), f2 = TriMesh::from_triangles(fold);
  f1.build(0.256235);
  f2.build(0.1);
  EXPECT_TRUE(f1.same_surface(0, 1));
  EXPECT_FALSE(f2.same_surface(0, 1));
}

TEST(MeshGeometry, BinSearchEqualsBruteForce) {
  TriMesh box = TriMesh::from_triangles(cube());
  box.scale(0.02);
  box.translate({-0.01, 0.003, 0.5});
  box.build(0.256235);
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> pos(-0.02, 0.02), rad(0.0005, 0.008);
  std::vector<int> a, b;
  int hits = 0;
  for (int s = 0; s < 20000; ++s) {
    const Vec3d x{pos(rng) - 0.0, pos(rng) + 0.013, pos(rng) + 0.51};
    const double r = rad(rng);
    box.near(x, r, a);
    box.near_brute(x, r, b);
    ASSERT_EQ(a, b) << "sphere " << s;
    hits += !a.empty();
  }
  EXPECT_GT(hits, 2000);  // the test exercises contacts, not only misses
}

TEST(MeshGeometry, LoadTransformsApplyInOrder) {
  TriMesh m = TriMesh::from_triangles({1, 0, 0, 2, 0, 0, 1, 1, 0});
  m.scale(2);                   // (2,0,0)
  m.rotate({0, 0, 1}, 90);      // (0,2,0)
  m.translate({1, 0, 0});       // (1,2,0)
  m.build(0.256235);
  EXPECT_NEAR(m.vert[0], 1, 1e-15);
  EXPECT_NEAR(m.vert[1], 2, 1e-15);
}

// Rigid rotation: a point of the surface moves on a circle, its velocity is omega x r.
TEST(MeshGeometry, RigidRotationPoseAndVelocity) {
  TriMesh m = TriMesh::from_triangles({1, 0, 0, 2, 0, 0, 1, 1, 0});
  m.build(0.256235);
  TriMesh::Motion rot;
  rot.rotate = true;
  rot.origin = {0, 0, 0};
  rot.axis = {0, 0, 1};
  rot.omega = M_PI / 2;  // quarter turn per time unit
  m.motions.push_back(rot);
  m.advance_to(0, 1e-3);
  m.advance_to(1000, 1e-3);
  const Vec3d p = m.to_world({1, 0, 0});
  EXPECT_NEAR(p[0], 0, 1e-12);
  EXPECT_NEAR(p[1], 1, 1e-12);
  const Vec3d v = m.velocity(p);
  EXPECT_NEAR(v[0], -M_PI / 2, 1e-12);
  EXPECT_NEAR(v[1], 0, 1e-12);
  const Vec3d b = m.to_body(p);
  EXPECT_NEAR(b[0], 1, 1e-12);
  EXPECT_NEAR(b[1], 0, 1e-12);
}

// Two motions superpose (LIGGGHTS: two move/mesh on one mesh): a surface
// point's central difference over two steps is its velocity (linear +
// omega x r) up to the order of the two increments within a step,
// omega |v| dt = 4e-6 here (tolerance 1e-5).
TEST(MeshGeometry, LinearAndRotationSuperpose) {
  TriMesh m = TriMesh::from_triangles({1, 0, 0, 2, 0, 0, 1, 1, 0});
  m.build(0.256235);
  TriMesh::Motion lin, rot;
  lin.v = {0.3, -0.2, 0.1};
  rot.rotate = true;
  rot.origin = {0.5, 0.5, 0};
  rot.axis = {0, 0, 1};
  rot.omega = 10;
  m.motions = {lin, rot};
  const double dt = 1e-6;
  m.advance_to(0, dt);
  m.advance_to(4999, dt);
  const Vec3d pm = m.to_world({2, 0, 0});
  m.advance_to(5000, dt);
  const Vec3d p0 = m.to_world({2, 0, 0});
  const Vec3d v = m.velocity(p0);
  m.advance_to(5001, dt);
  const Vec3d pp = m.to_world({2, 0, 0});
  for (int k = 0; k < 3; ++k) EXPECT_NEAR((pp[k] - pm[k]) / (2 * dt), v[k], 1e-5) << k;
  // the velocity field itself: v = v_lin + omega e_z x (p - origin)
  EXPECT_NEAR(v[0], 0.3 - 10 * (p0[1] - 0.5), 1e-12);
  EXPECT_NEAR(v[1], -0.2 + 10 * (p0[0] - 0.5), 1e-12);
  EXPECT_NEAR(v[2], 0.1, 1e-15);
}

}  // namespace test_mesh_geometry
