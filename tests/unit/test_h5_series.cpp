// core/h5_series: rows buffered and written in blocks (issue 43). The rows in
// the file are the appended bits whatever the block size; a SIGKILLed writer's
// file opens without SWMR and holds exactly the blocks written before the kill;
// big rows are written by bytes; a deck's rows are all on disk at the end of a
// run and when an error stops one (Simulation::flush_outputs).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/h5_series.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_h5_series {

using sable::H5Series;
using sable::test::Deck;
using sable::test::error_of;
using sable::test::TempDir;

namespace {

// A dataset's dimensions and raw 64-bit values, read without SWMR.
struct Read {
  std::vector<hsize_t> dims;
  std::vector<std::uint64_t> bits;
};
Read read_dataset(const std::string& path, const char* name, bool integer) {
  Read r;
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << path << " does not open plainly";
  if (f < 0) return r;
  const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  const hid_t s = H5Dget_space(d);
  r.dims.assign(H5Sget_simple_extent_ndims(s), 0);
  H5Sget_simple_extent_dims(s, r.dims.data(), nullptr);
  std::size_t n = 1;
  for (hsize_t k : r.dims) n *= k;
  r.bits.assign(n, 0);
  if (n) {
    EXPECT_GE(H5Dread(d, integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, r.bits.data()), 0);
  }
  H5Sclose(s);
  H5Dclose(d);
  H5Fclose(f);
  return r;
}

// Records of two double series (rows of 2 x 3 and scalars) and a step: any
// bit patterns (NaN payloads, infinities, subnormals, -0 among them).
struct Records {
  std::vector<double> a, b;
  std::vector<std::int64_t> step;
  explicit Records(std::size_t n) {
    std::uint64_t x = 0x9E3779B97F4A7C15ull;
    auto next = [&] {
      x = x * 6364136223846793005ull + 1442695040888963407ull;
      double v;
      std::memcpy(&v, &x, 8);
      return v;
    };
    const double special[] = {-0.0, std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::denorm_min(), 1.0 / 3.0, 0.1};
    for (std::size_t r = 0; r < n; ++r) {
      for (int c = 0; c < 6; ++c) a.push_back(r < 6 && c == 0 ? special[r] : next());
      b.push_back(next());
      step.push_back(static_cast<std::int64_t>(7 * r) - 3);
    }
  }
};

// Writes the first n records; the caller's `after` runs after each record.
template <class After>
void write(H5Series& h, const Records& rec, std::size_t n, After&& after) {
  const int a = h.series("a", {2, 3}, false), b = h.series("b", {}, false), s = h.series("step", {}, true);
  h.start();
  for (std::size_t r = 0; r < n; ++r) {
    h.append(a, &rec.a[6 * r]);
    h.append(b, &rec.b[r]);
    h.append(s, rec.step[r]);
    after(r);
  }
}

// The file holds exactly the first n records, bit for bit.
void expect_records(const std::string& path, const Records& rec, std::size_t n) {
  const Read a = read_dataset(path, "a", false), b = read_dataset(path, "b", false), s = read_dataset(path, "step", true);
  ASSERT_EQ(a.dims, (std::vector<hsize_t>{n, 2, 3})) << path;
  ASSERT_EQ(b.dims, (std::vector<hsize_t>{n})) << path;
  ASSERT_EQ(s.dims, (std::vector<hsize_t>{n})) << path;
  EXPECT_EQ(std::memcmp(a.bits.data(), rec.a.data(), 48 * n), 0) << path;
  EXPECT_EQ(std::memcmp(b.bits.data(), rec.b.data(), 8 * n), 0) << path;
  EXPECT_EQ(std::memcmp(s.bits.data(), rec.step.data(), 8 * n), 0) << path;
}

}  // namespace

