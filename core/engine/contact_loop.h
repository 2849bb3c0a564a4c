#pragma once
// The contact loop: walks a contact source (the half neighbour list, or a
// batch of grain-wall contacts found by a wall: primitive or mesh) for any
// contact law, and alone owns what is not physics: the thread split and the
// cross entries, history rows, SIMD gathering of the touching contacts into
// columns (core/engine/contact_columns.h) and the scatter of the forces in a fixed
// order (the same bits for any thread count). A law is compiled once per
// model combination; the loop once per history width.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/engine/contact_columns.h"
#include "core/engine/neighbor.h"
#include "core/engine/threads.h"

namespace sable {

// Particle-particle contacts: Neighbor's half list plus history parallel to it.
struct PairBatch {
  AtomView a;
  const int* first = nullptr;             // n + 1 offsets
  const int* jlist = nullptr;
  const std::uint8_t* shift = nullptr;    // image code per entry
  const double (*shift_vec)[3] = nullptr; // j's image = x[j] + shift_vec[code]
  ContactStore* store = nullptr;          // history (null without): row per entry, kHistory doubles per row
  int* row = nullptr;                     // store->row
  double* hist = nullptr;                 // store->rows()
  StepContext ctx;
  std::uint32_t groupbit = ~0u;           // records: both grains must be in this group
  long list_version = -1;                 // changes whenever the list is rebuilt (thread partition cache)
  AtomSplit* split = nullptr;             // receives the threads' atom ranges (per-atom passes follow them)
  const RangeTail* tail = nullptr;        // run on each range once its forces are final (Pair::compute_then)
  int span = 0;                           // NeighborList::span: j <= i + span (without image shift)
  // LIGGGHTS 3.8 mode (pair_gran.h): a separated pair keeps its history until
  // the first force pass after a neighbour rebuild (`rebuilt`), then loses it.
  bool keep_until_rebuild = false, rebuilt = false;
  Simd simd = simd_level();               // contact loops' width, read once per pass
};

// Particle-wall contacts found by a wall fix (overlap > 0 only).
struct WallBatch {
  AtomView a;
  std::size_t n = 0;
  const int* atom = nullptr;       // atom index of contact k
  const double* deltan = nullptr;  // overlap
  const double* en = nullptr;      // 3 per contact: unit normal, wall -> particle centre
  const double* vwall = nullptr;   // 3 per contact: wall velocity at the contact
  double* force = nullptr;         // out, 3 per contact: force on the grain
  double* hist = nullptr;          // history of contact k at hist + hist_index[k] * hist_stride
  const int* hist_index = nullptr;
  int hist_stride = 0;
  int wall_type = 1;
  StepContext ctx;
  Simd simd = simd_level();        // as PairBatch::simd
};

// Per-contact output (compute pair/gran/local, wall/gran/local): the loop's
// record pass evaluates the same columns without writing forces or history.
struct ContactRecord {
  int i, j;            // atom indices (j = -1 for a wall)
  int shift;           // pair: image code of j; wall: contact index in the batch
  double f[3];         // force on i
  double t[3];         // torque on i
  double delta;        // overlap
  double en[3];        // unit normal j (wall) -> i
};
struct ContactRecords {
  int hist_size = 0;
  std::vector<ContactRecord> rows;
  std::vector<double> hist;  // hist_size per row
  void clear() {
    rows.clear();
    hist.clear();
  }
};


class ContactLoop {
 public:
  virtual ~ContactLoop() = default;
  // Adds the contact forces and torques of the list to the grains; history advances with ctx.update.
  virtual void pair_forces(const PairBatch& b) = 0;
  virtual void pair_records(const PairBatch& b, ContactRecords& out) = 0;
  // Adds forces to the grains and writes each contact's force to b.force.
  // Called concurrently on batches with disjoint grains (FixWallGran's ranges).
  virtual void wall_forces(const WallBatch& b) const = 0;
  virtual void wall_records(const WallBatch& b, ContactRecords& out) const = 0;
};

// Widest history a loop is built for (core/engine/contact_loop.cpp instantiates 0..kMaxLoopHistory).
inline constexpr int kMaxLoopHistory = 9;
// The loop driving `law` (which must outlive it).
template <int kH>
std::unique_ptr<ContactLoop> make_contact_loop(const ColumnLaw<kH>& law);

}  // namespace sable
