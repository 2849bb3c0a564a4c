#pragma once
// A contact law: the compile-time composition of one sub-model per axis
// (normal, damping, tangential, rolling, cohesion), GranKernel<N, D, T, R, C>,
// evaluating a chunk of
// contacts from their kinematics (core/engine/contact_columns.h) and nothing else.
// The sub-model structs inline into one branch-free loop over the chunk's
// columns, which the compiler vectorises; the virtual interfaces are crossed
// once per chunk. Everything else (which contacts touch, threads, history
// rows, gathering and scattering) is the contact loop's, in core
// (core/engine/contact_loop.h), shared by every law and every contact source: the
// pair list, primitive walls, meshes. The same law serves them all, as
// LIGGGHTS registers each ContactModel<Style> for both pair and wall.
// Compiled for the combinations of contact_models/compiled_laws.txt; every
// other combination runs composed at run time (composed.h) with the same steps.
//
// A sub-model struct provides (see contact_models/README.md):
//   static constexpr const char* kName;  static constexpr int kHistory;
//   static void history_slots(std::vector<HistorySlot>&);
//   void settings(ModelSettings&);  void connect(PropertyRequest&);
//   normal:     NormalForce force(const Contact&, double* hist, const StepContext&) const;  (kn, kt, Fel, s)
//               void limit(NormalForce&) const;  (limitForce)
//               double contact_time(const ContactTimeInput&) const;  (undamped)
//               static constexpr LiggghtsDamping kLiggghtsDamping;  (its LIGGGHTS dashpot's form)
//   damping:    template <class N> void damp(const N&, const Contact&, NormalForce&) const;  (gamman, gammat)
//               optional: template <class N> double contact_time(const N&, const ContactTimeInput&) const;
//   tangential: Vec3 force(const Contact&, const NormalForce&, double* hist, const StepContext&) const;
//   rolling:    Vec3 torque(const Contact&, const NormalForce&, double* hist, const StepContext&) const;
//   cohesion:   static constexpr bool kActive;
//               double force(const Contact&, const NormalForce&, double* hist, const StepContext&) const;
//               bool reduces_tangential() const;  (the Coulomb cap sees the force: tangential_reduce)
// History columns follow the axes' order: normal, damping, tangential, rolling, cohesion.
#include <memory>
#include <string>
#include <vector>

#include "contact_models/contact.h"
#include "contact_models/materials.h"
#include "core/engine/contact_loop.h"

namespace sable {

// A law as the styles see it: its names, keywords and coefficients, and the
// contact loop that drives it (pair_forces ... wall_records go to the loop).
class ContactKernel {
 public:
  virtual ~ContactKernel() = default;
  // "model hertz damping liggghts tangential history rolling_friction cdt cohesion off"
  virtual std::string name() const = 0;
  virtual void settings(ModelSettings& s) = 0;
  // Look up coefficient tables; errors name `line` (the pair_style / fix wall/gran command).
  virtual void connect(const std::shared_ptr<Materials>& m, const Args& line) = 0;
  virtual const std::vector<HistorySlot>& history_slots() const = 0;
  virtual double contact_time(const ContactTimeInput& in) const = 0;

  void pair_forces(const PairBatch& b) { loop_->pair_forces(b); }
  void pair_records(const PairBatch& b, ContactRecords& out) { loop_->pair_records(b, out); }
  // Adds forces to the grains and writes each contact's force to b.force.
  // Called concurrently on batches with disjoint grains (FixWallGran's ranges).
  void wall_forces(const WallBatch& b) const { loop_->wall_forces(b); }
  void wall_records(const WallBatch& b, ContactRecords& out) const { loop_->wall_records(b, out); }

