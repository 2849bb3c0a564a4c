#pragma once
// What the contact loop hands a contact law: the state of a batch of touching
// contacts in columns (PairChunk for grain pairs, WallChunk for grain-wall
// contacts of every wall kind), the kinematics every law computes from them
// (LIGGGHTS' conventions), and the interface a law implements (ColumnLaw).
// The loop (core/engine/contact_loop.h) fills the columns; the law reads them and
// writes each contact's force, torques and new history; nothing else passes.
#include <cmath>
#include <cstdint>

#include "core/engine/atoms.h"
#include "core/engine/threads.h"

namespace sable {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
// The same sum over the first kD components (2D: z is zero and left out).
template <int kD>
inline double dot_d(const double* a, const double* b) {
  return kD == 3 ? a[0] * b[0] + a[1] * b[1] + a[2] * b[2] : a[0] * b[0] + a[1] * b[1];
}

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
  // The kinematics mode (ContactK): a sub-model templated on the contact type
  // may leave out what is zero (z components in 2D, rotation when frozen).
  static constexpr int kDim = 3;
  static constexpr bool kRotation = true;
};

// A contact seen in a mode the kernel knows at compile time: kD = 2, every
// grain in the x-y plane with spin about z only (z components and in-plane
// spin are exactly 0, so what is left out adds nothing); kRot = false, no
// grain turns (omega is not read and no torque made). The full 3D kernel on
// the same scene gives the same numbers (up to the sign of zeros).
template <int kD, bool kRot>
struct ContactK : Contact {
  static constexpr int kDim = kD;
  static constexpr bool kRotation = kRot;
};

// How a loop's contacts may be evaluated (AtomView::kinematics()).
enum class Kinematics : std::uint8_t { Full = 0, Plane = 1, Frozen = 2, PlaneFrozen = 3 };

// Per-step context shared by all contacts of one loop.
struct StepContext {
  double dt = 0;
  bool update = true;  // false during setup and for per-contact output: history is read, never written
};


// Raw views of the atom arrays a loop reads and writes.
struct AtomView {
  std::size_t n = 0;
  std::size_t nghost = 0;  // ghosts after the n owned atoms (several ranks)
  const double *x = nullptr, *v = nullptr, *omega = nullptr, *radius = nullptr, *rmass = nullptr;
  const int* type = nullptr;
  const std::uint32_t* mask = nullptr;
  double *f = nullptr, *torque = nullptr;
  int stride = 2;                 // ntypes + 1 (per-type-pair table stride)
  std::uint32_t freeze_bit = 0;   // grains of this group count as infinitely heavy (LIGGGHTS fix freeze)
  bool plane_2d = false, rotation = true;  // Atoms::plane_2d, Atoms::rotation
  Kinematics kinematics() const {
    return static_cast<Kinematics>((plane_2d ? 1 : 0) | (rotation ? 0 : 2));
  }
};

