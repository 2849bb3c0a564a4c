#pragma once
// What the contact loop hands a contact law: the state of a batch of touching
// contacts in columns (PairChunk for grain pairs, WallChunk for grain-wall
// contacts of every wall kind), the kinematics every law computes from them
// (LIGGGHTS' conventions), and the interface a law implements (ColumnLaw).
// The loop (core/contact_loop.h) fills the columns; the law reads them and
// writes each contact's force, torques and new history; nothing else passes.
#include <cmath>
#include <cstdint>

#include "core/atoms.h"
#include "core/threads.h"

namespace sable {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

struct Contact {
  double en[3];      // unit normal, j (or wall) -> i
  double deltan;     // overlap (> 0)
  double r;          // centre distance (wall: centre to wall = radi - deltan)
  double radi, radj;  // radj = 0 for a wall (infinite radius)
  double reff, meff;  // R* (wall: radi) and m* (wall: m_i)
  double cri, crj;    // contact radii r - deltan/2 (crj = 0 for a wall)
  double vn;          // normal relative velocity
  double vtr[3];      // tangential relative velocity at the contact point
  double wroll[3];    // relative spin for rolling friction (pair: w_i - w_j; wall: cri w_i / r as LIGGGHTS)
  int itype, jtype;   // jtype = wall material type for walls
  int tp;             // itype * (ntypes + 1) + jtype: index into per-type-pair tables
  bool is_wall;
};

// Per-step context shared by all contacts of one loop.
struct StepContext {
  double dt = 0;
  bool update = true;  // false during setup and for per-contact output: history is read, never written
};


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
  a.rmass = at.mass_override >= 0 ? at.column(at.mass_override).data() : at.rmass.data();
  a.type = at.type.data();
  a.mask = at.mask.data();
  a.f = at.f.data();
  a.torque = at.torque.data();
  a.stride = at.ntypes + 1;
  a.freeze_bit = freeze_bit;
  return a;
}


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
// (see ContactLoop::pair_forces), scattered in list order.
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

// Wall contacts gathered into columns (ContactLoop::wall_forces).
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


// What the contact loop needs of a law with kH history values per contact:
// evaluate every column of a chunk (force on i, torques on i and j; with
// `update`, the new history in place). Crossed once per chunk of up to 64
// contacts, so the per-contact code inlines and vectorises inside the law.
template <int kH>
class ColumnLaw {
 public:
  virtual ~ColumnLaw() = default;
  virtual void evaluate(PairChunk<kH>& ch, double dt, bool update, Simd simd) const = 0;
  virtual void evaluate(WallChunk<kH>& ch, double dt, bool update, Simd simd) const = 0;
};

}  // namespace sable
