#pragma once
// Cell binning + half Verlet list with skin (LIGGGHTS `neighbor SKIN bin`,
// `neigh_modify delay/every/check`). Periodic images are not ghost atoms: each
// list entry carries a shift code, so forces land directly on the owners.
// ContactStore keeps per-contact history, found from the list entries, and
// carries it across rebuilds in core's HistoryStore, keyed by (id_i, id_j).
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/engine/domain.h"
#include "core/engine/history_store.h"

namespace sable {

class Atoms;
class Domain;

struct NeighborList {
  std::vector<int> first;            // n+1 offsets
  std::vector<int> j;                // partner index (each atom's entries sorted by j, then shift)
  std::vector<std::uint8_t> shift;   // image code, kNoShift when none
  double shift_vec[27][3] = {};      // j's image = x[j] + shift_vec[code]
  int span = 0;                      // largest j - i of an entry without image shift
  static constexpr std::uint8_t kNoShift = 13;
  std::size_t size() const { return j.size(); }
};

struct HistorySlot {
  std::string name;
  bool flip;  // negate when the pair is seen as (j, i)
};

// History rows, one per contact rather than one per list entry (most entries
// are near misses within the skin): the force pass streams less than half the
// bytes. Contacts alive at the last rebuild (or compaction) come first, in list
// order; contacts begun since take rows at the end.
class ContactStore {
 public:
  static constexpr int kNone = -1;
  int size = 0;                     // doubles per contact
  std::vector<HistorySlot> slots;
  std::vector<int> row;             // per list entry: its history row, kNone while not in contact
  void configure(const std::vector<HistorySlot>& s);
  // `entries` list entries, none in contact.
  void resize(std::size_t entries);
  double* rows() { return buf_.get(); }
  const double* history(std::size_t k) const { return row[k] < 0 ? nullptr : buf_.get() + row[k] * size; }
  // A zeroed row for a contact that begins now (safe from several threads at
  // once). Each thread takes its rows from its own block of kBlock: rows that
  // two threads rewrite every step never share a cache line, and the shared
  // counter moves once per block (a row each made them bounce between cores).
  int new_row() {
    const int t = thread_slot();
    int r;
    if (t < kSlots) {
      Cursor& c = cursor_[t];
      if (c.next == c.end) {
        c.next = used_.fetch_add(kBlock, std::memory_order_relaxed);
        c.end = c.next + kBlock;
      }
      r = c.next++;
    } else {
      r = used_.fetch_add(1, std::memory_order_relaxed);
    }
    for (int m = 0; m < size; ++m) buf_[static_cast<std::size_t>(r) * size + m] = 0.0;
    return r;
  }
  // Entry k starts a contact now; returns its (zeroed) history.
  double* begin_contact(std::size_t k) { return buf_.get() + (row[k] = new_row()) * static_cast<std::size_t>(size); }
  // Before a force pass: room for one new contact per list entry, and a block
  // per thread (compacts when short).
  void make_room();
  std::size_t contacts() const;  // entries in contact
  std::size_t rows_used() const { return static_cast<std::size_t>(used_); }
  std::size_t capacity() const { return cap_; }
  // Keep history of touching pairs across a rebuild.
  // ids[i] is the id of the atom at index i when the list was built (atoms may
  // have been deleted, inserted or sorted since).
  void save(const NeighborList& list, const std::vector<long>& ids);
  void restore(const NeighborList& list, const Atoms& atoms);
  // The touching contacts of `list` (built over atoms whose ids were `ids`), as
  // save() keeps them: (id_i, id_j, 0) in list order.
  HistoryStore touching(const NeighborList& list, const std::vector<long>& ids) const;
  void touching(const NeighborList& list, const std::vector<long>& ids, HistoryStore& out) const;
  // Contacts from a restart file with slots `from`, matched to ours by name; the
  // next rebuild restores them like its own. Returns our slot names absent from
  // `from` (those values start at zero).
  std::vector<std::string> inject(const std::vector<HistorySlot>& from, const HistoryStore& c);
  // delete_atoms' renumbering: contacts injected and not yet restored follow it.
  void ids_renumbered(const std::vector<long>& old_ids, const std::vector<long>& new_ids) {
    injected_.renumber(old_ids, new_ids);
  }
  // The rows save() kept (Comm::exchange moves them with their grains).
  HistoryStore& saved() { return saved_; }

