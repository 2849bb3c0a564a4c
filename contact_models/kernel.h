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
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

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

// Particle-particle contacts: Neighbor's half list plus history parallel to it.
struct PairBatch {
  AtomView a;
  const int* first = nullptr;             // n + 1 offsets
  const int* jlist = nullptr;
  const std::uint8_t* shift = nullptr;    // image code per entry
  const double (*shift_vec)[3] = nullptr; // j's image = x[j] + shift_vec[code]
  double* hist = nullptr;                 // kHistory doubles per list entry (null without history)
  std::uint8_t* touch = nullptr;
  StepContext ctx;
  std::uint32_t groupbit = ~0u;           // records: both grains must be in this group
  // LIGGGHTS 3.8 mode (pair_gran.h): a separated pair keeps its history until
  // the first force pass after a neighbour rebuild (`rebuilt`), then loses it.
  bool keep_until_rebuild = false, rebuilt = false;
};

// Particle-wall contacts found by a wall fix (overlap > 0 only).
struct WallBatch {
  AtomView a;
  std::size_t n = 0;
  const int* atom = nullptr;       // atom index of contact k
  const double* deltan = nullptr;  // overlap
  const double* en = nullptr;      // 3 per contact: unit normal, wall -> particle centre
  const double* vwall = nullptr;   // 3 per contact: wall velocity at the contact
  double* hist = nullptr;          // history of contact k at hist + hist_index[k] * hist_stride
  const int* hist_index = nullptr;
  int hist_stride = 0;
  int wall_type = 1;
  StepContext ctx;
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
  // Adds forces to the grains; returns the summed force on the grains.
  virtual Vec3 wall_forces(const WallBatch& b) = 0;
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
  void pair_forces(const PairBatch& b) override { pair_loop<false>(b, nullptr); }
  void pair_records(const PairBatch& b, ContactRecords& out) override {
    out.clear();
    out.hist_size = kH;
    pair_loop<true>(b, &out);
  }
  Vec3 wall_forces(const WallBatch& b) override { return wall_loop<false>(b, nullptr); }
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

  struct Parts {
    double f[3], ti[3], tj[3];
  };

