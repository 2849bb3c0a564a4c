#pragma once
// One contact kernel per (normal, tangential, rolling) combination, composed
// at compile time: GranKernel<N, T, R> inlines the three sub-model structs
// into its loops, so the per-contact work has no virtual call, no std::function
// and no allocation. The virtual ContactKernel interface is crossed once per
// loop (per step), not per contact. The same instantiation serves pair
// contacts (half neighbour list) and wall contacts (a batch of
// particle-wall overlaps prepared by a wall fix), as LIGGGHTS registers each
// ContactModel<Style> for both pair and wall.
//
// A sub-model struct provides (see contact_models/README.md):
//   static constexpr const char* kName;  static constexpr int kHistory;
//   static void history_slots(std::vector<HistorySlot>&);
//   void settings(ModelSettings&);  void connect(PropertyRequest&);
//   normal:     NormalForce force(const Contact&, double* hist, const StepContext&) const;
//               double contact_time(const ContactTimeInput&) const;
//   tangential: Vec3 force(const Contact&, const NormalForce&, double* hist, const StepContext&) const;
//   rolling:    Vec3 torque(const Contact&, const NormalForce&, double* hist, const StepContext&) const;
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include "contact_models/contact.h"
#include "contact_models/materials.h"
#include "core/atoms.h"
#include "core/neighbor.h"
#include "core/threads.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace sable {

// Raw views of the atom arrays a loop reads and writes.
struct AtomView {
  std::size_t n = 0;
  const double *x = nullptr, *v = nullptr, *omega = nullptr, *radius = nullptr, *rmass = nullptr;
  const int* type = nullptr;
  const std::uint32_t* mask = nullptr;
  double *f = nullptr, *torque = nullptr;
  int stride = 2;                 // ntypes + 1 (per-type-pair table stride)
  std::uint32_t freeze_bit = 0;   // grains of this group count as infinitely heavy (LIGGGHTS fix freeze)
};

// The per-atom arrays a kernel reads and writes, for the first n atoms.
inline AtomView atom_view(Atoms& at, std::size_t n, std::uint32_t freeze_bit) {
  AtomView a;
  a.n = n;
  a.x = at.x.data();
  a.v = at.v.data();
  a.omega = at.omega.data();
  a.radius = at.radius.data();
  a.rmass = at.rmass.data();
  a.type = at.type.data();
  a.mask = at.mask.data();
  a.f = at.f.data();
  a.torque = at.torque.data();
  a.stride = at.ntypes + 1;
  a.freeze_bit = freeze_bit;
  return a;
}

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

// Per-contact output (compute pair/gran/local, wall/gran/local), produced by a
// separate instantiation of the loops that never writes forces or history.
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

// State of the two grains of a pair contact, as the kinematics below need it.
struct PairState {
  double dx, dy, dz;   // x_i - (x_j + image shift)
  double radi, radj, mi, mj;
  double vr[3];        // v_i - v_j
  double wi[3], wj[3];
  int frozen;          // bit 0: i frozen, bit 1: j frozen (fix freeze: infinitely heavy)
};

// Contact kinematics of a touching pair (LIGGGHTS' conventions, contact.h).
// One definition for the force loop and the per-contact records, so both give
// the same numbers bit for bit.
[[gnu::always_inline]] inline void pair_kinematics(Contact& c, const PairState& s) {
  c.is_wall = false;
  const double rsq = s.dx * s.dx + s.dy * s.dy + s.dz * s.dz;
  c.r = std::sqrt(rsq);
  const double rinv = 1.0 / c.r;
  c.en[0] = s.dx * rinv;
  c.en[1] = s.dy * rinv;
  c.en[2] = s.dz * rinv;
  const double radsum = s.radi + s.radj;
  c.deltan = radsum - c.r;
  c.radi = s.radi;
  c.radj = s.radj;
  c.reff = s.radi * s.radj / radsum;
  const double meff = s.mi * s.mj / (s.mi + s.mj);
  c.meff = (s.frozen & 2) ? s.mi : (s.frozen & 1) ? s.mj : meff;
  c.vn = s.vr[0] * c.en[0] + s.vr[1] * c.en[1] + s.vr[2] * c.en[2];
  c.cri = s.radi - 0.5 * c.deltan;
  c.crj = s.radj - 0.5 * c.deltan;
  const double wr0 = (c.cri * s.wi[0] + c.crj * s.wj[0]) * rinv;
  const double wr1 = (c.cri * s.wi[1] + c.crj * s.wj[1]) * rinv;
  const double wr2 = (c.cri * s.wi[2] + c.crj * s.wj[2]) * rinv;
  c.vtr[0] = s.vr[0] - c.vn * c.en[0] - (s.dz * wr1 - s.dy * wr2);
  c.vtr[1] = s.vr[1] - c.vn * c.en[1] - (s.dx * wr2 - s.dz * wr0);
  c.vtr[2] = s.vr[2] - c.vn * c.en[2] - (s.dy * wr0 - s.dx * wr1);
  c.wroll[0] = s.wi[0] - s.wj[0];
  c.wroll[1] = s.wi[1] - s.wj[1];
  c.wroll[2] = s.wi[2] - s.wj[2];
}

// Force on i and torques on i and j of one contact.
struct ContactParts {
  double f[3], ti[3], tj[3];
};

// Touching contacts of a stretch of the half list, gathered into columns
// (see GranKernel::pair_forces), scattered in list order.
template <int kH>
struct PairChunk {
  static constexpr int kCap = 64;
  int n = 0;      // contacts to evaluate (columns 0..n-1)
  int tp0 = -1;   // >= 0: every column's type pair (the loop then reads its coefficients once)
  int slot[kCap]; // threaded phase A: the cross slot of column m
  int row[kCap], i[kCap], j[kCap], itype[kCap], jtype[kCap], tp[kCap], frozen[kCap];
  alignas(64) double dx[kCap], dy[kCap], dz[kCap], radi[kCap], radj[kCap], mi[kCap], mj[kCap];
  alignas(64) double vr[3][kCap], wi[3][kCap], wj[3][kCap];
  alignas(64) double h[kH > 0 ? kH : 1][kCap];
  alignas(64) double f[3][kCap], ti[3][kCap], tj[3][kCap];

  [[gnu::always_inline]] inline void contact(int m, Contact& c) const {
    PairState s;
    s.dx = dx[m];
    s.dy = dy[m];
    s.dz = dz[m];
    s.radi = radi[m];
    s.radj = radj[m];
    s.mi = mi[m];
    s.mj = mj[m];
    s.frozen = frozen[m];
    for (int d = 0; d < 3; ++d) {
      s.vr[d] = vr[d][m];
      s.wi[d] = wi[d][m];
      s.wj[d] = wj[d][m];
    }
    pair_kinematics(c, s);
    c.itype = itype[m];
    c.jtype = jtype[m];
    c.tp = tp[m];
  }
  [[gnu::always_inline]] inline void store(int m, const ContactParts& p) {
    for (int d = 0; d < 3; ++d) {
      f[d][m] = p.f[d];
      ti[d][m] = p.ti[d];
      tj[d][m] = p.tj[d];
    }
  }
};

// State of a grain touching a wall.
struct WallState {
  double en[3];  // unit normal, wall -> grain centre
  double deltan, radi, mi;
  double vr[3];  // v_i - v_wall at the contact
  double wi[3];
};

// Wall contact kinematics (LIGGGHTS' conventions: the wall has infinite
// radius and mass). Shared by the force pass and the per-contact records.
[[gnu::always_inline]] inline void wall_kinematics(Contact& c, const WallState& s) {
  c.is_wall = true;
  c.en[0] = s.en[0];
  c.en[1] = s.en[1];
  c.en[2] = s.en[2];
  c.deltan = s.deltan;
  c.radi = s.radi;
  c.radj = 0.0;
  c.r = c.radi - c.deltan;
  c.reff = c.radi;  // wall: infinite radius ...
  c.meff = s.mi;    // ... and infinite mass
  c.vn = s.vr[0] * s.en[0] + s.vr[1] * s.en[1] + s.vr[2] * s.en[2];
  c.cri = c.radi - 0.5 * c.deltan;
  c.crj = 0.0;
  // LIGGGHTS: wr = cri w_i / r and vtr = vt - wr x (r en), i.e. contact point of i at -cri en.
  const double q = c.cri / c.r;
  c.wroll[0] = q * s.wi[0];
  c.wroll[1] = q * s.wi[1];
  c.wroll[2] = q * s.wi[2];
  const double dx = s.en[0] * c.r, dy = s.en[1] * c.r, dz = s.en[2] * c.r;
  c.vtr[0] = s.vr[0] - c.vn * s.en[0] - (dz * c.wroll[1] - dy * c.wroll[2]);
  c.vtr[1] = s.vr[1] - c.vn * s.en[1] - (dx * c.wroll[2] - dz * c.wroll[0]);
  c.vtr[2] = s.vr[2] - c.vn * s.en[2] - (dy * c.wroll[0] - dx * c.wroll[1]);
}