// 1000 records written one at a time, in blocks of up to 64 and in the default
// blocks give the same datasets, equal to the appended bits.
TEST(H5Series, BlockedRowsEqualRowByRowBitForBit) {
  TempDir tmp;
  const Records rec(1000);
  for (std::size_t block : {std::size_t(1), std::size_t(64), H5Series::kBlockRows}) {
    const std::string path = tmp / (std::to_string(block) + "rows.h5");
    {
      H5Series h(path, block);
      write(h, rec, 1000, [](std::size_t) {});
    }
    expect_records(path, rec, 1000);
  }
  // The one-at-a-time file against the blocked one, dataset by dataset.
  for (const char* name : {"a", "b", "step"}) {
    const bool integer = std::string(name) == "step";
    const Read one = read_dataset(tmp / "1rows.h5", name, integer), blocked = read_dataset(tmp / "64rows.h5", name, integer);
    EXPECT_EQ(one.dims, blocked.dims) << name;
    EXPECT_EQ(one.bits, blocked.bits) << name;
  }
}

// Blocks of 1, 2, 4, then 4 records: a writer SIGKILLed after 13 records has
// written 1 + 2 + 4 + 4 = 11 and loses the 2 buffered. The file opens without
// SWMR or h5clear and holds those 11 records bit for bit.
TEST(H5Series, KilledWriterKeepsTheBlocksWritten) {
  TempDir tmp;
  const std::string path = tmp / "killed.h5";
  const Records rec(13);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    H5Series h(path, 4);
    write(h, rec, 13, [](std::size_t) {});
    ::raise(SIGKILL);  // no destructor, no flush
    ::_exit(3);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
  expect_records(path, rec, 11);
}

// The buffer is also written when its rows reach kBlockBytes: rows of 800 kB are
// written at the 5th record (two buffered: 1.6 MB), not at the 7th (1 + 2 + 4).
TEST(H5Series, BigRowsAreWrittenWhenTheyFillTheByteBound) {
  TempDir tmp;
  const std::string path = tmp / "big.h5";
  const std::size_t n = 100000;
  ASSERT_GT(2 * 8 * n, H5Series::kBlockBytes);
  ASSERT_LT(8 * n, H5Series::kBlockBytes);
  std::vector<double> row(n);
  H5Series h(path);
  const int v = h.series("v", {n}, false), s = h.series("step", {}, true);
  h.start();
  std::vector<std::size_t> buffered;
  for (int r = 0; r < 5; ++r) {
    for (std::size_t k = 0; k < n; ++k) row[k] = r + 1e-6 * k;
    h.append(v, row.data());
    h.append(s, std::int64_t(r));
    buffered.push_back(h.buffered_records());
  }
  EXPECT_EQ(buffered, (std::vector<std::size_t>{0, 1, 0, 1, 0}));
  const Read rv = read_dataset(path, "v", false);
  ASSERT_EQ(rv.dims, (std::vector<hsize_t>{5, n}));
  double last;
  std::memcpy(&last, &rv.bits.back(), 8);
  EXPECT_EQ(last, 4 + 1e-6 * (n - 1));
}

namespace {

const char* kDeck = R"(units si
atom_style granular
region box block -1 1 -1 1 -1 1 units box
create_box 1 box
variable t equal step)";

// Steps of an ave/time text file (first column, comments skipped).
std::vector<std::int64_t> text_steps(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::int64_t> out;
  for (std::string l; std::getline(in, l);)
    if (!l.empty() && l[0] != '#') out.push_back(std::stoll(l));
  return out;
}

std::vector<std::int64_t> h5_steps(const std::string& path) {
  const Read r = read_dataset(path, "step", true);
  std::vector<std::int64_t> out(r.bits.size());
  std::memcpy(out.data(), r.bits.data(), 8 * out.size());
  return out;
}

}  // namespace

