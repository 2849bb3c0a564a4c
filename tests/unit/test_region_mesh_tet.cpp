// region mesh/tet: the inside of a tetrahedral VTK mesh (LIGGGHTS syntax), its
// transform (offset, scale, rotations in degrees) and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/geometry/region.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_region_mesh_tet {

using sable::test::Deck;

namespace {

// A cube [lo, lo + a]^3 split into the six tetrahedra around its main diagonal
// (Kuhn's triangulation), plus a surface triangle, an edge and a vertex cell as
// Gmsh writes them (to be skipped).
std::string cube_vtk(double lo, double a) {
  const std::string path = ::testing::TempDir() + "cube_" + std::to_string(lo) + "_" + std::to_string(a) + ".vtk";
  std::ofstream f(path);
  f << "# vtk DataFile Version 2.0\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n";
  for (int p = 0; p < 8; ++p) f << lo + a * (p & 1) << " " << lo + a * ((p >> 1) & 1) << " " << lo + a * ((p >> 2) & 1) << "\n";
  // 0 -> 7 diagonal; the paths 0 -> 7 through one, then two axes
  const int tets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  f << "CELLS 9 39\n1 0\n2 0 1\n3 0 1 3\n";
  for (auto& t : tets) f << "4 " << t[0] << " " << t[1] << " " << t[2] << " " << t[3] << "\n";
  f << "CELL_TYPES 9\n1\n3\n5\n10\n10\n10\n10\n10\n10\n";
  return path;
}

const char* kBox = R"(units si
atom_style granular
region box block -2 2 -2 2 -2 2 units box
create_box 1 box
)";

}  // namespace

// Lattice points inside a cube of tets. As LIGGGHTS 3.8 (whose mesh_tet tutorial
// gives 13 121 grains in both codes), a point on a face is outside, whether the
// face is the cube's or one two tets share: Kuhn's tets are the orderings of
// the three coordinates, so of the sc 0.1 lattice points 0.1 .. 0.9 of the cube
// [0.05, 0.95]^3 only those with three different coordinates count, 9 * 8 * 7.
TEST(RegionMeshTet, LatticeStrictlyInsideCubeOfTets) {
  Deck d;
  d(kBox);
  d("region m mesh/tet file " + cube_vtk(0.05, 0.9) + " scale 1. move 0. 0. 0. rotate 0. 0. 0. units box\n"
    "lattice sc 0.1\ncreate_atoms 1 region m\n");
  EXPECT_EQ(d->atoms.n, 504u);
  const sable::Region* r = d->find_region("m");
  ASSERT_NE(r, nullptr);
  EXPECT_NEAR(r->volume(), 0.9 * 0.9 * 0.9, 1e-12);
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(r->lo[k], 0.05);
    EXPECT_DOUBLE_EQ(r->hi[k], 0.95);
  }
}

// The transform as LIGGGHTS documents it: offset first, then scale, then rotations
// about x, y, z. The unit cube moved by (1,0,0), scaled by 0.5 covers x 0.5..1;
// turned 90 degrees about z, x 0.5..1 becomes y 0.5..1 and y 0..0.5 becomes x -0.5..0
// (the points tested have three different cube coordinates: not on a face).
TEST(RegionMeshTet, OffsetScaleRotate) {
  Deck d;
  d(kBox);
  d("region m mesh/tet file " + cube_vtk(0.0, 1.0) + " scale 0.5 move 1 0 0 rotate 0 0 90 units box\n");
  const sable::Region* r = d->find_region("m");
  ASSERT_NE(r, nullptr);
  const double in[3] = {-0.1, 0.8, 0.35}, out1[3] = {0.8, 0.1, 0.35}, out2[3] = {-0.1, 0.8, 0.6};
  EXPECT_TRUE(r->inside(in));
  EXPECT_FALSE(r->inside(out1));
  EXPECT_FALSE(r->inside(out2));
  EXPECT_NEAR(r->volume(), 0.125, 1e-12);
  EXPECT_NEAR(r->lo[0], -0.5, 1e-12);
  EXPECT_NEAR(r->hi[1], 1.0, 1e-12);
}

// Points on the cube's faces are outside too: the cube [0, 1]^3 adds the 11^3 - 9^3
// lattice points on its faces, none of which counts (still 9 * 8 * 7).
TEST(RegionMeshTet, FacePointsAreOutside) {
  Deck d;
  d(kBox);
  d("region m mesh/tet file " + cube_vtk(0.0, 1.0) + " scale 1 move 0 0 0 rotate 0 0 0 units box\n"
    "lattice sc 0.1\ncreate_atoms 1 region m\n");
  EXPECT_EQ(d->atoms.n, 504u);
  const sable::Region* r = d->find_region("m");
  const double corner[3] = {0, 0, 0}, face[3] = {0.5, 0.25, 0.0}, in[3] = {0.7, 0.5, 0.3};
  EXPECT_FALSE(r->inside(corner));
  EXPECT_FALSE(r->inside(face));
  EXPECT_TRUE(r->inside(in));
}

TEST(RegionMeshTet, Errors) {
  const std::string ok = cube_vtk(0.0, 1.0);
  auto error_of = [](const std::string& text) {
    Deck d;
    return sable::test::error_of(d, text);
  };
  EXPECT_NE(error_of(std::string(kBox) + "region m mesh/tet file nofile.vtk scale 1 move 0 0 0 rotate 0 0 0\n")
                .find("cannot open 'nofile.vtk'"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kBox) + "region m mesh/tet file " + ok + " move 0 0 0 scale 1 rotate 0 0 0\n")
                .find("expected 'scale'"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kBox) + "region m mesh/tet file " + ok + " scale -1 move 0 0 0 rotate 0 0 0\n")
                .find("a scale factor > 0"),
            std::string::npos);
  const std::string flat = ::testing::TempDir() + "no_tets.vtk";
  std::ofstream(flat) << "# vtk DataFile Version 2.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 0\n1 0 0\n0 1 0\n"
                         "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n";
  EXPECT_NE(error_of(std::string(kBox) + "region m mesh/tet file " + flat + " scale 1 move 0 0 0 rotate 0 0 0\n")
                .find("has none"),
            std::string::npos);
}

}  // namespace test_region_mesh_tet