// Wall contacts gathered into columns (GranKernel::wall_forces).
template <int kH>
struct WallChunk {
  static constexpr int kCap = 64;
  int n = 0;
  int tp0 = -1;  // as PairChunk::tp0
  int itype[kCap], jtype[kCap], tp[kCap];
  alignas(64) double en[3][kCap], deltan[kCap], radi[kCap], mi[kCap], vr[3][kCap], wi[3][kCap];
  alignas(64) double h[kH > 0 ? kH : 1][kCap];
  alignas(64) double f[3][kCap], ti[3][kCap];

  [[gnu::always_inline]] inline void contact(int m, Contact& c) const {
    WallState s;
    for (int d = 0; d < 3; ++d) {
      s.en[d] = en[d][m];
      s.vr[d] = vr[d][m];
      s.wi[d] = wi[d][m];
    }
    s.deltan = deltan[m];
    s.radi = radi[m];
    s.mi = mi[m];
    wall_kinematics(c, s);
    c.itype = itype[m];
    c.jtype = jtype[m];
    c.tp = tp[m];
  }
  [[gnu::always_inline]] inline void store(int m, const ContactParts& p) {
    for (int d = 0; d < 3; ++d) {
      f[d][m] = p.f[d];
      ti[d][m] = p.ti[d];
    }
  }
};

// Thread partition of the half list for the parallel force pass (GranKernel::pair_forces).
struct PairPartition {
  long version = -1;
  int nparts = 0;
  std::size_t natoms = 0, nentries = 0;
  std::vector<int> lo;                   // nparts + 1 atom bounds of the ranges
  std::vector<int> cross_first;          // nparts + 1: cross entries of range t
  std::vector<int> cross_k, cross_i, cross_j;  // per cross entry (list order): entry, its atoms i and j
  std::vector<int> cross_u;              // per cross entry: the range of j, whose thread evaluates it
  std::vector<int> in_first, in_s;       // range u's incoming cross entries (j in u): in_s[in_first[u] ..], list order
  std::vector<std::uint8_t> on;          // cross entry touching this step
  // What range u's phase A wrote, one row per touching entry in in_s order:
  // only these lines go to the cores of the i ranges.
  struct Slots {
    std::vector<double> fi;  // 6 per row: force and torque on i (read by i's thread)
    std::vector<double> tj;  // 3 per row: torque on j (read by u's thread itself)
    std::vector<int> at;     // nparts: the first row of range t's entries
  };
  std::vector<Slots> slots;              // per range u
  std::vector<int> cursor;               // per range, padded to cache lines: apply_outgoing's next row per later u
  std::size_t cursor_stride() const { return (static_cast<std::size_t>(nparts) + 15) / 16 * 16; }
  std::vector<std::atomic<long>> done_a;  // per range: the last pass whose phase A is done
  long pass = 0;                         // threaded passes so far
  bool rehome = false;                   // a new list: phase A moves its cross entries' history rows
  // Balance from measured time (the results do not depend on the split):
  std::vector<double> cum;               // n + 1: cumulative work weight by atom
  std::vector<double> seg_u, seg_d;      // cost profile: range bounds as weight fractions, seconds per weight
  std::vector<double> busy;              // per range: seconds in phase B since the split
  int calls = 0;                         // force passes since the split
};

class ContactKernel {
 public:
  virtual ~ContactKernel() = default;
  virtual std::string name() const = 0;  // "model hertz tangential history rolling_friction cdt"
  virtual void settings(ModelSettings& s) = 0;
  // Look up coefficient tables; errors name `line` (the pair_style / fix wall/gran command).
  virtual void connect(const std::shared_ptr<Materials>& m, const Args& line) = 0;
  virtual const std::vector<HistorySlot>& history_slots() const = 0;
  virtual void pair_forces(const PairBatch& b) = 0;
  virtual void pair_records(const PairBatch& b, ContactRecords& out) = 0;
  // Adds forces to the grains and writes each contact's force to b.force.
  // Called concurrently on batches with disjoint grains (FixWallGran's ranges).
  virtual void wall_forces(const WallBatch& b) = 0;
  virtual void wall_records(const WallBatch& b, ContactRecords& out) = 0;
  virtual double contact_time(const ContactTimeInput& in) const = 0;
};

template <class N, class T, class R>
class GranKernel final : public ContactKernel {
 public:
  static constexpr int kHN = N::kHistory, kHT = T::kHistory, kHR = R::kHistory;
  static constexpr int kH = kHN + kHT + kHR;

  GranKernel() {
    N::history_slots(slots_);
    T::history_slots(slots_);
    R::history_slots(slots_);
  }
  std::string name() const override {
    return std::string("model ") + N::kName + " tangential " + T::kName + " rolling_friction " + R::kName;
  }
  void settings(ModelSettings& s) override {
    normal_.settings(s);
    tangential_.settings(s);
    rolling_.settings(s);
  }
  void connect(const std::shared_ptr<Materials>& m, const Args& line) override {
    materials_ = m;  // keeps the tables the sub-models point into alive
    PropertyRequest p(*m, line, std::string("model ") + N::kName);
    normal_.connect(p);
    p.set_who(std::string("tangential ") + T::kName);
    tangential_.connect(p);
    p.set_who(std::string("rolling_friction ") + R::kName);
    rolling_.connect(p);
  }
  const std::vector<HistorySlot>& history_slots() const override { return slots_; }
  void pair_forces(const PairBatch& b) override { pair_forces_staged(b); }
  void pair_records(const PairBatch& b, ContactRecords& out) override {
    out.clear();
    out.hist_size = kH;
    pair_loop<true>(b, &out);
  }
  void wall_forces(const WallBatch& b) override { wall_forces_staged(b); }
  void wall_records(const WallBatch& b, ContactRecords& out) override {
    out.clear();
    out.hist_size = kH;
    wall_loop<true>(b, &out);
  }
  double contact_time(const ContactTimeInput& in) const override { return normal_.contact_time(in); }

  N normal_;
  T tangential_;
  R rolling_;

 private:
  std::vector<HistorySlot> slots_;
  std::shared_ptr<Materials> materials_;
  PairPartition part_;
  using Chunk = PairChunk<kH>;

  using Parts = ContactParts;

  // All sub-models on one contact: force on i and torques on i and j.
  [[gnu::always_inline]] inline Parts evaluate(const Contact& c, double* h, const StepContext& ctx) const {
    const NormalForce nf = normal_.force(c, h, ctx);
    const Vec3 ft = tangential_.force(c, nf, h + kHN, ctx);
    const Vec3 mr = rolling_.torque(c, nf, h + kHN + kHT, ctx);
    const double* en = c.en;
    Parts p;
    p.f[0] = nf.Fn * en[0] + ft.x;
    p.f[1] = nf.Fn * en[1] + ft.y;
    p.f[2] = nf.Fn * en[2] + ft.z;
    const double tor[3] = {en[1] * ft.z - en[2] * ft.y, en[2] * ft.x - en[0] * ft.z, en[0] * ft.y - en[1] * ft.x};
    p.ti[0] = -c.cri * tor[0] - mr.x;
    p.ti[1] = -c.cri * tor[1] - mr.y;
    p.ti[2] = -c.cri * tor[2] - mr.z;
    p.tj[0] = -c.crj * tor[0] + mr.x;
    p.tj[1] = -c.crj * tor[1] + mr.y;
    p.tj[2] = -c.crj * tor[2] + mr.z;
    return p;
  }

