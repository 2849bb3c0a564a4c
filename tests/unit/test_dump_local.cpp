// dump local over compute wall/gran/local: three grains at rest pressed into a
// plane wall with chosen overlaps (analytic Hertz forces); every record holds
// exactly the compute's rows, the file parses in LAMMPS' format, a step
// without contacts writes an empty record, and bad values name their word.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/engine/compute.h"
#include "tests/unit/deck_runner.h"
#include "tests/unit/right_wall_scene.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_dump_local {

using sable::test::Deck;
using sable::test::error_of;
using sable::test::TempDir;

namespace {

using namespace sable::test::right_wall;
const std::string kHead = std::string(kScene) + R"(
create_atoms 1 single 0.00921 0.0005 0 units box
create_atoms 1 single 0.00922 0.0035 0 units box
create_atoms 1 single 0.009204 0.0075 0 units box
compute wl all wall/gran/local pos id force)";
// overlaps 1e-5, 2e-5, 4e-6 (x = 0.01 - r + delta)
const double kDelta[3] = {1e-5, 2e-5, 4e-6};

// LIGGGHTS' Hertz against a wall: F = 4/3 Y* sqrt(r) delta^1.5, Y* = E / (2 (1 - nu^2)).

void setup(Deck& d) {
  d(kHead);
  for (std::size_t i = 0; i < d->atoms.n; ++i) d->atoms.set_radius_density(i, kR, kRho);
}

struct Record {
  long step = -1;
  std::size_t n = 0;
  std::string bounds, columns;
  std::vector<std::vector<std::string>> rows;  // values as written
};

// Reads LAMMPS' dump local text; a malformed file fails the test.
std::vector<Record> parse(const std::string& path) {
  std::ifstream in(path);
  std::vector<Record> out;
  std::string line;
  auto expect = [&](const std::string& head) {
    EXPECT_TRUE(std::getline(in, line)) << "missing " << head;
    EXPECT_EQ(line.rfind(head, 0), 0u) << "got '" << line << "', expected " << head;
    return line.substr(std::min(line.size(), head.size()));
  };
  while (std::getline(in, line)) {
    EXPECT_EQ(line, "ITEM: TIMESTEP");
    Record r;
    std::getline(in, line);
    r.step = std::stol(line);
    expect("ITEM: NUMBER OF ENTRIES");
    std::getline(in, line);
    r.n = std::stoul(line);
    r.bounds = expect("ITEM: BOX BOUNDS ");
    for (int k = 0; k < 3; ++k) {
      std::getline(in, line);
      double lo, hi;
      EXPECT_EQ(std::sscanf(line.c_str(), "%lf %lf", &lo, &hi), 2) << line;
    }
    r.columns = expect("ITEM: ENTRIES ");
    for (std::size_t k = 0; k < r.n; ++k) {
      EXPECT_TRUE(std::getline(in, line));
      std::istringstream ws(line);
      std::vector<std::string> w;
      for (std::string s; ws >> s;) w.push_back(s);
      r.rows.push_back(w);
    }
    out.push_back(r);
  }
  return out;
}

