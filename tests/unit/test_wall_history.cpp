// core/engine/wall_history.h: the walls' contact history keyed by (grain id, element).
// Expected values are written out by hand from the rules in the header.
#include <gtest/gtest.h>

#include <vector>

#include "core/engine/wall_history.h"
#include "core/io/restart.h"

namespace test_wall_history {

using Key = sable::WallHistory::Key;

// A store of two slots holding `keys` (sorted), row k = {10 k + 1, 10 k + 2}.
sable::WallHistory store_of(const std::vector<Key>& keys) {
  sable::WallHistory h;
  h.configure(2);
  std::vector<double> rows;
  for (std::size_t k = 0; k < keys.size(); ++k) rows.insert(rows.end(), {10.0 * k + 1, 10.0 * k + 2});
  sable::WallHistory::Order order;
  for (std::size_t k = 0; k < keys.size(); ++k) order.emplace_back(0, static_cast<int>(k));
  h.keep(order, [&](int, int k) { return keys[k]; }, [&](int, int k) { return rows.data() + 2 * k; });
  return h;
}

TEST(WallHistory, LooksUpTheSameKeyElseZeros) {
  const sable::WallHistory h = store_of({{1, 0}, {2, 0}, {3, 5}});
  const std::vector<Key> now = {{1, 0}, {3, 5}, {4, 0}};
  std::vector<double> out(6, -1.0);
  h.look_up(now.data(), now.size(), out.data());
  EXPECT_EQ(out, (std::vector<double>{1, 2, 21, 22, 0, 0}));
}

// A mesh grain that passed from triangle 1 onto triangle 2 takes triangle 1's
// row where the source allows it, but not while its contact on 1 goes on.
TEST(WallHistory, TakesAnEndedContactOfTheSameGrainOnlyWhereAllowed) {
  const sable::WallHistory h = store_of({{7, 1}, {8, 1}});
  auto same_surface = [](int before, int now) { return before == 1 && now == 2; };
  std::vector<double> out(2);
  const std::vector<Key> moved = {{7, 2}};
  h.look_up(moved.data(), 1, out.data(), same_surface);
  EXPECT_EQ(out, (std::vector<double>{1, 2}));
  h.look_up(moved.data(), 1, out.data());  // no transfer allowed
  EXPECT_EQ(out, (std::vector<double>{0, 0}));
  const std::vector<Key> both = {{7, 1}, {7, 2}};
  std::vector<double> out2(4);
  h.look_up(both.data(), 2, out2.data(), same_surface);
  EXPECT_EQ(out2, (std::vector<double>{1, 2, 0, 0}));
}

TEST(WallHistory, MergedOrderInterleavesSortedParts) {
  const std::vector<std::vector<Key>> parts = {{{2, 0}, {9, 1}}, {{1, 4}, {5, 0}, {9, 0}}, {}, {{3, 3}}};
  sable::WallHistory::Order order;
  sable::WallHistory::merged_order(
      static_cast<int>(parts.size()), [&](int p) { return parts[p].data(); }, [&](int p) { return parts[p].size(); },
      order);
  const sable::WallHistory::Order expected = {{1, 0}, {0, 0}, {3, 0}, {1, 1}, {1, 2}, {0, 1}};
  EXPECT_EQ(order, expected);
}

TEST(WallHistory, RenumberingFollowsTheGrainsAndDropsTheDeleted) {
  sable::WallHistory h = store_of({{2, 0}, {4, 3}, {4, 6}, {9, 0}});
  h.renumber({2, 4, 7}, {1, 2, 3});  // grain 9 was deleted
  ASSERT_EQ(h.count(), 3u);
  EXPECT_TRUE(h.key(0) == (Key{1, 0}));
  EXPECT_TRUE(h.key(1) == (Key{2, 3}));
  EXPECT_TRUE(h.key(2) == (Key{2, 6}));
  EXPECT_EQ(h.row(2)[0], 21.0);
  EXPECT_EQ(h.row(2)[1], 22.0);
}

TEST(WallHistory, RestartRoundTripAndAnotherModelRefused) {
  const sable::WallHistory h = store_of({{3, 0}, {5, 2}});
  sable::restart::Packer p;
  h.write(p);
  sable::WallHistory back;
  back.configure(2);
  sable::restart::Unpacker u(p.bytes, "test");
  ASSERT_TRUE(back.read(u));
  ASSERT_EQ(back.count(), 2u);
  EXPECT_TRUE(back.key(1) == (Key{5, 2}));
  EXPECT_EQ(back.row(1)[1], 12.0);
  sable::WallHistory three;
  three.configure(3);
  sable::restart::Unpacker u3(p.bytes, "test");
  EXPECT_FALSE(three.read(u3));
  EXPECT_EQ(three.count(), 0u);
}

}  // namespace test_wall_history