  // Per-contact records at the current state (compute pair/gran/local): a plain
  // loop over the list; history is copied, never written.
  template <bool kRecord>
  void pair_loop(const PairBatch& b, ContactRecords* out) {
    static_assert(kRecord, "forces go through pair_forces_staged");
    const AtomView& a = b.a;
    const double* x = a.x;
    const StepContext ctx{b.ctx.dt, false};
    [[maybe_unused]] double hbuf[kH > 0 ? kH : 1];
    for (std::size_t i = 0; i < a.n; ++i) {
      if (!(a.mask[i] & b.groupbit)) continue;
      const double xi = x[3 * i], yi = x[3 * i + 1], zi = x[3 * i + 2];
      const double radi = a.radius[i];
      for (int k = b.first[i]; k < b.first[i + 1]; ++k) {
        const int j = b.jlist[k];
        const double* sh = b.shift_vec[b.shift[k]];
        PairState s;
        s.dx = xi - (x[3 * j] + sh[0]);
        s.dy = yi - (x[3 * j + 1] + sh[1]);
        s.dz = zi - (x[3 * j + 2] + sh[2]);
        const double rsq = s.dx * s.dx + s.dy * s.dy + s.dz * s.dz;
        s.radi = radi;
        s.radj = a.radius[j];
        const double radsum = s.radi + s.radj;
        if (rsq >= radsum * radsum) continue;
        if (!(a.mask[j] & b.groupbit)) continue;
        gather_state(a, static_cast<int>(i), j, s);
        Contact c;
        pair_kinematics(c, s);
        c.itype = a.type[i];
        c.jtype = a.type[j];
        c.tp = c.itype * a.stride + c.jtype;
        double* h = nullptr;
        if constexpr (kH > 0) {
          const int r = b.row[k];
          for (int m = 0; m < kH; ++m) hbuf[m] = r < 0 ? 0.0 : b.hist[static_cast<std::size_t>(r) * kH + m];
          h = hbuf;
        }
        const Parts p = evaluate(c, h, ctx);
        ContactRecord r{static_cast<int>(i), j, b.shift[k], {p.f[0], p.f[1], p.f[2]}, {p.ti[0], p.ti[1], p.ti[2]},
                        c.deltan, {c.en[0], c.en[1], c.en[2]}};
        out->rows.push_back(r);
        if constexpr (kH > 0) out->hist.insert(out->hist.end(), h, h + kH);
      }
    }
  }

  // Masses, velocities, spins and freeze flags of pair (i, j).
  static void gather_state(const AtomView& a, int i, int j, PairState& s) {
    s.mi = a.rmass[i];
    s.mj = a.rmass[j];
    s.frozen = ((a.mask[i] & a.freeze_bit) ? 1 : 0) | ((a.mask[j] & a.freeze_bit) ? 2 : 0);
    const double *v = a.v, *w = a.omega;
    for (int d = 0; d < 3; ++d) {
      s.vr[d] = v[3 * i + d] - v[3 * j + d];
      s.wi[d] = w[3 * i + d];
      s.wj[d] = w[3 * j + d];
    }
  }

  // ---- The force pass -------------------------------------------------------
  //
  // Each stretch of the half list goes through three stages, a chunk of
  // PairChunk::kCap contacts at a time:
  //   1. filter: which entries touch (branch-free append; an ended contact
  //      forgets its history); the state of the touching pairs is copied into
  //      columns;
  //   2. evaluate: all sub-models on every column, a loop over independent
  //      contacts without branches that the compiler vectorises (AVX-512 or
  //      AVX2 where the CPU has it, SSE2 otherwise: the same operations lane by
  //      lane, so the same bits);
  //   3. scatter: forces and torques added to the grains in list order.
  //
  // Threads (OpenMP, when the list is long enough) own contiguous atom ranges
  // balanced by work. A contact whose j lies in a later range (a "cross"
  // entry) is evaluated into its own slot by the thread of j's range, first
  // (phase A), which then adds the slots aimed at its atoms and runs its range
  // (phase B). The thread of i's range runs its range (phase B) and adds the
  // slots of its own cross entries last, once phase A of the later ranges is
  // done (a flag each, long since set by then: no barrier). An atom's entries
  // are sorted by j (Neighbor::build), so its cross entries are the last of
  // them and phase B runs the serial loop on the rest. Every atom thus
  // receives exactly the serial sequence of additions: j-side contributions by
  // increasing list entry (all from lower atoms), then its own entries in list
  // order (nothing else adds to an atom once its own entries are done). The
  // result is bit-identical to the serial pass for any thread count, with no
  // atomics on forces and no per-thread force copies. Only j's thread reads the
  // other range's grains (i's), and only i's forces go back: the fewest cache
  // lines crossing between the cores.

  void pair_forces_staged(const PairBatch& b) {
    const int nparts = pair_thread_count(b.a.n, b.a.n ? static_cast<std::size_t>(b.first[b.a.n]) : 0);
    if (nparts <= 1) {
      if (b.split) b.split->n = 0;
      Chunk ch;
      pair_range(b, 0, static_cast<int>(b.a.n), nullptr, 0, ch);
      if (b.tail) for_atom_ranges(b.split ? *b.split : AtomSplit{}, b.a.n, *b.tail);  // equal ranges
      return;
    }
#ifdef _OPENMP
    const double w0 = omp_get_wtime();
    PairPartition& pp = part_;
    const long version0 = pp.version;
    const int calls0 = pp.calls;
    plan_partition(b, nparts);
    PairTrace* const trace = PairTrace::get();
    const double plan = omp_get_wtime() - w0;
    if (trace) trace->begin(nparts);
    ++pp.calls;
    const long pass = ++pp.pass;
    if (b.split) {
      b.split->n = b.a.n;
      b.split->lo = pp.lo;
    }
    ThreadBalance& tb = thread_balance(PassKind::Pair);
    tb.begin(nparts);
#pragma omp parallel num_threads(nparts)
    {
      const int nt = omp_get_num_threads(), tid = omp_get_thread_num();
      Chunk ch;
      // Phase A of all this thread's ranges before any waiting (fewer threads
      // than ranges must not wait on themselves).
      const double a0 = omp_get_wtime();
      for (int t = tid; t < nparts; t += nt) {
        const double t0 = omp_get_wtime();
        cross_range(b, pp, t, ch);
        pp.busy[t] += omp_get_wtime() - t0;
        pp.done_a[t].store(pass, std::memory_order_release);
      }
      double busy = omp_get_wtime() - a0;
      if (trace) {
        double* r = &trace->t[4 * static_cast<std::size_t>(tid)];
        r[0] = a0 - w0, r[1] = r[2] = a0 + busy - w0;
      }
      for (int t = tid; t < nparts; t += nt) {
        const double t0 = omp_get_wtime();
        apply_incoming(b, pp, t);
        pair_range(b, pp.lo[t], pp.lo[t + 1], &pp, t, ch);
        if (b.tail) (*b.tail)(t, static_cast<std::size_t>(pp.lo[t]), static_cast<std::size_t>(pp.lo[t + 1]));
        const double dt = omp_get_wtime() - t0;
        pp.busy[t] += dt;
        busy += dt;
      }
      tb.busy[tid] += busy;
      if (trace) trace->t[4 * static_cast<std::size_t>(tid) + 3] = omp_get_wtime() - w0;
    }
    pp.rehome = false;
    tb.wall += omp_get_wtime() - w0;
    ++tb.calls;
    if (trace) trace->write(plan, pp.version != version0 ? 2 : pp.calls <= calls0 ? 1 : 0, omp_get_wtime() - w0);
#endif
  }

  // What stage 1 reads, copied out of the batch: locals cannot be aliased by
  // the byte stores into `touch`, so the compiler keeps them in registers.
  struct ListView {
    const double* x;
    const double* radius;
    const int* jlist;
    const std::uint8_t* shift;
    const double (*shift_vec)[3];
    int* row;
    ContactStore* store;
    bool forget;  // an ended contact loses its history now (else at the next rebuild)
  };
  static ListView list_view(const PairBatch& b) {
    return {b.a.x, b.a.radius, b.jlist, b.shift, b.shift_vec, b.row, b.store, !b.keep_until_rebuild || b.rebuilt};
  }