  // All sub-models on one contact: force on i and torques on i and j.
  inline Parts evaluate(const Contact& c, double* h, const StepContext& ctx) const {
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

  // kRecord: per-contact output at the current state; history is copied, never written.
  template <bool kRecord>
  void pair_loop(const PairBatch& b, ContactRecords* out) {
    const AtomView& a = b.a;
    const double *x = a.x, *v = a.v, *w = a.omega;
    const StepContext ctx{b.ctx.dt, kRecord ? false : b.ctx.update};
    [[maybe_unused]] double hbuf[kH > 0 ? kH : 1];
    for (std::size_t i = 0; i < a.n; ++i) {
      if constexpr (kRecord)
        if (!(a.mask[i] & b.groupbit)) continue;
      const double xi = x[3 * i], yi = x[3 * i + 1], zi = x[3 * i + 2];
      const double radi = a.radius[i], mi = a.rmass[i];
      const int itype = a.type[i];
      const bool ifrozen = a.mask[i] & a.freeze_bit;
      for (int k = b.first[i]; k < b.first[i + 1]; ++k) {
        const int j = b.jlist[k];
        const double* sh = b.shift_vec[b.shift[k]];
        const double dx = xi - (x[3 * j] + sh[0]), dy = yi - (x[3 * j + 1] + sh[1]), dz = zi - (x[3 * j + 2] + sh[2]);
        const double rsq = dx * dx + dy * dy + dz * dz;
        const double radj = a.radius[j], radsum = radi + radj;
        if (rsq >= radsum * radsum) {
          if constexpr (kH > 0 && !kRecord)
            if (b.touch[k] && (!b.keep_until_rebuild || b.rebuilt)) {  // contact ended: forget it
              b.touch[k] = 0;
              for (int m = 0; m < kH; ++m) b.hist[k * kH + m] = 0.0;
            }
          continue;
        }
        if constexpr (kRecord)
          if (!(a.mask[j] & b.groupbit)) continue;
        Contact c;
        c.is_wall = false;
        c.r = std::sqrt(rsq);
        const double rinv = 1.0 / c.r;
        c.en[0] = dx * rinv;
        c.en[1] = dy * rinv;
        c.en[2] = dz * rinv;
        c.deltan = radsum - c.r;
        c.radi = radi;
        c.radj = radj;
        c.reff = radi * radj / radsum;
        const double mj = a.rmass[j];
        c.meff = mi * mj / (mi + mj);
        if (ifrozen) c.meff = mj;
        if (a.mask[j] & a.freeze_bit) c.meff = mi;
        const double vr0 = v[3 * i] - v[3 * j], vr1 = v[3 * i + 1] - v[3 * j + 1], vr2 = v[3 * i + 2] - v[3 * j + 2];
        c.vn = vr0 * c.en[0] + vr1 * c.en[1] + vr2 * c.en[2];
        c.cri = radi - 0.5 * c.deltan;
        c.crj = radj - 0.5 * c.deltan;
        const double wr0 = (c.cri * w[3 * i] + c.crj * w[3 * j]) * rinv;
        const double wr1 = (c.cri * w[3 * i + 1] + c.crj * w[3 * j + 1]) * rinv;
        const double wr2 = (c.cri * w[3 * i + 2] + c.crj * w[3 * j + 2]) * rinv;
        c.vtr[0] = vr0 - c.vn * c.en[0] - (dz * wr1 - dy * wr2);
        c.vtr[1] = vr1 - c.vn * c.en[1] - (dx * wr2 - dz * wr0);
        c.vtr[2] = vr2 - c.vn * c.en[2] - (dy * wr0 - dx * wr1);
        c.wroll[0] = w[3 * i] - w[3 * j];
        c.wroll[1] = w[3 * i + 1] - w[3 * j + 1];
        c.wroll[2] = w[3 * i + 2] - w[3 * j + 2];
        c.itype = itype;
        c.jtype = a.type[j];
        c.tp = itype * a.stride + c.jtype;
        double* h = nullptr;
        if constexpr (kH > 0) {
          h = b.hist + static_cast<std::size_t>(k) * kH;
          if constexpr (kRecord) {
            for (int m = 0; m < kH; ++m) hbuf[m] = h[m];
            h = hbuf;
          } else {
            b.touch[k] = 1;
          }
        }
        const Parts p = evaluate(c, h, ctx);
        if constexpr (kRecord) {
          ContactRecord r{static_cast<int>(i), j, b.shift[k], {p.f[0], p.f[1], p.f[2]}, {p.ti[0], p.ti[1], p.ti[2]},
                          c.deltan, {c.en[0], c.en[1], c.en[2]}};
          out->rows.push_back(r);
          if constexpr (kH > 0) out->hist.insert(out->hist.end(), h, h + kH);
        } else {
          double* fi = a.f + 3 * i;
          double* fj = a.f + 3 * j;
          double* ti = a.torque + 3 * i;
          double* tj = a.torque + 3 * j;
          for (int d = 0; d < 3; ++d) {
            fi[d] += p.f[d];
            fj[d] -= p.f[d];
            ti[d] += p.ti[d];
            tj[d] += p.tj[d];
          }
        }
      }
    }
  }

  template <bool kRecord>
  Vec3 wall_loop(const WallBatch& b, ContactRecords* out) {
    const AtomView& a = b.a;
    const double *v = a.v, *w = a.omega;
    const StepContext ctx{b.ctx.dt, kRecord ? false : b.ctx.update};
    [[maybe_unused]] double hbuf[kH > 0 ? kH : 1];
    double sum[3] = {0, 0, 0};
    for (std::size_t k = 0; k < b.n; ++k) {
      const int i = b.atom[k];
      const double* en = b.en + 3 * k;
      const double* vw = b.vwall + 3 * k;
      Contact c;
      c.is_wall = true;
      c.en[0] = en[0];
      c.en[1] = en[1];
      c.en[2] = en[2];
      c.deltan = b.deltan[k];
      c.radi = a.radius[i];
      c.radj = 0.0;
      c.r = c.radi - c.deltan;
      c.reff = c.radi;     // wall: infinite radius ...
      c.meff = a.rmass[i];  // ... and infinite mass
      const double vr0 = v[3 * i] - vw[0], vr1 = v[3 * i + 1] - vw[1], vr2 = v[3 * i + 2] - vw[2];
      c.vn = vr0 * en[0] + vr1 * en[1] + vr2 * en[2];
      c.cri = c.radi - 0.5 * c.deltan;
      c.crj = 0.0;
      // LIGGGHTS: wr = cri w_i / r and vtr = vt - wr x (r en), i.e. contact point of i at -cri en.
      const double s = c.cri / c.r;
      c.wroll[0] = s * w[3 * i];
      c.wroll[1] = s * w[3 * i + 1];
      c.wroll[2] = s * w[3 * i + 2];
      const double dx = en[0] * c.r, dy = en[1] * c.r, dz = en[2] * c.r;
      c.vtr[0] = vr0 - c.vn * en[0] - (dz * c.wroll[1] - dy * c.wroll[2]);
      c.vtr[1] = vr1 - c.vn * en[1] - (dx * c.wroll[2] - dz * c.wroll[0]);
      c.vtr[2] = vr2 - c.vn * en[2] - (dy * c.wroll[0] - dx * c.wroll[1]);
      c.itype = a.type[i];
      c.jtype = b.wall_type;
      c.tp = c.itype * a.stride + c.jtype;
      double* h = nullptr;
      if constexpr (kH > 0) {
        h = b.hist + static_cast<std::size_t>(b.hist_index[k]) * b.hist_stride;
        if constexpr (kRecord) {
          for (int m = 0; m < kH; ++m) hbuf[m] = h[m];
          h = hbuf;
        }
      }
      const Parts p = evaluate(c, h, ctx);
      if constexpr (kRecord) {
        ContactRecord r{i, -1, static_cast<int>(k), {p.f[0], p.f[1], p.f[2]}, {p.ti[0], p.ti[1], p.ti[2]},
                        c.deltan, {en[0], en[1], en[2]}};
        out->rows.push_back(r);
        if constexpr (kH > 0) out->hist.insert(out->hist.end(), h, h + kH);
      } else {
        for (int d = 0; d < 3; ++d) {
          a.f[3 * i + d] += p.f[d];
          a.torque[3 * i + d] += p.ti[d];
          sum[d] += p.f[d];
        }
      }
    }
    return {sum[0], sum[1], sum[2]};
  }
};

}  // namespace sable