// fix ave/time every step: at the end of each run (the deck's fix still alive)
// the HDF5 file holds every record of the text file; without the flush at run
// end the first run's 100 records would stop at 63 (blocks 1 + 2 + ... + 32).
TEST(H5Series, DeckRowsAreOnDiskAtTheEndOfEachRun) {
  TempDir tmp;
  Deck d;
  d(kDeck)("fix a all ave/time 1 1 1 v_t file " + (tmp / "a.txt") + " hdf5 " + (tmp / "a.h5"));
  d("run 100");
  const auto first = text_steps(tmp / "a.txt");
  ASSERT_GE(first.size(), 100u);
  EXPECT_EQ(h5_steps(tmp / "a.h5"), first);
  d("run 50");
  const auto second = text_steps(tmp / "a.txt");
  EXPECT_EQ(second.size(), first.size() + 50);
  EXPECT_EQ(h5_steps(tmp / "a.h5"), second);
}

// An error that stops a run (fix halt ... error hard at step 38) leaves every
// record made before it in the file: the same steps as the text file.
TEST(H5Series, DeckRowsAreOnDiskWhenAnErrorStopsTheRun) {
  TempDir tmp;
  Deck d;
  d(kDeck)("fix a all ave/time 1 1 1 v_t file " + (tmp / "a.txt") + " hdf5 " + (tmp / "a.h5"));
  d("fix h all halt 1 v_t > 37.5 error hard");
  EXPECT_NE(error_of(d, "run 100").find("met on step 38"), std::string::npos);
  const auto text = text_steps(tmp / "a.txt");
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), 38);
  EXPECT_EQ(h5_steps(tmp / "a.h5"), text);
}

// The time axis: declared last (a series after it is refused, so `step` stays
// the record's end), a record ended without it is refused; the root's `units`,
// `time` with each record's time, and `timestep`, the first record's dt (given
// with the record: a deck may set dt after the output's line).
TEST(H5Series, TimeAxisLastWithUnitsAndTheFirstRecordsTimestep) {
  TempDir tmp;
  const std::string path = tmp / "t.h5";
  auto message = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  {
    H5Series plain(tmp / "plain.h5");
    plain.series("v", {}, false);
    plain.start();
    EXPECT_NE(message([&] { plain.end_record(1, 0.1, 0.1); }).find("has no time axis"), std::string::npos);
  }
  H5Series h(path, 1);
  const int v = h.series("v", {}, false);
  h.time_axis("si");
  EXPECT_NE(message([&] { h.series("late", {}, false); }).find("declare series 'late' before the time axis"),
            std::string::npos);
  h.start();
  std::size_t written = 0;
  h.on_written = [&](std::size_t records) { written = records; };
  const double x[3] = {1.5, 2.5, 3.5};
  for (int r = 0; r < 3; ++r) {
    h.append(v, &x[r]);
    h.end_record(10 * (r + 1), 1e-3 * (r + 1), r == 0 ? 1e-4 : 2e-4);  // dt of the first record: 1e-4
  }
  h.flush();
  EXPECT_EQ(written, 3u);
  const Read t = read_dataset(path, "time", false), step = read_dataset(path, "step", true);
  ASSERT_EQ(t.dims, (std::vector<hsize_t>{3}));
  double times[3];
  std::memcpy(times, t.bits.data(), sizeof times);
  EXPECT_EQ(times[2], 3e-3);
  EXPECT_EQ(step.bits[2], 30u);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, "time", H5P_DEFAULT);
  for (hid_t obj : {f, d}) {
    double dt = 0;
    const hid_t a = H5Aopen(obj, "timestep", H5P_DEFAULT);
    ASSERT_GE(a, 0);
    EXPECT_GE(H5Aread(a, H5T_NATIVE_DOUBLE, &dt), 0);
    EXPECT_EQ(dt, 1e-4);
    H5Aclose(a);
  }
  auto text_attr = [](hid_t obj, const char* name) {
    const hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
    if (a < 0) return std::string("(none)");
    const hid_t type = H5Aget_type(a);
    char* s = nullptr;
    H5Aread(a, type, &s);
    std::string r = s ? s : "";
    H5free_memory(s);
    H5Tclose(type);
    H5Aclose(a);
    return r;
  };
  EXPECT_EQ(text_attr(f, "units"), "si");
  EXPECT_EQ(text_attr(d, "units"), "s");
  H5Dclose(d);
  H5Fclose(f);
}

}  // namespace test_h5_series