  // x_i - (x_j + image shift of entry k).
  [[gnu::always_inline]] static inline void separation(const ListView& L, double xi, double yi, double zi, int j, int k,
                                                       double& dx, double& dy, double& dz) {
    const double* xj = L.x + 3 * j;
    double xj0 = xj[0], xj1 = xj[1], xj2 = xj[2];
    const std::uint8_t code = L.shift[k];
    if (code != NeighborList::kNoShift) {  // periodic image: rare, so predictable
      const double* sh = L.shift_vec[code];
      xj0 += sh[0];
      xj1 += sh[1];
      xj2 += sh[2];
    }
    dx = xi - xj0;
    dy = yi - xj1;
    dz = zi - xj2;
  }

  // Stage 1 for list entry k of atom i: append to the columns (n: the chunk's
  // count, kept in a register by the caller) if touching; a new contact takes a
  // history row, an ended one forgets it.
  [[gnu::always_inline]] static inline void filter_entry(const ListView& L, Chunk& ch, int& n, int i, double xi,
                                                         double yi, double zi, double radi, int k) {
    const int j = L.jlist[k];
    double dx, dy, dz;
    separation(L, xi, yi, zi, j, k, dx, dy, dz);
    const double rsq = dx * dx + dy * dy + dz * dz;
    const double radj = L.radius[j], radsum = radi + radj;
    const bool touching = !(rsq >= radsum * radsum);
    // What the contact needs from the list, kept (the column is overwritten
    // unless the pair touches): the gather then reads no position again.
    ch.i[n] = i;
    ch.j[n] = j;
    ch.dx[n] = dx;
    ch.dy[n] = dy;
    ch.dz[n] = dz;
    ch.radi[n] = radi;
    ch.radj[n] = radj;
    if constexpr (kH > 0) {
      // Contact begun or ended. Rare, so the branch is predictable as long as
      // it does not test `touching` alone (a coin flip): hence the arithmetic.
      int r = L.row[k];
      const unsigned t = touching, has = r >= 0, gone = !t && has;
      if (__builtin_expect(((t & !has) | (gone & static_cast<unsigned>(L.forget))) != 0, 0))
        L.row[k] = r = t ? L.store->new_row() : ContactStore::kNone;
      ch.row[n] = r;
    }
    n += touching;
  }

  // Stage 1, second half: copy the rest of the touching pairs' state into columns.
  // Specialised for the common scene: no frozen grains, one atom type.
  void gather(const PairBatch& b, Chunk& ch) const {
    const bool types = b.a.stride > 2, general = types || b.a.freeze_bit != 0;
    ch.tp0 = types ? -1 : b.a.stride + 1;  // one atom type: one type pair
#if defined(__x86_64__) && defined(__GNUC__)
    if (b.simd == Simd::AVX512) return general ? gather_columns_avx512<true>(b, ch) : gather_columns_avx512<false>(b, ch);
#endif
    return general ? gather_columns<true>(b, ch) : gather_columns<false>(b, ch);
  }
  template <bool kGeneral>
  void gather_columns(const PairBatch& b, Chunk& ch) const {
    const AtomView& a = b.a;
    const double *v = a.v, *w = a.omega, *rmass = a.rmass;
    const int n = ch.n;
    for (int m = 0; m < n; ++m) {
      const int i = ch.i[m], j = ch.j[m];
      ch.mi[m] = rmass[i];
      ch.mj[m] = rmass[j];
      for (int d = 0; d < 3; ++d) {
        ch.vr[d][m] = v[3 * i + d] - v[3 * j + d];
        ch.wi[d][m] = w[3 * i + d];
        ch.wj[d][m] = w[3 * j + d];
      }
      if constexpr (kGeneral) {
        ch.frozen[m] = ((a.mask[i] & a.freeze_bit) ? 1 : 0) | ((a.mask[j] & a.freeze_bit) ? 2 : 0);
        ch.itype[m] = a.type[i];
        ch.jtype[m] = a.type[j];
        ch.tp[m] = a.type[i] * a.stride + a.type[j];
      } else {  // one type (1), nothing frozen
        ch.frozen[m] = 0;
        ch.itype[m] = ch.jtype[m] = 1;
        ch.tp[m] = a.stride + 1;
      }
      if constexpr (kH > 0) {
        const double* h = b.hist + static_cast<std::size_t>(ch.row[m]) * kH;
        for (int q = 0; q < kH; ++q) ch.h[q][m] = h[q];
      }
    }
  }

#if defined(__x86_64__) && defined(__GNUC__)
  // gather_columns eight contacts at a time (AVX-512; three-double rows by
  // rows3, scalars by gathers): the same copies and the same differences, so
  // the same bits. Scalar, each column costs a load and a store per contact;
  // here a store per eight. Every column is
  // written in blocks of eight (the chunk has room; lanes past n are unused).
  [[gnu::target("avx512f,avx512vl"), gnu::always_inline]] static inline void put(int* p, __m256i x) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), x);
  }
  // Eight rows of three doubles (at base + 3 * idx[l]) into three columns:
  // eight masked loads and a transpose instead of three 8-lane gathers
  // (24 element loads). On an AMD EPYC (Zen 4) this cut the filter's and the
  // gather's samples by 30 % and 40 % (bed_30k, 1 thread).
  [[gnu::target("avx512f,avx512vl"), gnu::always_inline]] static inline void rows3(const double* base, const int* idx,
                                                                                __m512d& cx, __m512d& cy, __m512d& cz) {
    __m512d z[4];
    for (int l = 0; l < 4; ++l) {  // lanes 0-3: row l, lanes 4-7: row l + 4 (the fourth double masked off)
      const __m512d lo = _mm512_maskz_loadu_pd(7, base + 3 * static_cast<std::ptrdiff_t>(idx[l]));
      const __m256d hi = _mm256_maskz_loadu_pd(7, base + 3 * static_cast<std::ptrdiff_t>(idx[l + 4]));
      z[l] = _mm512_mask_broadcast_f64x4(lo, 0xF0, hi);
    }
    // (permutes, not unpack / insert: GCC 12 warns on those intrinsics' undefined operand)
    const __m512i lo2 = _mm512_setr_epi64(0, 8, 2, 10, 4, 12, 6, 14), hi2 = _mm512_setr_epi64(1, 9, 3, 11, 5, 13, 7, 15);
    const __m512d t0 = _mm512_permutex2var_pd(z[0], lo2, z[1]), t1 = _mm512_permutex2var_pd(z[0], hi2, z[1]);
    const __m512d t2 = _mm512_permutex2var_pd(z[2], lo2, z[3]), t3 = _mm512_permutex2var_pd(z[2], hi2, z[3]);
    // t0: x0 x1 z0 z1 x4 x5 z4 z5, t2 the same for rows 2, 3, 6, 7; t1, t3: the y values
    const __m512i even = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13), odd = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
    cx = _mm512_permutex2var_pd(t0, even, t2);
    cy = _mm512_permutex2var_pd(t1, even, t3);
    cz = _mm512_permutex2var_pd(t0, odd, t2);
  }
  template <bool kGeneral>
  [[gnu::target("avx512f,avx512dq,avx512vl")]] void gather_columns_avx512(const PairBatch& b, Chunk& ch) const {
    const AtomView& a = b.a;
    const __m512d zero = _mm512_setzero_pd();
    const int n = ch.n;
    for (int m = 0; m < n; m += 8) {
      const __mmask8 k = static_cast<__mmask8>(n - m >= 8 ? 0xFF : (1u << (n - m)) - 1);
      const __m256i i = _mm256_maskz_loadu_epi32(k, ch.i + m), j = _mm256_maskz_loadu_epi32(k, ch.j + m);
      _mm512_store_pd(ch.mi + m, _mm512_mask_i32gather_pd(zero, k, i, a.rmass, 8));
      _mm512_store_pd(ch.mj + m, _mm512_mask_i32gather_pd(zero, k, j, a.rmass, 8));
      alignas(32) int ii[8], jj[8];  // lanes past n read atom 0 (unused)
      _mm256_store_si256(reinterpret_cast<__m256i*>(ii), i);
      _mm256_store_si256(reinterpret_cast<__m256i*>(jj), j);
      __m512d ci[3], cj[3];
      rows3(a.v, ii, ci[0], ci[1], ci[2]);
      rows3(a.v, jj, cj[0], cj[1], cj[2]);
      for (int d = 0; d < 3; ++d) _mm512_store_pd(ch.vr[d] + m, _mm512_sub_pd(ci[d], cj[d]));
      rows3(a.omega, ii, ci[0], ci[1], ci[2]);
      rows3(a.omega, jj, cj[0], cj[1], cj[2]);
      for (int d = 0; d < 3; ++d) {
        _mm512_store_pd(ch.wi[d] + m, ci[d]);
        _mm512_store_pd(ch.wj[d] + m, cj[d]);
      }
      if constexpr (kGeneral) {
        const __m256i z = _mm256_setzero_si256(), fb = _mm256_set1_epi32(static_cast<int>(a.freeze_bit));
        const int* mask = reinterpret_cast<const int*>(a.mask);
        const __m256i mi = _mm256_mmask_i32gather_epi32(z, k, i, mask, 4);
        const __m256i mj = _mm256_mmask_i32gather_epi32(z, k, j, mask, 4);
        const __m256i one = _mm256_set1_epi32(1), two = _mm256_set1_epi32(2);
        const __m256i fi = _mm256_maskz_mov_epi32(_mm256_test_epi32_mask(mi, fb), one);
        const __m256i fj = _mm256_maskz_mov_epi32(_mm256_test_epi32_mask(mj, fb), two);
        put(ch.frozen + m, _mm256_or_si256(fi, fj));
        const __m256i ti = _mm256_mmask_i32gather_epi32(z, k, i, a.type, 4);
        const __m256i tj = _mm256_mmask_i32gather_epi32(z, k, j, a.type, 4);
        put(ch.itype + m, ti);
        put(ch.jtype + m, tj);
        put(ch.tp + m, _mm256_add_epi32(_mm256_mullo_epi32(ti, _mm256_set1_epi32(a.stride)), tj));
      } else {  // one type (1), nothing frozen
        put(ch.frozen + m, _mm256_setzero_si256());
        put(ch.itype + m, _mm256_set1_epi32(1));
        put(ch.jtype + m, _mm256_set1_epi32(1));
        put(ch.tp + m, _mm256_set1_epi32(a.stride + 1));
      }
      if constexpr (kH == 3) {  // tangential history alone (the common model): a row is three doubles
        alignas(32) int rr[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(rr), _mm256_maskz_loadu_epi32(k, ch.row + m));
        __m512d h0, h1, h2;
        rows3(b.hist, rr, h0, h1, h2);
        _mm512_store_pd(ch.h[0] + m, h0);
        _mm512_store_pd(ch.h[1] + m, h1);
        _mm512_store_pd(ch.h[2] + m, h2);
      } else if constexpr (kH > 0) {  // 64-bit row offsets: row * kH may pass 2^31 doubles
        const __m512i r = _mm512_mullo_epi64(_mm512_maskz_cvtepi32_epi64(k, _mm256_maskz_loadu_epi32(k, ch.row + m)),
                                             _mm512_set1_epi64(kH));
        for (int q = 0; q < kH; ++q) _mm512_store_pd(ch.h[q] + m, _mm512_mask_i64gather_pd(zero, k, r, b.hist + q, 8));
      }
    }
  }
