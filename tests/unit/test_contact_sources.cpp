// contact_sources(): the pair style's grain pairs, a primitive wall and a mesh wall
// behind one interface (core/engine/contact_source.h), in the deck's order, each
// giving its contacts' records; the values against LIGGGHTS' Hertz law by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/engine/contact_source.h"
#include "tests/unit/deck_runner.h"
#include "tests/unit/right_wall_scene.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_sources {

using sable::ContactRecords;
using sable::ContactSource;
using sable::test::Deck;
using namespace sable::test::right_wall;

namespace {

// Two triangles covering the plane y = Y over the whole box (x, z in [-0.02, 0.02]).
std::string floor_stl(double y) {
  const std::string path = ::testing::TempDir() + "contact_sources_floor.stl";
  std::ofstream f(path);
  f.precision(17);
  auto tri = [&](double x0, double z0, double x1, double z1, double x2, double z2) {
    f << "facet normal 0 1 0\nouter loop\nvertex " << x0 << " " << y << " " << z0 << "\nvertex " << x1 << " " << y
      << " " << z1 << "\nvertex " << x2 << " " << y << " " << z2 << "\nendloop\nendfacet\n";
  };
  f << "solid floor\n";
  tri(-0.02, -0.02, 0.02, -0.02, 0.02, 0.02);
  tri(-0.02, -0.02, 0.02, 0.02, -0.02, 0.02);
  f << "endsolid\n";
  return path;
}

constexpr double kFloor = -0.004, kWallOverlap = 3e-5, kFloorOverlap = 2e-5;

// A touching pair, a grain pressed into the plane x = 0.01 and one into the mesh floor.
void scene(Deck& d) {
  d(kScene);
  d("fix floor all mesh/surface file " + floor_stl(kFloor) + " type 1");
  d("fix mw all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor");
  const double at[4][2] = {{-0.005, 0.005},
                           {-0.005 + 2 * kR - 1e-5, 0.005},
                           {kWall - kR + kWallOverlap, 0.012},
                           {0.0, kFloor + kR - kFloorOverlap}};
  for (const auto& p : at)
    d("create_atoms 1 single " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " 0 units box");
  for (std::size_t i = 0; i < d->atoms.n; ++i) d->atoms.set_radius_density(i, kR, kRho);
  d("run 0");
}

}  // namespace

TEST(ContactSources, PairsThenFixesInTheDecksOrder) {
  Deck d;
  scene(d);
  const auto sources = sable::contact_sources(*d);
  ASSERT_EQ(sources.size(), 3u);
  EXPECT_EQ(sources[0]->contact_kind(), ContactSource::Kind::Pairs);
  EXPECT_EQ(sources[1]->contact_kind(), ContactSource::Kind::Wall);
  EXPECT_EQ(sources[2]->contact_kind(), ContactSource::Kind::Mesh);
  EXPECT_EQ(sources[0], sable::pair_contacts(*d));
  EXPECT_EQ(sources[1], sable::contact_source_of_fix(*d, "right"));
  EXPECT_EQ(sources[2], sable::contact_source_of_fix(*d, "mw"));
  EXPECT_EQ(sable::contact_source_of_fix(*d, "floor"), nullptr);  // a mesh holder, not a contact source
  EXPECT_EQ(sable::contact_source_of_fix(*d, "m1"), nullptr);
  EXPECT_EQ(sable::contact_source_of_fix(*d, "nowhere"), nullptr);
  EXPECT_EQ(sources[1]->plane_axis(), 0);
  EXPECT_EQ(sources[2]->plane_axis(), -1);
  for (ContactSource* s : sources) EXPECT_EQ(s->history_slots().size(), 3u) << s->law_name();  // the shear spring
}

// Each source records only its own contact, with Hertz' force F = 4/3 Y* sqrt(R*) delta^1.5 at
// rest (no dashpot, no spring yet): R* = r/2 for the equal pair (4/3 Y* sqrt(r/2) = hertz / sqrt 2),
// R* = r for both walls; the wall point on the wall, the triangle one of the mesh's two.
TEST(ContactSources, EachSourceRecordsItsContactWithHertzForce) {
  Deck d;
  scene(d);
  ContactRecords rec;
  const auto sources = sable::contact_sources(*d);
  const double want[3] = {hertz(1e-5) / std::sqrt(2.0), hertz(kWallOverlap), hertz(kFloorOverlap)};
  const long grain[3] = {1, 3, 4};
  for (int k = 0; k < 3; ++k) {
    sources[k]->records(d->groups.bit(0), rec);
    ASSERT_EQ(rec.rows.size(), 1u) << k;
    const auto& c = rec.rows[0];
    EXPECT_EQ(d->atoms.id[c.i], grain[k]) << k;
    const double f = std::sqrt(c.f[0] * c.f[0] + c.f[1] * c.f[1] + c.f[2] * c.f[2]);
    EXPECT_NEAR(f, want[k], 1e-9 * want[k]) << k;
  }
  sources[1]->records(d->groups.bit(0), rec);
  EXPECT_NEAR(sources[1]->wall_point(rec.rows[0].shift)[0], kWall, 1e-15);
  EXPECT_EQ(sources[1]->wall_velocity(rec.rows[0].shift)[0], 0.0);
  EXPECT_EQ(sources[1]->element(rec.rows[0].shift), 0);
  sources[2]->records(d->groups.bit(0), rec);
  EXPECT_NEAR(sources[2]->wall_point(rec.rows[0].shift)[1], kFloor, 1e-15);
  const int tri = sources[2]->element(rec.rows[0].shift);
  EXPECT_TRUE(tri == 0 || tri == 1) << tri;
}

// The primitive wall's last force pass: the same contact and force as its records,
// until the atoms change (then it declines and records() is the way).
TEST(ContactSources, WallLastPassUntilTheAtomsChange) {
  Deck d;
  scene(d);
  ContactSource* wall = sable::contact_source_of_fix(*d, "right");
  int seen = 0;
  double fx = 0;
  EXPECT_TRUE(wall->last_pass([&](int i, const double* p, const double* f) {
    ++seen;
    EXPECT_EQ(d->atoms.id[i], 3);
    EXPECT_NEAR(p[0], kWall, 1e-15);
    fx = f[0];
  }));
  EXPECT_EQ(seen, 1);
  EXPECT_NEAR(fx, -hertz(kWallOverlap), 1e-9 * hertz(kWallOverlap));  // pushed away from the wall
  d("create_atoms 1 single -0.008 0.018 0 units box");
  EXPECT_FALSE(wall->last_pass([&](int, const double*, const double*) { ++seen; }));
  EXPECT_EQ(seen, 1);
  EXPECT_EQ(sable::contact_source_of_fix(*d, "mw")->last_pass([](int, const double*, const double*) {}), false);
}

}  // namespace test_contact_sources
