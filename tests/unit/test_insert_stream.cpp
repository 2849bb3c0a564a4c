// fix insert/stream (LIGGGHTS 3.8 semantics, fixes/fix_insert_stream.cpp):
// the flight of a grain from the extruded volume to the face and its release,
// the extrusion from insert_every + duration, and a restart followed by
// reset_timestep (the insertion schedule and the grains in flight move with
// the counter). The schedule and the checks of tests/decks/insert_stream.in
// are not repeated here.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_insert_stream {

using sable::test::Deck;

namespace {

// Face: the square [0.03, 0.07]^2 at z = 0.08, written here; vel (0.1, 0, -1):
// v_n = (0, 0, -1). No contacts, no gravity.
std::string face_file() {
  static const std::string path =
      (std::filesystem::temp_directory_path() / ("sable_stream_face_" + std::to_string(::getpid()) + ".stl")).string();
  if (!std::filesystem::exists(path)) {
    FILE* f = std::fopen(path.c_str(), "w");
    std::fputs(
        "solid f\nfacet normal 0 0 1\nouter loop\nvertex 0.03 0.03 0.08\nvertex 0.07 0.03 0.08\nvertex 0.07 0.07 0.08\n"
        "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0.03 0.03 0.08\nvertex 0.07 0.07 0.08\n"
        "vertex 0.03 0.07 0.08\nendloop\nendfacet\nendsolid f\n",
        f);
    std::fclose(f);
  }
  return path;
}

std::string box() {
  return R"(units si
atom_style granular
boundary f f f
region box block 0 0.1 0 0.1 -0.5 0.2 units box
create_box 1 box
timestep 1e-5
)";
}

const char* kGrains = R"(fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.001
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix integr all nve/sphere
)";

std::string stream(const std::string& more) {
  return "fix face all mesh/surface file " + face_file() +
         " type 1\nfix ins all insert/stream seed 49979687 distributiontemplate pdd vel constant 0.1 0 -1 "
         "insertion_face face " + more + "\n";
}

}  // namespace

// One grain (50 per s x 2000 steps x 1e-5 s = 1 per insertion): until its
// release step 1 + int(d / (|v_n| dt)) it sits at x0 + v_n (s - 1) dt with
// v = v_n and no spin; at that step it takes vel, then moves at vel (no force acts).
TEST(InsertStream, FlightThenRelease) {
  Deck d;
  d(box())(kGrains)(stream("nparticles 1 particlerate 50 extrude_length 0.02"));
  d("run 1");
  ASSERT_EQ(d->atoms.n, 1u);
  const double x0[3] = {d->atoms.x[0], d->atoms.x[1], d->atoms.x[2]};
  const double depth = x0[2] - 0.08;
  ASSERT_GE(depth, 0.001);
  ASSERT_LE(depth, 0.021);
  const long release = 1 + static_cast<long>((depth + 1e-14) / 1e-5);
  d("run " + std::to_string(release - 2));  // to the step before the release
  EXPECT_EQ(d->step, release - 1);
  EXPECT_DOUBLE_EQ(d->atoms.x[0], x0[0]);
  EXPECT_DOUBLE_EQ(d->atoms.x[2], x0[2] - (release - 2) * 1e-5);
  EXPECT_EQ(d->atoms.v[0], 0.0);
  EXPECT_EQ(d->atoms.v[2], -1.0);
  EXPECT_GE(d->atoms.x[2] - 0.08, 1e-5 * (1 - 1e-9));  // still upstream of the face
  d("run 1");
  EXPECT_EQ(d->atoms.v[0], 0.1);
  EXPECT_EQ(d->atoms.v[2], -1.0);
  const double zr = d->atoms.x[2];
  EXPECT_LT(zr - 0.08, 1e-5);  // released within one step's travel of the face
  EXPECT_GE(zr - 0.08, -1e-12);
  d("run 100");
  EXPECT_NEAR(d->atoms.x[0], x0[0] + 0.1 * 100 * 1e-5, 1e-14);
  EXPECT_NEAR(d->atoms.x[2], zr - 100 * 1e-5, 1e-14);
}

// insert_every K with duration D: L = D |v_n| dt = 1000 * 1 * 1e-5 = 0.01, so
// centres lie r .. L + r above the face; 100 grains every 2000 steps.
TEST(InsertStream, DurationSetsTheExtrusion) {
  Deck d;
  d(box())(kGrains)(stream("nparticles 300 particlerate 5000 insert_every 2000 duration 1000"));
  d("run 1");
  ASSERT_EQ(d->atoms.n, 100u);
  double lo = 1, hi = -1;
  for (std::size_t i = 0; i < d->atoms.n; ++i)
    lo = std::min(lo, d->atoms.x[3 * i + 2]), hi = std::max(hi, d->atoms.x[3 * i + 2]);
  EXPECT_GE(lo, 0.081 - 1e-12);
  EXPECT_LE(hi, 0.091 + 1e-12);
  EXPECT_GT(hi - lo, 0.008);  // 100 uniform depths span nearly all of L
  d("run 2000");
  EXPECT_EQ(d->atoms.n, 200u);
}

// A restart written while grains fly, then reset_timestep 0 and 50000 (as
// LIGGGHTS' tutorial insert_stream_reset_timestep does): the next insertion
// comes the same number of steps later (LIGGGHTS 3.8 moved it the same way:
// 120001 -> 70000 in that tutorial) and every grain follows the same path, to
// the bit, as in the run that went on without a restart.
TEST(InsertStream, RestartAndResetTimestepKeepTheFlight) {
  const std::string fix = "nparticles 300 particlerate 5000 extrude_length 0.02";
  Deck a;
  a(box())(kGrains)(stream(fix))("run 3000")("run 2000");
  ASSERT_EQ(a->atoms.n, 300u);  // steps 1, 2001, 4001

  const auto file = std::filesystem::temp_directory_path() / ("sable_stream_" + std::to_string(::getpid()) + ".restart");
  Deck c;
  c(box())(kGrains)(stream(fix))("run 3000")("write_restart " + file.string());
  ASSERT_EQ(c->atoms.n, 200u);
  Deck r;
  r("units si\natom_style granular\nread_restart " + file.string());
  std::filesystem::remove(file);
  r("timestep 1e-5\n")(kGrains)(stream(fix))("reset_timestep 0")("reset_timestep 50000")("run 999");
  EXPECT_EQ(r->atoms.n, 200u);  // the insertion due at 4001 now comes at 51001
  r("run 1001");
  ASSERT_EQ(r->atoms.n, a->atoms.n);
  EXPECT_EQ(r->step, 52000);
  long differ = 0;  // by atom ID: the runs' neighbour sorts need not order the atoms alike
  for (std::size_t i = 0; i < a->atoms.n; ++i) {
    const std::size_t j = r->atoms.index_of(a->atoms.id[i]);
    ASSERT_NE(j, sable::Atoms::npos);
    differ += std::memcmp(&a->atoms.x[3 * i], &r->atoms.x[3 * j], 3 * sizeof(double)) != 0 ||
              std::memcmp(&a->atoms.v[3 * i], &r->atoms.v[3 * j], 3 * sizeof(double)) != 0;
  }
  EXPECT_EQ(differ, 0);
}

}  // namespace test_insert_stream