#endif

  // Stage 2 (see above). Columns in, force/torque columns and new history out.
  // Cols: PairChunk or WallChunk (their contact() builds the kinematics).
  // kUniform: one type pair (ch.tp0) for all, so each coefficient is one
  // loaded value, not a per-lane table lookup.
  template <bool kUpdate, bool kUniform, class Cols>
  [[gnu::always_inline]] inline void evaluate_columns(Cols& ch, double dt) const {
    const StepContext ctx{dt, kUpdate};
    const int n = ch.n, tp0 = ch.tp0;
#pragma GCC ivdep
    for (int m = 0; m < n; ++m) {
      Contact c;
      ch.contact(m, c);
      if constexpr (kUniform) c.tp = tp0;
      double h[kH > 0 ? kH : 1];
      for (int q = 0; q < kH; ++q) h[q] = ch.h[q][m];
      const Parts p = evaluate(c, h, ctx);
      if constexpr (kUpdate)
        for (int q = 0; q < kH; ++q) ch.h[q][m] = h[q];
      ch.store(m, p);
    }
  }
  // The four (update, uniform) instantiations, chosen per chunk.
  template <class Cols>
  [[gnu::always_inline]] inline void evaluate_columns_all(Cols& ch, double dt, bool update) const {
    const bool uniform = ch.tp0 >= 0;
    if (update && uniform)
      evaluate_columns<true, true>(ch, dt);
    else if (update)
      evaluate_columns<true, false>(ch, dt);
    else if (uniform)
      evaluate_columns<false, true>(ch, dt);
    else
      evaluate_columns<false, false>(ch, dt);
  }
#if defined(__x86_64__) && defined(__GNUC__)
  template <class Cols>
  [[gnu::target("avx2"), gnu::flatten]] void evaluate_columns_avx2(Cols& ch, double dt, bool update) const {
    evaluate_columns_all(ch, dt, update);
  }
  template <class Cols>
  [[gnu::target("avx512f,avx512dq"), gnu::flatten]] void evaluate_columns_avx512(Cols& ch, double dt,
                                                                                 bool update) const {
    evaluate_columns_all(ch, dt, update);
  }
#endif
  template <class Cols>
  [[gnu::flatten]] void evaluate_columns_base(Cols& ch, double dt, bool update) const {
    evaluate_columns_all(ch, dt, update);
  }
  template <class Cols>
  void evaluate_columns_any(Cols& ch, double dt, bool update, Simd simd) const {
#if defined(__x86_64__) && defined(__GNUC__)
    switch (simd) {
      case Simd::AVX512: return evaluate_columns_avx512(ch, dt, update);
      case Simd::AVX2: return evaluate_columns_avx2(ch, dt, update);
      case Simd::SSE2: break;
    }
#endif
    evaluate_columns_base(ch, dt, update);
  }

  // Stages 1b-3 for the chunk. Not inlined into the filter loop, which then
  // keeps its values in registers.
  [[gnu::noinline]] void flush(const PairBatch& b, Chunk& ch) const {
    gather(b, ch);
    evaluate_columns_any(ch, b.ctx.dt, b.ctx.update, b.simd);
    if (b.ctx.update)
      scatter<true>(b, ch);
    else
      scatter<false>(b, ch);
    ch.n = 0;
  }

  // Stage 3: forces and torques onto the grains in list order; history back.
  template <bool kUpdate>
  void scatter(const PairBatch& b, const Chunk& ch) const {
    double* f = b.a.f;
    double* t = b.a.torque;
    [[maybe_unused]] double* hist = b.hist;
    for (int e = 0; e < ch.n; ++e) {
      const int i = ch.i[e], j = ch.j[e];
      for (int d = 0; d < 3; ++d) {
        f[3 * i + d] += ch.f[d][e];
        f[3 * j + d] -= ch.f[d][e];
        t[3 * i + d] += ch.ti[d][e];
        t[3 * j + d] += ch.tj[d][e];
      }
      if constexpr (kH > 0 && kUpdate) {
        const std::size_t r = static_cast<std::size_t>(ch.row[e]);
        for (int c = 0; c < kH; ++c) hist[r * kH + c] = ch.h[c][e];
      }
    }
  }

  static void store_history(const PairBatch& b, const Chunk& ch) {
    if constexpr (kH > 0) {
      double* hist = b.hist;
      const int n = ch.n;
      if (b.ctx.update)
        for (int m = 0; m < n; ++m)
          for (int q = 0; q < kH; ++q) hist[static_cast<std::size_t>(ch.row[m]) * kH + q] = ch.h[q][m];
    }
  }

  // Phase B (or the whole serial pass, pp null): the entries of atoms [lo, hi)
  // in list order. Threaded, an atom's entries with j >= hi (its last ones,
  // the list being sorted by j) were evaluated in phase A: their slots are
  // added after the range, when each atom's own entries are done.
  void pair_range(const PairBatch& b, int lo, int hi, PairPartition* pp, int t, Chunk& ch) const {
    ch.n = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    if (b.simd == Simd::AVX512)
      pair_entries_avx512(b, lo, hi, pp != nullptr, ch);
    else
#endif
      pair_entries(b, lo, hi, pp != nullptr, ch);
    flush(b, ch);
    if (pp) apply_outgoing(b, *pp, t);
  }

  // Atom i's entries in phase B: all, or (`trim`) those with j < hi.
  static int entries_end(const ListView& L, const int* first, int i, int hi, bool trim) {
    int kend = first[i + 1];
    if (trim)
      while (kend > first[i] && L.jlist[kend - 1] >= hi) --kend;
    return kend;
  }

  // Stage 1 over the entries of atoms [lo, hi), flushing full chunks; the last,
  // partial chunk is left in `ch`.
  void pair_entries(const PairBatch& b, int lo, int hi, bool trim, Chunk& ch) const {
    const ListView L = list_view(b);
    const int* first = b.first;
    int n = 0;
    const int lead = prefetch_lead(b);
    for (int i = lo; i < hi; ++i) {
      if (i + lead < hi) prefetch_atom(b.a, i + lead);
      const double xi = L.x[3 * i], yi = L.x[3 * i + 1], zi = L.x[3 * i + 2], radi = L.radius[i];
      for (int k = first[i], kend = entries_end(L, first, i, hi, trim); k < kend; ++k) {
        filter_entry(L, ch, n, i, xi, yi, zi, radi, k);
        if (n == Chunk::kCap) {
          ch.n = n;
          flush(b, ch);
          n = 0;
        }
      }
    }
    ch.n = n;
  }

