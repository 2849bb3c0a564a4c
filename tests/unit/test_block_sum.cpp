// core/engine/block_sum.h: the reduction core offers fixes (wall forces, frozen
// grains' forces, later mesh and rigid-body sums) gives the bits of one serial
// pass over the blocks for any split of the positions into thread ranges.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/engine/block_sum.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_block_sum {

namespace {

// Values of very different magnitudes, so the order of the additions shows in the bits.
std::vector<double> values(std::size_t n) {
  std::mt19937_64 g(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> v(3 * n);
  for (double& x : v) x = u(g) * std::pow(10.0, 8.0 * u(g));
  return v;
}

// The sum over ranges split at `bounds` (every third position left out: items need not be dense).
std::array<double, 3> ranged_sum(const std::vector<double>& v, const std::vector<std::size_t>& bounds,
                                 std::size_t block) {
  const std::size_t n = v.size() / 3;
  sable::BlockSum<3> s;
  s.begin(n, block, static_cast<int>(bounds.size()) - 1);
  for (std::size_t r = 0; r + 1 < bounds.size(); ++r) {
    s.range(static_cast<int>(r), bounds[r]);
    for (std::size_t p = bounds[r]; p < bounds[r + 1]; ++p)
      if (p % 3 != 1) s.add(static_cast<int>(r), p, &v[3 * p]);
  }
  std::array<double, 3> t;
  s.finish(t.data());
  return t;
}

}  // namespace

TEST(BlockSum, SameBitsForAnySplit) {
  const std::size_t n = 5000, block = 64;
  const std::vector<double> v = values(n);
  // The serial definition: each block's items in order, then the blocks in order.
  std::array<double, 3> expect{0, 0, 0};
  for (std::size_t b0 = 0; b0 < n; b0 += block) {
    double part[3] = {0, 0, 0};
    for (std::size_t p = b0; p < std::min(n, b0 + block); ++p)
      if (p % 3 != 1)
        for (int k = 0; k < 3; ++k) part[k] += v[3 * p + k];
    for (int k = 0; k < 3; ++k) expect[k] += part[k];
  }
  const std::vector<std::vector<std::size_t>> splits = {
      {0, n}, {0, 2500, n}, {0, 1000, 1001, 3333, n}, {0, 10, 20, 30, 4000, n}, {0, 0, 64, 128, 4999, n}};
  for (const auto& b : splits) {
    const auto got = ranged_sum(v, b, block);
    EXPECT_EQ(std::memcmp(got.data(), expect.data(), sizeof expect), 0) << "split into " << b.size() - 1 << " ranges";
  }
  // Summing each range on its own and then the ranges would not be the same bits: the test can fail.
  double naive = 0.0;
  for (std::size_t r = 0; r < 2; ++r) {
    double part = 0.0;
    for (std::size_t p = r ? 1000 : 0; p < (r ? n : 1000); ++p)
      if (p % 3 != 1) part += v[3 * p];
    naive += part;
  }
  EXPECT_NE(naive, expect[0]);
}

}  // namespace test_block_sum