 private:
  void reserve_rows(std::size_t rows);  // capacity for `rows` rows; contents dropped
  void set_used(int rows);              // rows taken; the threads' blocks are given up
  static int thread_slot();             // the calling thread's cursor
  static constexpr int kBlock = 64, kSlots = 64;  // rows per block; cursors (more threads share the counter)
  static std::size_t slack();           // rows the threads' blocks may take beyond the new contacts
  struct alignas(64) Cursor {
    int next = 0, end = 0;  // the thread's free rows [next, end)
  };
  std::unique_ptr<Cursor[]> cursor_ = std::make_unique<Cursor[]>(kSlots);
  std::unique_ptr<double[]> buf_;       // not zeroed: new rows are zeroed when taken
  std::size_t cap_ = 0;                 // rows
  std::atomic<int> used_{0};            // rows taken
  HistoryStore saved_, injected_;
  std::vector<int> from_;  // restore(): each entry's saved contact
};

class Neighbor {
 public:
  double skin = 0.0;
  bool skin_set = false;
  int delay = 0, every = 1;
  bool check = true;
  bool sort = true;  // reorder atoms by bin at every build (cache locality)
  long builds = 0;
  long last_build_step = -1;
  // Set by fixes that change radii (fix adapt): the rebuild check then counts
  // each grain's growth since the last build with its displacement.
  bool radii_vary = false;

  NeighborList list;

  // neigh_modify exclude (LAMMPS' rules): pairs of these types, or with one grain in
  // each group, never enter the list; empty: nothing is tested.
  struct Exclusion {
    bool by_type;
    int type_a, type_b;          // by_type
    std::uint32_t bit_a, bit_b;  // by group
  };
  std::vector<Exclusion> exclusions;

  // Rebuild now: wrap periodic atoms, bin, (sort), list, carry history.
  void build(Atoms& atoms, const Domain& domain, ContactStore* store, long step);
  // Several ranks (core/engine/comm_atoms.cpp): the bins cover `bins` (the subdomain
  // and its ghost layer; periodic only along axes one rank spans, whose images keep
  // their shift codes), the caller has wrapped and exchanged the atoms, the atoms
  // are not sorted, and the list pairs each owned atom with owned atoms above it
  // and with every ghost near it (newton off).
  struct Ghosted {
    bool on = false;
    Domain bins;
    double cutoff = 0.0;  // the ghost layer's width: 2 r_max (over all ranks) + skin
  } ghosted;
  // The pair's history saved now, before the exchange moves grains; build() then skips it.
  void save_history(ContactStore* store);
  // (Several ranks, after the exchange, before the ghosts:) the owned atoms in the
  // order of bins a cutoff wide over `box` (cache locality of the pair pass; a
  // decomposed build does not sort), if `sort` is on.
  void sort_owned(Atoms& atoms, const Domain& box, double cutoff);
  // True when a rebuild is due at this step (LIGGGHTS rules).
  bool decide(const Atoms& atoms, long step);
  // The last step at which decide() scanned every position (a NaN or infinite
  // one there forces a rebuild, which checks the atoms).
  long positions_scanned_step = -1;
  long prescans_used = 0;  // rebuild checks that took the scan done ahead (below)
  double max_displacement_sq(const Atoms& atoms) const;
  bool moved_or_grew(const Atoms& atoms) const;
  // The check's scan done ahead, range by range, by the threads that just
  // moved those atoms (Simulation::run's pipelined step): expect_prescan()
  // announces it for `step` (serially), prescan_range() scans [lo, hi) on
  // thread t; decide() at that step then uses it instead of its own pass.
  void expect_prescan(const Atoms& atoms, long step);
  void prescan_range(const Atoms& atoms, int t, std::size_t lo, std::size_t hi);
  double cutoff() const { return cutoff_; }
  // The bin axis that varied slowest at the last build (pick_slow_axis).
  int slow_axis() const { return slow_axis_; }
  // Atom ids in index order at the last build: how to read `list` after atoms moved.
  const std::vector<long>& built_ids() const { return ids_; }
  // delete_atoms' renumbering (old_ids ascending): the list's grains take their
  // new ids, a deleted one none, so that the next rebuild carries history by them.
  void ids_renumbered(const std::vector<long>& old_ids, const std::vector<long>& new_ids);

 private:
  std::vector<double> xhold_;
  std::vector<double> rhold_;  // radii at the last build (radii_vary only)
  std::vector<long> ids_;  // atom ids (owned, then ghosts) at the last build, to read the old list
  bool history_saved_ = false;  // save_history() since the last build
  double cutoff_ = 0.0;
  std::vector<int> bin_of_, bin_start_, bin_atoms_;  // bin_atoms_: unsorted builds only
  std::vector<std::size_t> order_;                  // sorted builds: the atoms in bin order
  int slow_axis_ = -1;  // slowest-varying bin axis at the last build
  struct {
    long step = -1;  // the step it is for (-1: none)
    std::size_t n = 0;
    std::vector<double> part;  // per range
  } prescan_;
  int pick_slow_axis(const Atoms& atoms, const Domain& domain, const int nb[3], const double inv[3]);
  struct alignas(64) ScanBlock {
    std::vector<int> j;
    std::vector<std::uint8_t> shift;
  };
  std::vector<ScanBlock> blocks_;  // per-thread list parts of a threaded build
};

}  // namespace sable