#if defined(__x86_64__) && defined(__GNUC__)
  // pair_entries eight entries at a time (AVX-512): partners' positions (rows3)
  // and radii (a gather) read, the touching lanes compressed into the columns. The same
  // arithmetic and tests as filter_entry, so the same contacts in the same
  // order; periodic images and contacts that begin or end (rare) are handled
  // lane by lane, in list order (history rows are taken in the same order).
  // The lanes of `m` packed to the front of 8 values at p (all 8 written: the
  // chunk keeps room; a compressing store to memory is much slower).
  [[gnu::target("avx512f,avx512vl"), gnu::always_inline]] static inline void put8(int* p, __mmask8 m, __m256i v) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), _mm256_maskz_compress_epi32(m, v));
  }
  [[gnu::target("avx512f"), gnu::always_inline]] static inline void put8(double* p, __mmask8 m, __m512d v) {
    _mm512_storeu_pd(p, _mm512_maskz_compress_pd(m, v));
  }
  [[gnu::target("avx512f,avx512dq,avx512vl,avx512bw")]] void pair_entries_avx512(const PairBatch& b, int lo, int hi,
                                                                                bool trim, Chunk& ch) const {
    const ListView L = list_view(b);
    const int* first = b.first;
    int n = 0;
    const int lead = prefetch_lead(b);
    const __m128i noshift = _mm_set1_epi8(static_cast<char>(NeighborList::kNoShift));
    const __m512d zero = _mm512_setzero_pd();
    for (int i = lo; i < hi; ++i) {
      if (i + lead < hi) prefetch_atom(b.a, i + lead);
      const int kend = entries_end(L, first, i, hi, trim);
      if (first[i] == kend) continue;
      const __m512d xi = _mm512_set1_pd(L.x[3 * i]), yi = _mm512_set1_pd(L.x[3 * i + 1]);
      const __m512d zi = _mm512_set1_pd(L.x[3 * i + 2]), radi = _mm512_set1_pd(L.radius[i]);
      for (int k = first[i]; k < kend; k += 8) {
        if (n > Chunk::kCap - 8) {
          ch.n = n;
          flush(b, ch);
          n = 0;
        }
        const int cnt = std::min(8, kend - k);
        const __mmask8 m = static_cast<__mmask8>((1u << cnt) - 1);
        const __m256i j = _mm256_maskz_loadu_epi32(m, L.jlist + k);
        alignas(32) int jj[8];  // lanes past cnt read atom 0 (masked off below)
        _mm256_store_si256(reinterpret_cast<__m256i*>(jj), j);
        __m512d xj, yj, zj;
        rows3(L.x, jj, xj, yj, zj);
        const __m128i code = _mm_maskz_loadu_epi8(m, L.shift + k);
        if (_mm_mask_cmpneq_epi8_mask(m, code, noshift)) {  // periodic images: x_j + shift, lane by lane
          alignas(64) double px[8], py[8], pz[8];
          _mm512_store_pd(px, xj);
          _mm512_store_pd(py, yj);
          _mm512_store_pd(pz, zj);
          for (int l = 0; l < cnt; ++l)
            if (L.shift[k + l] != NeighborList::kNoShift) {
              const double* sh = L.shift_vec[L.shift[k + l]];
              px[l] += sh[0];
              py[l] += sh[1];
              pz[l] += sh[2];
            }
          xj = _mm512_load_pd(px);
          yj = _mm512_load_pd(py);
          zj = _mm512_load_pd(pz);
        }
        const __m512d dx = _mm512_sub_pd(xi, xj), dy = _mm512_sub_pd(yi, yj), dz = _mm512_sub_pd(zi, zj);
        const __m512d rsq =
            _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
        const __m512d radj = _mm512_mask_i32gather_pd(zero, m, j, L.radius, 8);
        const __m512d radsum = _mm512_add_pd(radi, radj);
        const __mmask8 touch = _mm512_mask_cmp_pd_mask(m, rsq, _mm512_mul_pd(radsum, radsum), _CMP_NGE_UQ);
        if constexpr (kH > 0) {
          __m256i r = _mm256_maskz_loadu_epi32(m, L.row + k);
          const __mmask8 has = _mm256_mask_cmpge_epi32_mask(m, r, _mm256_setzero_si256());
          const __mmask8 change = (touch & ~has) | (L.forget ? (m & ~touch & has) : 0);
          if (change) {  // contacts begin (a new, zeroed row) or end (no row)
            for (int l = 0; l < cnt; ++l)
              if ((change >> l) & 1) L.row[k + l] = ((touch >> l) & 1) ? L.store->new_row() : ContactStore::kNone;
            r = _mm256_maskz_loadu_epi32(m, L.row + k);
          }
          put8(ch.row + n, touch, r);
        }
        put8(ch.i + n, touch, _mm256_set1_epi32(i));
        put8(ch.j + n, touch, j);
        put8(ch.dx + n, touch, dx);
        put8(ch.dy + n, touch, dy);
        put8(ch.dz + n, touch, dz);
        put8(ch.radi + n, touch, radi);
        put8(ch.radj + n, touch, radj);
        n += __builtin_popcount(touch);
      }
    }
    ch.n = n;
  }