 protected:
  std::unique_ptr<ContactLoop> loop_;
};

// The steps of one contact that every law shares, compiled (GranKernel) or
// composed at run time (contact_models/composed.h): one definition, so both
// do the same operations in the same order and give the same bits.

// The normal model's force with the damping model's dashpot, then limitForce.
template <class N, class D, class K>
[[gnu::always_inline]] inline NormalForce damped_normal_force(const N& normal, const D& damping, const K& c, double* h,
                                                              const StepContext& ctx) {
  NormalForce nf = normal.force(c, h, ctx);
  damping.damp(normal, c, nf);
  nf.Fn = nf.Fel - nf.gamman * c.vn;
  normal.limit(nf);
  return nf;
}

// The law's contact time (the stability check): the damping model's where it
// has one (a linear spring with its dashpot), else the normal model's.
template <class N, class D>
double law_contact_time(const N& normal, const D& damping, const ContactTimeInput& in) {
  if constexpr (requires { damping.contact_time(normal, in); })
    return damping.contact_time(normal, in);
  else
    return normal.contact_time(in);
}

// A cohesive pull f acts on the grains; the Coulomb cap and rolling friction
// see it only when `seen` (tangential_reduce on, LIGGGHTS 3.8's sidata.Fn).
// Returns the part kept apart from nf.Fn.
[[gnu::always_inline]] inline double add_cohesion(NormalForce& nf, double f, bool seen) {
  nf.Fn += seen ? f : 0.0;
  return seen ? 0.0 : f;
}

// Force on i (normal fn along en plus ft) and the torques on i and j (lever
// arms cri, crj; rolling torque mr taken from i, given to j).
template <class K>
[[gnu::always_inline]] inline ContactParts contact_parts(const K& c, double fn, const Vec3& ft, const Vec3& mr) {
  constexpr bool k3 = K::kDim == 3;
  const double* en = c.en;
  ContactParts p{};
  p.f[0] = fn * en[0] + ft.x;
  p.f[1] = fn * en[1] + ft.y;
  p.f[2] = k3 ? fn * en[2] + ft.z : 0.0;
  if constexpr (K::kRotation) {
    const double tor2 = en[0] * ft.y - en[1] * ft.x;
    p.ti[2] = -c.cri * tor2 - mr.z;
    p.tj[2] = -c.crj * tor2 + mr.z;
    if constexpr (k3) {
      const double tor0 = en[1] * ft.z - en[2] * ft.y, tor1 = en[2] * ft.x - en[0] * ft.z;
      p.ti[0] = -c.cri * tor0 - mr.x;
      p.ti[1] = -c.cri * tor1 - mr.y;
      p.tj[0] = -c.crj * tor0 + mr.x;
      p.tj[1] = -c.crj * tor1 + mr.y;
    } else {
      p.ti[0] = p.ti[1] = p.tj[0] = p.tj[1] = 0.0;
    }
  }
  return p;
}

template <class N, class D, class T, class R, class C>
class GranKernel final
    : public ContactKernel,
      public ColumnLaw<N::kHistory + D::kHistory + T::kHistory + R::kHistory + C::kHistory> {
 public:
  static constexpr int kHN = N::kHistory, kHD = D::kHistory, kHT = T::kHistory, kHR = R::kHistory;
  static constexpr int kH = kHN + kHD + kHT + kHR + C::kHistory;
  static_assert(kH <= kMaxLoopHistory, "more history values per contact than core/engine/contact_loop.cpp builds loops for");

  GranKernel() {
    N::history_slots(slots_);
    D::history_slots(slots_);
    T::history_slots(slots_);
    R::history_slots(slots_);
    C::history_slots(slots_);
    loop_ = make_contact_loop<kH>(*this);
  }
  std::string name() const override {
    return std::string("model ") + N::kName + " damping " + D::kName + " tangential " + T::kName +
           " rolling_friction " + R::kName + " cohesion " + C::kName;
  }
  void settings(ModelSettings& s) override {
    normal_.settings(s);
    damping_.settings(s);
    tangential_.settings(s);
    rolling_.settings(s);
    cohesion_.settings(s);
  }
  void connect(const std::shared_ptr<Materials>& m, const Args& line) override {
    materials_ = m;  // keeps the tables the sub-models point into alive
    PropertyRequest p(*m, line, std::string("model ") + N::kName);
    normal_.connect(p);
    p.set_who(std::string("damping ") + D::kName);
    damping_.connect(p, normal_);
    p.set_who(std::string("tangential ") + T::kName);
    tangential_.connect(p);
    p.set_who(std::string("rolling_friction ") + R::kName);
    rolling_.connect(p);
    p.set_who(std::string("cohesion ") + C::kName);
    cohesion_.connect(p);
  }
  const std::vector<HistorySlot>& history_slots() const override { return slots_; }
  double contact_time(const ContactTimeInput& in) const override { return law_contact_time(normal_, damping_, in); }
  void evaluate(PairChunk<kH>& ch, double dt, bool update, Simd simd, Kinematics kin) const override {
    evaluate_columns_any(ch, dt, update, simd, kin);
  }
  void evaluate(WallChunk<kH>& ch, double dt, bool update, Simd simd, Kinematics kin) const override {
    evaluate_columns_any(ch, dt, update, simd, kin);
  }

  N normal_;
  D damping_;
  T tangential_;
  R rolling_;
  C cohesion_;

 private:
  std::vector<HistorySlot> slots_;
  std::shared_ptr<Materials> materials_;
  using Parts = ContactParts;

  // All sub-models on one contact: force on i and torques on i and j. K
  // (Contact or ContactK) may leave out z (2D) or the torques (no rotation):
  // those parts are then not computed (the scatter adds no torque).
  template <class K>
  [[gnu::always_inline]] inline Parts evaluate_one(const K& c, double* h, const StepContext& ctx) const {
    NormalForce nf = damped_normal_force(normal_, damping_, c, h, ctx);
    double fcoh = 0.0;
    if constexpr (C::kActive)
      fcoh = add_cohesion(nf, cohesion_.force(c, nf, h + kHN + kHD + kHT + kHR, ctx), cohesion_.reduces_tangential());
    const Vec3 ft = tangential_.force(c, nf, h + kHN + kHD, ctx);
    Vec3 mr{};
    if constexpr (K::kRotation) mr = rolling_.torque(c, nf, h + kHN + kHD + kHT, ctx);
    return contact_parts(c, nf.Fn + fcoh, ft, mr);
  }

  // Columns in,  force/torque columns and new history out.
  // Cols: PairChunk or WallChunk (their contact() builds the kinematics).
  // kUniform: one type pair (ch.tp0) for all, so each coefficient is one
  // loaded value, not a per-lane table lookup.
  // K: the kinematics mode (Contact: full 3D; ContactK<kD, kRot>).
  template <bool kUpdate, bool kUniform, class K = Contact, class Cols>
  [[gnu::always_inline]] inline void evaluate_columns(Cols& ch, double dt) const {
    const StepContext ctx{dt, kUpdate};
    const int n = ch.n, tp0 = ch.tp0;
#pragma GCC ivdep
    for (int m = 0; m < n; ++m) {
      K c;
      ch.contact(m, c);
      if constexpr (kUniform) c.tp = tp0;
      double h[kH > 0 ? kH : 1];
      for (int q = 0; q < kH; ++q) h[q] = ch.h[q][m];
      const Parts p = evaluate_one(c, h, ctx);
      if constexpr (kUpdate)
        for (int q = 0; q < kH; ++q) ch.h[q][m] = h[q];
      ch.template store<K::kRotation>(m, p);
    }
  }
  // The four (update, uniform) instantiations of the full kernel, chosen per
  // chunk, and the reduced modes (2D, no rotation) for the force pass (update):
  // setup and per-contact records take the full kernel, which agrees with them.
  template <class Cols>
  [[gnu::always_inline]] inline void evaluate_columns_all(Cols& ch, double dt, bool update, Kinematics kin) const {
    const bool uniform = ch.tp0 >= 0;
    if (update && kin != Kinematics::Full) {
      switch (kin) {
        case Kinematics::Plane:
          return uniform ? evaluate_columns<true, true, ContactK<2, true>>(ch, dt)
                         : evaluate_columns<true, false, ContactK<2, true>>(ch, dt);
        case Kinematics::Frozen:
          return uniform ? evaluate_columns<true, true, ContactK<3, false>>(ch, dt)
                         : evaluate_columns<true, false, ContactK<3, false>>(ch, dt);
        default:
          return uniform ? evaluate_columns<true, true, ContactK<2, false>>(ch, dt)
                         : evaluate_columns<true, false, ContactK<2, false>>(ch, dt);
      }
    }
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
  [[gnu::target("avx2"), gnu::flatten]] void evaluate_columns_avx2(Cols& ch, double dt, bool update, Kinematics kin) const {
    evaluate_columns_all(ch, dt, update, kin);
  }
  template <class Cols>
  [[gnu::target("avx512f,avx512dq"), gnu::flatten]] void evaluate_columns_avx512(Cols& ch, double dt,
                                                                                 bool update, Kinematics kin) const {
    evaluate_columns_all(ch, dt, update, kin);
  }
#endif
  template <class Cols>
  [[gnu::flatten]] void evaluate_columns_base(Cols& ch, double dt, bool update, Kinematics kin) const {
    evaluate_columns_all(ch, dt, update, kin);
  }
  template <class Cols>
  void evaluate_columns_any(Cols& ch, double dt, bool update, Simd simd, Kinematics kin) const {
#if defined(__x86_64__) && defined(__GNUC__)
    switch (simd) {
      case Simd::AVX512: return evaluate_columns_avx512(ch, dt, update, kin);
      case Simd::AVX2: return evaluate_columns_avx2(ch, dt, update, kin);
      case Simd::SSE2: break;
    }
#endif
    evaluate_columns_base(ch, dt, update, kin);
  }

};

}  // namespace sable