// The per-atom arrays a kernel reads and writes, for the first n atoms.
inline AtomView atom_view(Atoms& at, std::size_t n, std::uint32_t freeze_bit) {
  AtomView a;
  a.n = n;
  a.nghost = at.nghost;
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
  a.plane_2d = at.plane_2d;
  a.rotation = at.rotation;
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
// the same numbers bit for bit. kD = 2 leaves out the z terms, !kRot the spin
// (ContactK): the terms left out are exact zeros there.
template <int kD = 3, bool kRot = true>
[[gnu::always_inline]] inline void pair_kinematics(Contact& c, const PairState& s) {
  constexpr bool k3 = kD == 3;
  c.is_wall = false;
  const double rsq = k3 ? s.dx * s.dx + s.dy * s.dy + s.dz * s.dz : s.dx * s.dx + s.dy * s.dy;
  c.r = std::sqrt(rsq);
  const double rinv = 1.0 / c.r;
  c.en[0] = s.dx * rinv;
  c.en[1] = s.dy * rinv;
  c.en[2] = k3 ? s.dz * rinv : 0.0;
  const double radsum = s.radi + s.radj;
  c.deltan = radsum - c.r;
  c.radi = s.radi;
  c.radj = s.radj;
  c.reff = s.radi * s.radj / radsum;
  const double meff = s.mi * s.mj / (s.mi + s.mj);
  c.meff = (s.frozen & 2) ? s.mi : (s.frozen & 1) ? s.mj : meff;
  c.vn = k3 ? s.vr[0] * c.en[0] + s.vr[1] * c.en[1] + s.vr[2] * c.en[2] : s.vr[0] * c.en[0] + s.vr[1] * c.en[1];
  c.cri = s.radi - 0.5 * c.deltan;
  c.crj = s.radj - 0.5 * c.deltan;
  c.vtr[0] = s.vr[0] - c.vn * c.en[0];
  c.vtr[1] = s.vr[1] - c.vn * c.en[1];
  c.vtr[2] = k3 ? s.vr[2] - c.vn * c.en[2] : 0.0;
  c.wroll[0] = c.wroll[1] = c.wroll[2] = 0.0;
  if constexpr (kRot) {  // the contact points' velocity from the spins
    const double wr2 = (c.cri * s.wi[2] + c.crj * s.wj[2]) * rinv;
    if constexpr (k3) {
      const double wr0 = (c.cri * s.wi[0] + c.crj * s.wj[0]) * rinv;
      const double wr1 = (c.cri * s.wi[1] + c.crj * s.wj[1]) * rinv;
      c.vtr[0] -= s.dz * wr1 - s.dy * wr2;
      c.vtr[1] -= s.dx * wr2 - s.dz * wr0;
      c.vtr[2] -= s.dy * wr0 - s.dx * wr1;
      c.wroll[0] = s.wi[0] - s.wj[0];
      c.wroll[1] = s.wi[1] - s.wj[1];
    } else {
      c.vtr[0] += s.dy * wr2;
      c.vtr[1] -= s.dx * wr2;
    }
    c.wroll[2] = s.wi[2] - s.wj[2];
  }
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

  // Contact kinematics of column m in the mode of K (Contact or ContactK).
  template <class K = Contact>
  [[gnu::always_inline]] inline void contact(int m, K& c) const {
    constexpr int kD = K::kDim;
    constexpr bool kRot = K::kRotation;
    PairState s;
    s.dx = dx[m];
    s.dy = dy[m];
    s.dz = kD == 3 ? dz[m] : 0.0;
    s.radi = radi[m];
    s.radj = radj[m];
    s.mi = mi[m];
    s.mj = mj[m];
    s.frozen = frozen[m];
    for (int d = 0; d < 3; ++d) {  // only what the mode reads (the rest is never gathered)
      const bool used = d < kD;
      const bool spin = kRot && (kD == 3 || d == 2);
      s.vr[d] = used ? vr[d][m] : 0.0;
      s.wi[d] = spin ? wi[d][m] : 0.0;
      s.wj[d] = spin ? wj[d][m] : 0.0;
    }
    pair_kinematics<kD, kRot>(c, s);
    c.itype = itype[m];
    c.jtype = jtype[m];
    c.tp = tp[m];
  }
  // kRot false: no torque columns (the scatter then adds none).
  template <bool kRot = true>
  [[gnu::always_inline]] inline void store(int m, const ContactParts& p) {
    for (int d = 0; d < 3; ++d) {
      f[d][m] = p.f[d];
      if constexpr (kRot) {
        ti[d][m] = p.ti[d];
        tj[d][m] = p.tj[d];
      }
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
// kD, kRot as pair_kinematics (in 2D the normal's z is taken as 0: a wall
// touching grains in the plane has an in-plane normal).
template <int kD = 3, bool kRot = true>
[[gnu::always_inline]] inline void wall_kinematics(Contact& c, const WallState& s) {
  constexpr bool k3 = kD == 3;
  c.is_wall = true;
  c.en[0] = s.en[0];
  c.en[1] = s.en[1];
  c.en[2] = k3 ? s.en[2] : 0.0;
  c.deltan = s.deltan;
  c.radi = s.radi;
  c.radj = 0.0;
  c.r = c.radi - c.deltan;
  c.reff = c.radi;  // wall: infinite radius ...
  c.meff = s.mi;    // ... and infinite mass
  c.vn = k3 ? s.vr[0] * s.en[0] + s.vr[1] * s.en[1] + s.vr[2] * s.en[2] : s.vr[0] * s.en[0] + s.vr[1] * s.en[1];
  c.cri = c.radi - 0.5 * c.deltan;
  c.crj = 0.0;
  c.vtr[0] = s.vr[0] - c.vn * c.en[0];
  c.vtr[1] = s.vr[1] - c.vn * c.en[1];
  c.vtr[2] = k3 ? s.vr[2] - c.vn * c.en[2] : 0.0;
  c.wroll[0] = c.wroll[1] = c.wroll[2] = 0.0;
  if constexpr (kRot) {
    // LIGGGHTS: wr = cri w_i / r and vtr = vt - wr x (r en), i.e. contact point of i at -cri en.
    const double q = c.cri / c.r;
    const double dx = c.en[0] * c.r, dy = c.en[1] * c.r;
    c.wroll[2] = q * s.wi[2];
    if constexpr (k3) {
      const double dz = c.en[2] * c.r;
      c.wroll[0] = q * s.wi[0];
      c.wroll[1] = q * s.wi[1];
      c.vtr[0] -= dz * c.wroll[1] - dy * c.wroll[2];
      c.vtr[1] -= dx * c.wroll[2] - dz * c.wroll[0];
      c.vtr[2] -= dy * c.wroll[0] - dx * c.wroll[1];
    } else {
      c.vtr[0] += dy * c.wroll[2];
      c.vtr[1] -= dx * c.wroll[2];
    }
  }
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

  template <class K = Contact>
  [[gnu::always_inline]] inline void contact(int m, K& c) const {
    constexpr int kD = K::kDim;
    constexpr bool kRot = K::kRotation;
    WallState s;
    for (int d = 0; d < 3; ++d) {
      const bool used = d < kD;
      s.en[d] = used ? en[d][m] : 0.0;
      s.vr[d] = used ? vr[d][m] : 0.0;
      s.wi[d] = kRot && (kD == 3 || d == 2) ? wi[d][m] : 0.0;
    }
    s.deltan = deltan[m];
    s.radi = radi[m];
    s.mi = mi[m];
    wall_kinematics<kD, kRot>(c, s);
    c.itype = itype[m];
    c.jtype = jtype[m];
    c.tp = tp[m];
  }
  template <bool kRot = true>
  [[gnu::always_inline]] inline void store(int m, const ContactParts& p) {
    for (int d = 0; d < 3; ++d) {
      f[d][m] = p.f[d];
      if constexpr (kRot) ti[d][m] = p.ti[d];
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
  // kin: the loop's mode (AtomView::kinematics); a law may always use Full,
  // which gives the same numbers, only slower.
  virtual void evaluate(PairChunk<kH>& ch, double dt, bool update, Simd simd, Kinematics kin) const = 0;
  virtual void evaluate(WallChunk<kH>& ch, double dt, bool update, Simd simd, Kinematics kin) const = 0;
};

}  // namespace sable
