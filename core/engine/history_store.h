#pragma once
// Contact history rows keyed by (grain id, partner, element): core's one store of
// what a contact remembers, for every contact source. A grain pair's partner is
// the other grain's id (element 0); a wall's partner is kWall, the wall that owns
// the store, and its element a mesh's triangle (0 for a primitive wall).
// It is what survives a neighbour rebuild (the pair's rows per list entry, in
// ContactStore, are saved here and restored from here), what a restart keeps,
// and what follows a renumbering of the grains. Walls keep the rows of their
// last force pass in key order, so a look-up depends neither on where grains
// sit in memory nor on which thread met them; a pair's saved rows are in list
// order and found by id.
#include <algorithm>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace sable {

namespace restart {
class Packer;
class Unpacker;
}  // namespace restart

class HistoryStore {
 public:
  static constexpr long kWall = -1;  // the partner of a wall's contacts
  struct Key {
    long tag;      // the grain's id
    long partner;  // the other grain's id, or kWall
    int element;   // a mesh's triangle, else 0
    friend bool operator<(const Key& a, const Key& b) {
      if (a.tag != b.tag) return a.tag < b.tag;
      return a.partner != b.partner ? a.partner < b.partner : a.element < b.element;
    }
    friend bool operator==(const Key& a, const Key& b) = default;
  };
  // (part, index) of contacts held in several parts, each in key order.
  using Order = std::vector<std::pair<int, int>>;

  void configure(int size) {
    size_ = size;
    clear();
  }
  void clear() { tag_.clear(), partner_.clear(), element_.clear(), hist_.clear(); }
  int size() const { return size_; }
  std::size_t count() const { return tag_.size(); }
  Key key(std::size_t r) const { return {tag_[r], partner_[r], element_[r]}; }
  const double* row(std::size_t r) const { return hist_.data() + r * size_; }
  double* row(std::size_t r) { return hist_.data() + r * size_; }
  // Rows filled by index (several threads may fill rows of their own): resize,
  // then set_key and row.
  void resize(std::size_t rows) {
    tag_.resize(rows), partner_.resize(rows), element_.resize(rows), hist_.resize(rows * size_);
  }
  void set_key(std::size_t r, const Key& k) { tag_[r] = k.tag, partner_[r] = k.partner, element_[r] = k.element; }
  // Appends `from`'s rows (same row size) after ours.
  void append(const HistoryStore& from);

  // (Walls.) The history of each of `keys` (sorted, no repeats; the store in
  // key order) into out, size() values per key: the row of the same key; else
  // a row of the same grain and partner whose element is not in `keys` (that
  // contact has ended) and that takes(its element, the key's element) accepts
  // (a mesh: the grain passed onto a triangle of the same surface); else zeros.
  // found (if given): 1 where a row was taken, else 0.
  template <class Takes>
  void look_up(const Key* keys, std::size_t n, double* out, Takes&& takes, char* found = nullptr) const;
  void look_up(const Key* keys, std::size_t n, double* out, char* found = nullptr) const {
    look_up(keys, n, out, [](int, int) { return false; }, found);
  }

  // (Walls.) The contacts of parts 0..nparts-1 in one key order; keys_of(p) and count_of(p)
  // give part p's keys, each part already in key order.
  template <class KeysOf, class CountOf>
  static void merged_order(int nparts, KeysOf&& keys_of, CountOf&& count_of, Order& out);
  // The store becomes this pass's contacts: `order` over the parts, key_of(p, k)
  // and hist_of(p, k) the key and history of contact k of part p.
  template <class KeyOf, class HistOf>
  void keep(const Order& order, KeyOf&& key_of, HistOf&& hist_of);

  // Grain old_ids[k] is now new_ids[k] (old_ids ascending, new_ids in the same
  // order: a key order holds), in both the grain and a grain partner; rows
  // naming a grain not listed are dropped.
  void renumber(const std::vector<long>& old_ids, const std::vector<long>& new_ids);

  // Several ranks (Comm::exchange). dest(id): the rank a grain this rank owns moves
  // to, -1 when it stays, -2 when this rank does not own it. A row goes with its
  // grain: into out[rank] as a record (tag, partner, element, row); a pair's row
  // (partner a grain) also goes to its partner's new rank, turned to (partner, grain)
  // with the `flip` slots negated; a row stays while either of its grains stays.
  void migrate(const std::function<int(long)>& dest, const std::vector<char>& flip,
               std::vector<std::vector<double>>& out);
  std::size_t record_size() const { return 3 + static_cast<std::size_t>(size_); }
  // Appends `rows` records made by migrate() from `in`; returns the doubles read.
  std::size_t receive(const double* in, std::size_t rows);
  void sort();  // into key order

  void write(restart::Packer& p) const;
  // False (and the store left empty) when the file's rows have another size.
  bool read(restart::Unpacker& u);

 private:
  int size_ = 0;
  std::vector<long> tag_, partner_;
  std::vector<int> element_;
  std::vector<double> hist_;
};

template <class Takes>
void HistoryStore::look_up(const Key* keys, std::size_t n, double* out, Takes&& takes, char* found) const {
  const std::size_t hs = static_cast<std::size_t>(size_);
  std::fill(out, out + n * hs, 0.0);
  if (found) std::fill(found, found + n, 0);
  if (hs == 0) return;
  const long rows = static_cast<long>(tag_.size());
  long lo = 0;  // keys and rows both in key order: one walk through the rows
  for (std::size_t k = 0; k < n; ++k) {
    const Key& key = keys[k];
    while (lo < rows && (tag_[lo] < key.tag || (tag_[lo] == key.tag && partner_[lo] < key.partner))) ++lo;
    long hi = lo;
    while (hi < rows && tag_[hi] == key.tag && partner_[hi] == key.partner) ++hi;
    long from = -1;
    for (auto j = lo; j < hi && from < 0; ++j)
      if (element_[j] == key.element) from = j;
    for (auto j = lo; j < hi && from < 0; ++j) {
      if (std::binary_search(keys, keys + n, Key{key.tag, key.partner, element_[j]})) continue;  // that contact goes on
      if (takes(element_[j], key.element)) from = j;
    }
    if (from >= 0) std::copy_n(hist_.begin() + from * hs, hs, out + k * hs);
    if (found) found[k] = from >= 0;
  }
}

template <class KeysOf, class CountOf>
void HistoryStore::merged_order(int nparts, KeysOf&& keys_of, CountOf&& count_of, Order& out) {
  out.clear();
  auto before = [&](const auto& a, const auto& b) { return keys_of(a.first)[a.second] < keys_of(b.first)[b.second]; };
  for (int p = 0; p < nparts; ++p) {
    const std::size_t mid = out.size();
    for (std::size_t k = 0; k < count_of(p); ++k) out.emplace_back(p, static_cast<int>(k));
    std::inplace_merge(out.begin(), out.begin() + static_cast<long>(mid), out.end(), before);
  }
}

template <class KeyOf, class HistOf>
void HistoryStore::keep(const Order& order, KeyOf&& key_of, HistOf&& hist_of) {
  const std::size_t hs = static_cast<std::size_t>(size_);
  resize(order.size());
  for (std::size_t r = 0; r < order.size(); ++r) {
    set_key(r, key_of(order[r].first, order[r].second));
    if (hs) std::copy_n(hist_of(order[r].first, order[r].second), hs, hist_.begin() + r * hs);
  }
}

}  // namespace sable