std::string g(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

int col(sable::Compute* c, const std::string& name) {
  for (int k = 0; k < c->local_cols; ++k)
    if (c->local_names[k] == name) return k;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

}  // namespace

TEST(DumpLocal, RecordsHoldTheComputesRowsAndHertzForces) {
  TempDir tmp;
  Deck d;
  setup(d);
  sable::Compute* c = d->find_compute("wl");
  // grain id is the third id column (wall index, 0, grain id); y1 the contact point on the wall.
  const int cid = col(c, "id1") + 3, cy = col(c, "y1"), cfx = col(c, "fx");
  const std::string cols = "index c_wl[" + std::to_string(cid) + "] c_wl[" + std::to_string(cy + 1) + "] c_wl[" +
                           std::to_string(cfx + 1) + "] c_wl[" + std::to_string(cfx + 2) + "]";
  d("dump dl all local 5 " + (tmp / "wall.txt") + " " + cols);
  d("run 10");
  // The compute's rows at step 10, as the last record must hold them.
  c->local_now();
  ASSERT_EQ(c->local_rows(), 3u);
  // Grains away from the wall: step 15 has no contact.
  d("displace_atoms all move -0.001 0 0 units box");
  d("run 5");

  const std::vector<Record> recs = parse(tmp / "wall.txt");
  ASSERT_EQ(recs.size(), 4u);  // steps 0, 5, 10, 15 (step 10 once)
  for (int k = 0; k < 4; ++k) EXPECT_EQ(recs[k].step, 5 * k);
  EXPECT_EQ(recs[0].bounds, "ff ff ff");
  EXPECT_EQ(recs[0].columns, cols);
  const Record& r = recs[2];
  ASSERT_EQ(r.n, 3u);
  const int nc = c->local_cols;
  for (std::size_t k = 0; k < 3; ++k) {
    const double* row = &c->local[k * nc];
    ASSERT_EQ(r.rows[k].size(), 5u);
    EXPECT_EQ(r.rows[k][0], std::to_string(k + 1));
    EXPECT_EQ(r.rows[k][1], g(row[cid - 1]));
    EXPECT_EQ(r.rows[k][2], g(row[cy]));
    EXPECT_EQ(r.rows[k][3], g(row[cfx]));
    EXPECT_EQ(r.rows[k][4], g(row[cfx + 1]));
    // The wall pushes grain id k+1 along -x with the Hertz force of its overlap (the force on the grain).
    const int gid = static_cast<int>(row[cid - 1]);
    ASSERT_GE(gid, 1);
    ASSERT_LE(gid, 3);
    const double f = hertz(kDelta[gid - 1]);
    EXPECT_NEAR(row[cfx], -f, 1e-9 * f) << "grain " << gid;  // the overlap carries the rounding of 0.01 - r + delta
    EXPECT_EQ(row[cfx + 1], 0.0);
    EXPECT_NEAR(std::stod(r.rows[k][3]), -f, 1e-5 * f);
    EXPECT_EQ(row[cy], d->atoms.x[3 * d->atoms.index_of(gid) + 1]);
  }
  EXPECT_EQ(recs[1].rows, recs[0].rows);  // nothing moves between records
  EXPECT_EQ(recs[3].n, 0u);
  EXPECT_TRUE(recs[3].rows.empty());
}

TEST(DumpLocal, BadValuesNameTheirWord) {
  TempDir tmp;
  Deck d;
  setup(d);
  d("compute ke all ke");
  const std::string pre = "dump dl all local 5 " + (tmp / "x.txt") + " ";
  const std::string e1 = error_of(d, pre + "c_nope[1]");
  EXPECT_NE(e1.find("test:1"), std::string::npos) << e1;
  EXPECT_NE(e1.find("'c_nope[1]'"), std::string::npos) << e1;
  EXPECT_NE(error_of(d, pre + "c_ke[1]").find("'c_ke[1]'"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "c_wl[13]").find("1..12"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "c_wl[0]").find("'c_wl[0]'"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "c_wl").find("'c_wl'"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "x").find("'x'"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "index").find("at least one c_ID[k]"), std::string::npos);
  // Computes of different row counts: found when written, naming the value.
  d("compute pl all pair/gran/local id");
  d(pre + "c_wl[1] c_pl[1]");
  const std::string e2 = error_of(d, "run 0");
  EXPECT_NE(e2.find("'c_pl[1]'"), std::string::npos) << e2;
  EXPECT_NE(e2.find("same number of rows"), std::string::npos) << e2;
}

// dump local over compute wall/gran/slices' rows: the one wall's contacts, the
// force on the wall (+x on the right wall), summing to f_ID[1].
TEST(DumpLocal, SlicesRowsOfOneWall) {
  TempDir tmp;
  Deck d;
  setup(d);
  d("compute sl all wall/gran/slices right 10 dim y lo 0 hi 0.01");
  d("dump dl all local 1 " + (tmp / "rows.txt") + " c_sl[1] c_sl[3] c_sl[5] c_sl[6]");
  d("run 0");
  const std::vector<Record> recs = parse(tmp / "rows.txt");
  ASSERT_EQ(recs.size(), 1u);
  ASSERT_EQ(recs[0].n, 3u);
  EXPECT_EQ(recs[0].columns, "c_sl[1] c_sl[3] c_sl[5] c_sl[6]");
  double sum = 0;
  for (const auto& row : recs[0].rows) {
    ASSERT_EQ(row.size(), 4u);
    const int id = std::stoi(row[0]);
    const double f = hertz(kDelta[id - 1]);
    EXPECT_NEAR(std::stod(row[2]), f, 1e-5 * f);
    EXPECT_EQ(row[3], "0");
    sum += std::stod(row[2]);
  }
  EXPECT_NEAR(sum, d->find_fix("right")->compute_vector(1), 1e-5 * sum);
}

// dump_modify format: %.17g gives the compute's doubles back exactly; a bad
// format or sort names its word.
TEST(DumpLocal, FormatFloatGivesFullPrecision) {
  TempDir tmp;
  Deck d;
  setup(d);
  d("compute sl all wall/gran/slices right 10 dim y lo 0 hi 0.01");
  const std::string pre = "dump dl all local 1 " + (tmp / "rows.txt") + " index c_sl[1] c_sl[5]";
  d(pre);
  d("dump_modify dl format float %.17g");
  d("run 0");
  sable::Compute* c = d->find_compute("sl");
  c->local_now();
  const std::vector<Record> recs = parse(tmp / "rows.txt");
  ASSERT_EQ(recs.size(), 1u);
  ASSERT_EQ(recs[0].n, c->local_rows());
  for (std::size_t r = 0; r < recs[0].n; ++r) {
    EXPECT_EQ(recs[0].rows[r][0], std::to_string(r + 1));
    EXPECT_EQ(std::stod(recs[0].rows[r][2]), c->local[r * 7 + 4]);  // bit for bit
  }
  EXPECT_NE(error_of(d, "dump_modify dl format float %d").find("'%d'"), std::string::npos);
  EXPECT_NE(error_of(d, "dump_modify dl format float %g%s").find("'%g%s'"), std::string::npos);
  EXPECT_NE(error_of(d, "dump_modify dl format 1 %g").find("'1'"), std::string::npos);  // index
  EXPECT_NE(error_of(d, "dump_modify dl sort id").find("'sort'"), std::string::npos);
}

// dump_modify every N (LAMMPS: any dump) sets dump local's period: run 6 with every 3
// writes the snapshots of steps 0, 3 and 6; a period of 0 names its word.
TEST(DumpLocal, ModifyEverySetsThePeriod) {
  TempDir tmp;
  Deck d;
  setup(d);
  d("compute sl all wall/gran/slices right 10 dim y lo 0 hi 0.01");
  d("dump dl all local 1 " + (tmp / "rows.txt") + " index c_sl[1]");
  d("dump_modify dl every 3 first no");
  d("run 6");
  EXPECT_EQ(parse(tmp / "rows.txt").size(), 3u);
  EXPECT_NE(error_of(d, "dump_modify dl every 0").find("'0'"), std::string::npos);
}

}  // namespace test_dump_local