#endif

  // Partners j > i lie up to `span` atoms ahead, a slab of bins, and are read
  // there for the first time since the last pass: irregular reads (touching
  // pairs only) that the hardware does not prefetch, and out of cache once N
  // outgrows it. So each atom's state is requested `lead` atoms before the
  // first i that can need it (x and radius, read for every entry, need no help).
  static int prefetch_lead(const PairBatch& b) { return b.span + 16; }
  [[gnu::always_inline]] static inline void prefetch_atom(const AtomView& a, int p) {
    __builtin_prefetch(a.v + 3 * p);
    __builtin_prefetch(a.omega + 3 * p);
    __builtin_prefetch(a.rmass + p);
    __builtin_prefetch(a.f + 3 * p, 1);
    __builtin_prefetch(a.torque + 3 * p, 1);
  }

  // Phase A of range u: the cross entries whose j lies in it, the touching
  // ones into rows of its slots.
  void cross_range(const PairBatch& b, PairPartition& pp, int u, Chunk& ch) const {
    const ListView L = list_view(b);
    PairPartition::Slots& out = pp.slots[u];
    if (pp.rehome) rehome_rows(b, pp, u);
    int n = 0, rows = 0, t = 0;
    for (int q = pp.in_first[u]; q < pp.in_first[u + 1]; ++q) {
      const int s = pp.in_s[q];
      while (t < u && s >= pp.cross_first[t + 1]) out.at[++t] = rows;  // range t's entries start here
      const int i = pp.cross_i[s], k = pp.cross_k[s];
      const int before = n;
      filter_entry(L, ch, n, i, L.x[3 * i], L.x[3 * i + 1], L.x[3 * i + 2], L.radius[i], k);
      pp.on[s] = static_cast<std::uint8_t>(n != before);
      ch.slot[before] = rows;
      rows += n != before;
      if (n == Chunk::kCap) {
        ch.n = n;
        cross_flush(b, out, ch);
        n = 0;
      }
    }
    while (t < u) out.at[++t] = rows;
    ch.n = n;
    cross_flush(b, out, ch);
  }

  // A new list's cross entries' history to rows of this thread's own (the
  // same values). The list hands out rows in list order, so a cross entry's
  // row sat among those of i's other contacts, which i's thread rewrites at
  // every step as this one rewrites it: each line went between the cores
  // twice a step. (Restarted bed_30k, two threads with the cores apart:
  // +3.5 to +6 % in paired runs.)
  static void rehome_rows(const PairBatch& b, const PairPartition& pp, int u) {
    if constexpr (kH > 0) {
      if (!b.store) return;
      double* rows = b.store->rows();
      const std::size_t w = static_cast<std::size_t>(b.store->size);
      for (int q = pp.in_first[u]; q < pp.in_first[u + 1]; ++q) {
        int& r = b.row[pp.cross_k[pp.in_s[q]]];
        if (r < 0) continue;
        const int moved = b.store->new_row();
        std::copy(rows + r * w, rows + (r + 1) * w, rows + moved * w);
        r = moved;
      }
    }
  }

  [[gnu::noinline]] void cross_flush(const PairBatch& b, PairPartition::Slots& out, Chunk& ch) const {
    gather(b, ch);
    evaluate_columns_any(ch, b.ctx.dt, b.ctx.update, b.simd);
    for (int m = 0; m < ch.n; ++m) {
      const std::size_t r = static_cast<std::size_t>(ch.slot[m]);
      double* fi = &out.fi[6 * r];
      double* tj = &out.tj[3 * r];
      for (int d = 0; d < 3; ++d) {
        fi[d] = ch.f[d][m];
        fi[3 + d] = ch.ti[d][m];
        tj[d] = ch.tj[d][m];
      }
    }
    store_history(b, ch);
    ch.n = 0;
  }

  // Phase B, last: the i-side of range t's own cross entries, in list order,
  // once the later ranges' phase A has filled their slots.
  void apply_outgoing(const PairBatch& b, PairPartition& pp, int t) const {
    const int s0 = pp.cross_first[t], s1 = pp.cross_first[t + 1];
    if (s0 == s1) return;
    const long pass = pp.pass;
    for (int u = t + 1; u < pp.nparts; ++u)
      for (int spins = 0; pp.done_a[u].load(std::memory_order_acquire) != pass; ++spins)
        if (spins > 1000) std::this_thread::yield();  // more threads than cores
    int* next = &pp.cursor[pp.cursor_stride() * static_cast<std::size_t>(t)];
    for (int u = t + 1; u < pp.nparts; ++u) next[u - t - 1] = pp.slots[u].at[t];
    double* f = b.a.f;
    double* tq = b.a.torque;
    for (int s = s0; s < s1; ++s) {
      if (!pp.on[s]) continue;
      const int u = pp.cross_u[s], i = pp.cross_i[s];
      const double* fi = &pp.slots[u].fi[6 * static_cast<std::size_t>(next[u - t - 1]++)];
      for (int d = 0; d < 3; ++d) {
        f[3 * i + d] += fi[d];
        tq[3 * i + d] += fi[3 + d];
      }
    }
  }

  // Phase B, first: j-side contributions of cross entries to the atoms of
  // range t (evaluated by this thread in phase A). They come from earlier
  // ranges; taken in list order, each atom receives its own in list order, as
  // in the serial pass.
  void apply_incoming(const PairBatch& b, const PairPartition& pp, int t) const {
    double* f = b.a.f;
    double* tq = b.a.torque;
    const PairPartition::Slots& in = pp.slots[t];
    std::size_t r = 0;
    for (int q = pp.in_first[t]; q < pp.in_first[t + 1]; ++q) {
      const int s = pp.in_s[q];
      if (!pp.on[s]) continue;
      const int a = pp.cross_j[s];
      const double* fi = &in.fi[6 * r];
      const double* tj = &in.tj[3 * r];
      ++r;
      for (int d = 0; d < 3; ++d) {
        f[3 * a + d] -= fi[d];
        tq[3 * a + d] += tj[d];
      }
    }
  }

  // Ranges balanced by work: entries, touching ones counting 3 more, weighted
  // by the cost per weight each range took since the last split (cache misses,
  // threads slowed by the machine), re-split as soon as kLearnCalls passes show
  // the ranges more than 4 % apart: on a shared host one core can run at half
  // speed for 10-50 passes and then recover. A re-split costs a search per
  // bound and one look per atom for the cross entries (0.06 ms on bed_30k),
  // so following the host is cheap. Any split gives the same bits.
  static constexpr int kLearnCalls = 3;  // passes measured before a re-split
  void plan_partition(const PairBatch& b, int nparts) {
    PairPartition& pp = part_;
    const std::size_t n = b.a.n, ne = static_cast<std::size_t>(b.first[n]);
    const bool same_list = pp.version == b.list_version && pp.nparts == nparts && pp.natoms == n && pp.nentries == ne;
    if (same_list && !(pp.calls >= kLearnCalls && unbalanced(pp))) return;
    learn_costs(pp);
    pp.version = b.list_version;
    pp.nparts = nparts;
    pp.natoms = n;
    pp.nentries = ne;
    if (!same_list) {  // weights in parallel, then their running sum
      pp.cum.resize(n + 1);
      pp.cum[0] = 0.0;
      const long nl = static_cast<long>(n);
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nparts)
#endif
      for (long i = 0; i < nl; ++i) {
        int touching = 0;  // an integer count: no chain of dependent floating-point adds
        if constexpr (kH > 0)
          for (int k = b.first[i]; k < b.first[i + 1]; ++k) touching += b.row[k] >= 0;
        pp.cum[i + 1] = 1.0 + (b.first[i + 1] - b.first[i]) + 3.0 * touching;
      }
      for (std::size_t i = 0; i < n; ++i) pp.cum[i + 1] += pp.cum[i];
    }
    split(pp, nparts);
    cross_lists(b, pp);
    pp.rehome = !same_list;
    pp.busy.assign(nparts, 0.0);
    pp.calls = 0;
  }

  static bool unbalanced(const PairPartition& pp) {
    const auto [lo, hi] = std::minmax_element(pp.busy.begin(), pp.busy.end());
    return *hi > 1.04 * *lo;
  }

  // Seconds per unit of weight in each range since the last split.
  static void learn_costs(PairPartition& pp) {
    const int np = static_cast<int>(pp.busy.size());
    if (pp.calls < kLearnCalls || np != pp.nparts || pp.cum.size() != pp.natoms + 1 || pp.cum.back() <= 0.0) return;
    const double total = pp.cum.back();
    pp.seg_u.assign(np + 1, 1.0);
    pp.seg_d.assign(np, 0.0);
    for (int t = 0; t < np; ++t) {
      const double w = pp.cum[pp.lo[t + 1]] - pp.cum[pp.lo[t]];
      pp.seg_u[t] = pp.cum[pp.lo[t]] / total;
      pp.seg_d[t] = w > 0.0 ? pp.busy[t] / w : 0.0;
    }
    const double mean = std::accumulate(pp.busy.begin(), pp.busy.end(), 0.0) / total;
    for (double& d : pp.seg_d) d = d > 0.0 ? d : mean;  // an empty range: no measurement
    if (mean <= 0.0) pp.seg_u.clear();
  }

  // Range bounds with equal predicted time: weight times the learned cost of
  // its place (as a fraction of the total weight); equal weight before any.
  // The predicted time of the weight [0, c) is piecewise linear in c (slope
  // seg_d on each learned segment), so each bound is found by a search, with
  // no pass over the atoms.
  static void split(PairPartition& pp, int nparts) {
    const std::size_t n = pp.natoms;
    const double total = pp.cum[n];
    const std::size_t nseg = pp.seg_u.size() >= 2 && total > 0.0 ? pp.seg_d.size() : 0;
    std::vector<double> t0(nseg + 1, 0.0);  // predicted time at each segment's start
    for (std::size_t s = 0; s < nseg; ++s) t0[s + 1] = t0[s] + pp.seg_d[s] * (pp.seg_u[s + 1] - pp.seg_u[s]) * total;
    const double whole = nseg ? t0[nseg] : total;
    pp.lo.assign(nparts + 1, 0);
    for (int t = 1; t < nparts; ++t) {
      const double target = whole * t / nparts;
      double c = target;  // the weight whose predicted time is `target`
      if (nseg) {
        const std::size_t s = std::min<std::size_t>(std::upper_bound(t0.begin(), t0.end(), target) - t0.begin(), nseg) - 1;
        c = pp.seg_u[s] * total + (target - t0[s]) / pp.seg_d[s];
      }
      pp.lo[t] = static_cast<int>(std::lower_bound(pp.cum.begin(), pp.cum.end(), c) - pp.cum.begin());
      pp.lo[t] = std::clamp(pp.lo[t], pp.lo[t - 1], static_cast<int>(n));
    }
    pp.lo[nparts] = static_cast<int>(n);
  }

  // Cross entries (j in a later range) of each range, in list order. An atom's
  // entries are sorted by j, so its cross entries are a suffix, present only
  // when its last j lies beyond the range: one look per atom, cheap enough to
  // re-split whenever the threads drift apart.
  static void cross_lists(const PairBatch& b, PairPartition& pp) {
    const int nparts = pp.nparts;
    pp.cross_k.clear();
    pp.cross_i.clear();
    pp.cross_j.clear();
    pp.cross_first.assign(nparts + 1, 0);
    for (int t = 0; t + 1 < nparts; ++t) {
      const int hi = pp.lo[t + 1];
      for (int i = pp.lo[t]; i < hi; ++i) {
        const int k0 = b.first[i], k1 = b.first[i + 1];
        if (k1 == k0 || b.jlist[k1 - 1] < hi) continue;
        int k = k1;
        while (k > k0 && b.jlist[k - 1] >= hi) --k;
        for (; k < k1; ++k) {
          pp.cross_k.push_back(k);
          pp.cross_i.push_back(i);
          pp.cross_j.push_back(b.jlist[k]);
        }
      }
      pp.cross_first[t + 1] = static_cast<int>(pp.cross_k.size());
    }
    const int ncross = static_cast<int>(pp.cross_k.size());
    pp.cross_first[nparts] = ncross;
    // Each range's incoming entries, by a counting sort on j's range (stable:
    // list order within each).
    pp.cross_u.resize(ncross);
    pp.in_first.assign(nparts + 1, 0);
    for (int s = 0; s < ncross; ++s) {
      pp.cross_u[s] = static_cast<int>(std::upper_bound(pp.lo.begin(), pp.lo.end(), pp.cross_j[s]) - pp.lo.begin()) - 1;
      ++pp.in_first[pp.cross_u[s] + 1];
    }
    for (int u = 0; u < nparts; ++u) pp.in_first[u + 1] += pp.in_first[u];
    pp.in_s.resize(ncross);
    std::vector<int> at(pp.in_first.begin(), pp.in_first.end() - 1);
    for (int s = 0; s < ncross; ++s) pp.in_s[at[pp.cross_u[s]]++] = s;
    pp.on.resize(ncross);  // each entry's, and its slot row, written in phase A
    pp.slots.resize(nparts);
    for (int u = 0; u < nparts; ++u) {
      const std::size_t m = static_cast<std::size_t>(pp.in_first[u + 1] - pp.in_first[u]);
      pp.slots[u].fi.resize(6 * m);
      pp.slots[u].tj.resize(3 * m);
      pp.slots[u].at.assign(nparts, 0);
    }
    pp.cursor.resize(pp.cursor_stride() * static_cast<std::size_t>(nparts));
    if (pp.done_a.size() < static_cast<std::size_t>(nparts)) pp.done_a = std::vector<std::atomic<long>>(nparts);  // zeroed
  }

  // Wall contacts: gathered into columns and evaluated like pair contacts
  // (stage 2 above); forces added to the grains and written to b.force.
  void wall_forces_staged(const WallBatch& b) {
    const AtomView& a = b.a;
    WallChunk<kH> ch;
    ch.tp0 = a.stride > 2 ? -1 : a.stride + b.wall_type;  // one atom type (1): one type pair
    for (std::size_t k0 = 0; k0 < b.n; k0 += WallChunk<kH>::kCap) {
      const int n = static_cast<int>(std::min<std::size_t>(WallChunk<kH>::kCap, b.n - k0));
      ch.n = n;
      for (int m = 0; m < n; ++m) {
        const std::size_t k = k0 + m;
        const int i = b.atom[k];
        for (int d = 0; d < 3; ++d) {
          ch.en[d][m] = b.en[3 * k + d];
          ch.vr[d][m] = a.v[3 * i + d] - b.vwall[3 * k + d];
          ch.wi[d][m] = a.omega[3 * i + d];
        }
        ch.deltan[m] = b.deltan[k];
        ch.radi[m] = a.radius[i];
        ch.mi[m] = a.rmass[i];
        ch.itype[m] = a.type[i];
        ch.jtype[m] = b.wall_type;
        ch.tp[m] = a.type[i] * a.stride + b.wall_type;
        if constexpr (kH > 0) {
          const double* h = b.hist + static_cast<std::size_t>(b.hist_index[k]) * b.hist_stride;
          for (int q = 0; q < kH; ++q) ch.h[q][m] = h[q];
        }
      }
      evaluate_columns_any(ch, b.ctx.dt, b.ctx.update, b.simd);
      for (int m = 0; m < n; ++m) {
        const std::size_t k = k0 + m;
        const int i = b.atom[k];
        for (int d = 0; d < 3; ++d) {
          a.f[3 * i + d] += ch.f[d][m];
          a.torque[3 * i + d] += ch.ti[d][m];
          b.force[3 * k + d] = ch.f[d][m];
        }
        if constexpr (kH > 0)
          if (b.ctx.update) {
            double* h = b.hist + static_cast<std::size_t>(b.hist_index[k]) * b.hist_stride;
            for (int q = 0; q < kH; ++q) h[q] = ch.h[q][m];
          }
      }
    }
  }

  // Per-contact records of wall contacts (compute wall/gran/local); history is copied, never written.
  template <bool kRecord>
  Vec3 wall_loop(const WallBatch& b, ContactRecords* out) {
    static_assert(kRecord, "forces go through wall_forces_staged");
    const AtomView& a = b.a;
    const StepContext ctx{b.ctx.dt, false};
    [[maybe_unused]] double hbuf[kH > 0 ? kH : 1];
    for (std::size_t k = 0; k < b.n; ++k) {
      const int i = b.atom[k];
      const double* en = b.en + 3 * k;
      WallState s;
      for (int d = 0; d < 3; ++d) {
        s.en[d] = en[d];
        s.vr[d] = a.v[3 * i + d] - b.vwall[3 * k + d];
        s.wi[d] = a.omega[3 * i + d];
      }
      s.deltan = b.deltan[k];
      s.radi = a.radius[i];
      s.mi = a.rmass[i];
      Contact c;
      wall_kinematics(c, s);
      c.itype = a.type[i];
      c.jtype = b.wall_type;
      c.tp = c.itype * a.stride + c.jtype;
      double* h = nullptr;
      if constexpr (kH > 0) {
        const double* hs = b.hist + static_cast<std::size_t>(b.hist_index[k]) * b.hist_stride;
        for (int m = 0; m < kH; ++m) hbuf[m] = hs[m];
        h = hbuf;
      }
      const Parts p = evaluate(c, h, ctx);
      ContactRecord r{i, -1, static_cast<int>(k), {p.f[0], p.f[1], p.f[2]}, {p.ti[0], p.ti[1], p.ti[2]},
                      c.deltan, {en[0], en[1], en[2]}};
      out->rows.push_back(r);
      if constexpr (kH > 0) out->hist.insert(out->hist.end(), h, h + kH);
    }
    return {};
  }
};

}  // namespace sable
