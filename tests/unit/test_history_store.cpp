// core/engine/history_store.h: the walls' contact history keyed by (grain id, element).
// Expected values are written out by hand from the rules in the header.
#include <gtest/gtest.h>

#include <vector>

#include "core/engine/history_store.h"
#include "core/io/restart.h"

namespace test_history_store {

using Key = sable::HistoryStore::Key;
constexpr long W = sable::HistoryStore::kWall;

// A store of two slots holding `keys` in the order given, row k = {10 k + 1, 10 k + 2}.
sable::HistoryStore store_of(const std::vector<Key>& keys) {
  sable::HistoryStore h;
  h.configure(2);
  std::vector<double> rows;
  for (std::size_t k = 0; k < keys.size(); ++k) rows.insert(rows.end(), {10.0 * k + 1, 10.0 * k + 2});
  sable::HistoryStore::Order order;
  for (std::size_t k = 0; k < keys.size(); ++k) order.emplace_back(0, static_cast<int>(k));
  h.keep(order, [&](int, int k) { return keys[k]; }, [&](int, int k) { return rows.data() + 2 * k; });
  return h;
}

TEST(HistoryStore, LooksUpTheSameKeyElseZeros) {
  const sable::HistoryStore h = store_of({{1, W, 0}, {2, W, 0}, {3, W, 5}});
  const std::vector<Key> now = {{1, W, 0}, {3, W, 5}, {4, W, 0}};
  std::vector<double> out(6, -1.0);
  h.look_up(now.data(), now.size(), out.data());
  EXPECT_EQ(out, (std::vector<double>{1, 2, 21, 22, 0, 0}));
}

// A mesh grain that passed from triangle 1 onto triangle 2 takes triangle 1's
// row where the source allows it, but not while its contact on 1 goes on.
TEST(HistoryStore, TakesAnEndedContactOfTheSameGrainOnlyWhereAllowed) {
  const sable::HistoryStore h = store_of({{7, W, 1}, {8, W, 1}});
  auto same_surface = [](int before, int now) { return before == 1 && now == 2; };
  std::vector<double> out(2);
  const std::vector<Key> moved = {{7, W, 2}};
  h.look_up(moved.data(), 1, out.data(), same_surface);
  EXPECT_EQ(out, (std::vector<double>{1, 2}));
  h.look_up(moved.data(), 1, out.data());  // no transfer allowed
  EXPECT_EQ(out, (std::vector<double>{0, 0}));
  const std::vector<Key> both = {{7, W, 1}, {7, W, 2}};
  std::vector<double> out2(4);
  h.look_up(both.data(), 2, out2.data(), same_surface);
  EXPECT_EQ(out2, (std::vector<double>{1, 2, 0, 0}));
}

TEST(HistoryStore, MergedOrderInterleavesSortedParts) {
  const std::vector<std::vector<Key>> parts = {{{2, W, 0}, {9, W, 1}}, {{1, W, 4}, {5, W, 0}, {9, W, 0}}, {}, {{3, W, 3}}};
  sable::HistoryStore::Order order;
  sable::HistoryStore::merged_order(
      static_cast<int>(parts.size()), [&](int p) { return parts[p].data(); }, [&](int p) { return parts[p].size(); },
      order);
  const sable::HistoryStore::Order expected = {{1, 0}, {0, 0}, {3, 0}, {1, 1}, {1, 2}, {0, 1}};
  EXPECT_EQ(order, expected);
}

TEST(HistoryStore, RenumberingFollowsTheGrainsAndDropsTheDeleted) {
  sable::HistoryStore h = store_of({{2, W, 0}, {4, W, 3}, {4, W, 6}, {9, W, 0}});
  h.renumber({2, 4, 7}, {1, 2, 3});  // grain 9 was deleted
  ASSERT_EQ(h.count(), 3u);
  EXPECT_TRUE(h.key(0) == (Key{1, W, 0}));
  EXPECT_TRUE(h.key(1) == (Key{2, W, 3}));
  EXPECT_TRUE(h.key(2) == (Key{2, W, 6}));
  EXPECT_EQ(h.row(2)[0], 21.0);
  EXPECT_EQ(h.row(2)[1], 22.0);
}

// Grain pairs: the partner is a grain, renumbered with it; a pair with a
// deleted partner goes. Rows keep their order (a pair's are in list order).
TEST(HistoryStore, RenumberingFollowsGrainPartners) {
  sable::HistoryStore h = store_of({{9, 4, 0}, {2, 4, 0}, {4, 7, 0}, {3, W, 1}});
  h.renumber({2, 3, 4, 9}, {1, 2, 3, 4});  // grain 7 was deleted
  ASSERT_EQ(h.count(), 3u);
  EXPECT_TRUE(h.key(0) == (Key{4, 3, 0}));
  EXPECT_TRUE(h.key(1) == (Key{1, 3, 0}));
  EXPECT_TRUE(h.key(2) == (Key{2, W, 1}));
  EXPECT_EQ(h.row(2)[0], 31.0);
}

// A wall's look-up matches the partner too: rows of another partner are
// neither found nor taken by the transfer rule.
TEST(HistoryStore, LookUpMatchesThePartner) {
  const sable::HistoryStore h = store_of({{5, W, 1}});
  const std::vector<Key> other = {{5, 8, 1}, {5, 8, 2}};
  std::vector<double> out(4, -1.0);
  h.look_up(other.data(), other.size(), out.data(), [](int, int) { return true; });
  EXPECT_EQ(out, (std::vector<double>{0, 0, 0, 0}));
}

// Rows appended after the store's own, as a rebuild puts a restart's contacts
// after the list's.
TEST(HistoryStore, AppendKeepsBothInOrder) {
  sable::HistoryStore a = store_of({{1, 2, 0}});
  a.append(store_of({{3, 4, 0}, {5, 6, 0}}));
  ASSERT_EQ(a.count(), 3u);
  EXPECT_TRUE(a.key(2) == (Key{5, 6, 0}));
  EXPECT_EQ(a.row(2)[1], 12.0);
  EXPECT_EQ(a.row(0)[0], 1.0);
}

TEST(HistoryStore, RestartRoundTripAndAnotherModelRefused) {
  const sable::HistoryStore h = store_of({{3, W, 0}, {5, 6, 2}});
  sable::restart::Packer p;
  h.write(p);
  sable::HistoryStore back;
  back.configure(2);
  sable::restart::Unpacker u(p.bytes, "test");
  ASSERT_TRUE(back.read(u));
  ASSERT_EQ(back.count(), 2u);
  EXPECT_TRUE(back.key(0) == (Key{3, W, 0}));
  EXPECT_TRUE(back.key(1) == (Key{5, 6, 2}));
  EXPECT_EQ(back.row(1)[1], 12.0);
  sable::HistoryStore three;
  three.configure(3);
  sable::restart::Unpacker u3(p.bytes, "test");
  EXPECT_FALSE(three.read(u3));
  EXPECT_EQ(three.count(), 0u);
}

// Several ranks (Comm::exchange): grain 1 leaves for rank 1, grain 2 stays, grain 3
// leaves for rank 0, grain 9 is not this rank's. Slot 0 flips with the pair's
// direction (a tangential spring), slot 1 does not.
TEST(HistoryStore, MigrateSendsRowsWithTheirGrainsAndTurnsPairRowsForThePartner) {
  sable::HistoryStore h = store_of({{1, 2, 0}, {2, 3, 0}, {1, 3, 0}, {1, W, 0}, {2, W, 0}, {9, 2, 0}, {9, 8, 0}});
  auto dest = [](long id) { return id == 1 ? 1 : id == 3 ? 0 : id == 2 ? -1 : -2; };
  std::vector<std::vector<double>> out(2);
  h.migrate(dest, {1, 0}, out);
  // rank 1: (1,2) as it is; (1,3) as it is; the wall row of 1
  EXPECT_EQ(out[1], (std::vector<double>{1, 2, 0, 1, 2, 1, 3, 0, 21, 22, 1, W, 0, 31, 32}));
  // rank 0: (2,3) turned to (3,2) with slot 0 negated; (1,3) turned to (3,1)
  EXPECT_EQ(out[0], (std::vector<double>{3, 2, 0, -11, 12, 3, 1, 0, -21, 22}));
  // kept: rows with a grain that stays here (2): (1,2), (2,3), (2,W), (9,2)
  ASSERT_EQ(h.count(), 4u);
  const std::vector<Key> kept = {h.key(0), h.key(1), h.key(2), h.key(3)};
  EXPECT_EQ(kept, (std::vector<Key>{{1, 2, 0}, {2, 3, 0}, {2, W, 0}, {9, 2, 0}}));
  EXPECT_EQ(h.row(2)[0], 41);
}

TEST(HistoryStore, ReceiveAppendsRecordsAndSortPutsThemInKeyOrder) {
  sable::HistoryStore h = store_of({{5, W, 0}});
  const std::vector<double> in = {7, W, 2, 1.5, 2.5, 3, W, 0, 4.5, 5.5};
  EXPECT_EQ(h.receive(in.data(), 2), in.size());
  h.sort();
  ASSERT_EQ(h.count(), 3u);
  EXPECT_EQ(h.key(0), (Key{3, W, 0}));
  EXPECT_EQ(h.key(1), (Key{5, W, 0}));
  EXPECT_EQ(h.key(2), (Key{7, W, 2}));
  EXPECT_EQ(std::vector<double>(h.row(2), h.row(2) + 2), (std::vector<double>{1.5, 2.5}));
}

}  // namespace test_history_store
