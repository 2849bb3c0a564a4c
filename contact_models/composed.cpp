#include "contact_models/composed.h"

#include <algorithm>
#include <utility>

namespace sable {
namespace {

// A composed law with kH history values per contact (the contact loop is
// compiled per width, so this is too: one instance per width, not per law).
template <int kH>
class ComposedKernel final : public ContactKernel, public ColumnLaw<kH> {
 public:
  explicit ComposedKernel(ComposedParts p) : p_(std::move(p)) {
    p_.normal->history_slots(slots_);
    p_.tangential->history_slots(slots_);
    p_.rolling->history_slots(slots_);
    p_.cohesion->history_slots(slots_);
    ht_ = p_.normal->history();  // history columns follow the axes' order, as GranKernel's
    hr_ = ht_ + p_.tangential->history();
    hc_ = hr_ + p_.rolling->history();
    loop_ = make_contact_loop<kH>(*this);
  }
  std::string name() const override {
    const auto& n = p_.names;
    return "model " + n[0] + " damping " + n[1] + " tangential " + n[2] + " rolling_friction " + n[3] +
           " cohesion " + n[4];
  }
  void settings(ModelSettings& s) override {
    p_.normal->settings(s);  // and the damping model's
    p_.tangential->settings(s);
    p_.rolling->settings(s);
    p_.cohesion->settings(s);
  }
  void connect(const std::shared_ptr<Materials>& m, const Args& line) override {  // as GranKernel::connect
    materials_ = m;
    PropertyRequest p(*m, line, "model " + p_.names[0]);
    p_.normal->connect(p);
    p.set_who("tangential " + p_.names[2]);
    p_.tangential->connect(p);
    p.set_who("rolling_friction " + p_.names[3]);
    p_.rolling->connect(p);
    p.set_who("cohesion " + p_.names[4]);
    p_.cohesion->connect(p);
  }
  const std::vector<HistorySlot>& history_slots() const override { return slots_; }
  double contact_time(const ContactTimeInput& in) const override { return p_.normal->contact_time(in); }
  void evaluate(PairChunk<kH>& ch, double dt, bool update, Simd, Kinematics kin) const override {
    evaluate_chunk(ch, dt, update, kin);
  }
  void evaluate(WallChunk<kH>& ch, double dt, bool update, Simd, Kinematics kin) const override {
    evaluate_chunk(ch, dt, update, kin);
  }

 private:
  static constexpr int kW = kH > 0 ? kH : 1;  // history row stride
  ComposedParts p_;
  int ht_ = 0, hr_ = 0, hc_ = 0;  // first history column of tangential, rolling, cohesion
  std::vector<HistorySlot> slots_;
  std::shared_ptr<Materials> materials_;

  // The chunk's kinematics in mode K (the columns hold only what that mode reads).
  template <class K, class Cols>
  static void contacts_as(const Cols& ch, Contact* c) {
    for (int m = 0; m < ch.n; ++m) {
      K k;
      ch.contact(m, k);
      c[m] = k;
    }
  }
  template <class Cols>
  static void contacts(const Cols& ch, Kinematics mode, Contact* c) {
    switch (mode) {
      case Kinematics::Full: contacts_as<Contact>(ch, c); break;
      case Kinematics::Plane: contacts_as<ContactK<2, true>>(ch, c); break;
      case Kinematics::Frozen: contacts_as<ContactK<3, false>>(ch, c); break;
      case Kinematics::PlaneFrozen: contacts_as<ContactK<2, false>>(ch, c); break;
    }
    if (ch.tp0 >= 0)  // one type pair: as GranKernel's uniform loop
      for (int m = 0; m < ch.n; ++m) c[m].tp = ch.tp0;
  }

  // GranKernel::evaluate_one on every column, one axis at a time. The reduced
  // modes (2D, no rotation) are the force pass's only, as in GranKernel; they
  // give the full kernel's numbers (up to the sign of zeros, which the
  // scatter of those modes does not add).
  template <class Cols>
  void evaluate_chunk(Cols& ch, double dt, bool update, Kinematics kin) const {
    constexpr int kCap = Cols::kCap;
    const int n = ch.n;
    const StepContext ctx{dt, update};
    const Kinematics mode = update ? kin : Kinematics::Full;
    const bool rotation = mode == Kinematics::Full || mode == Kinematics::Plane;
    Contact c[kCap];
    contacts(ch, mode, c);
    double h[kCap * kW];
    for (int m = 0; m < n; ++m)
      for (int q = 0; q < kH; ++q) h[m * kW + q] = ch.h[q][m];
    NormalForce nf[kCap];
    double fcoh[kCap];
    Vec3 ft[kCap], mr[kCap];
    p_.normal->forces(c, n, h, kW, ctx, nf);
    if (p_.cohesion->active())
      p_.cohesion->forces(c, nf, n, h + hc_, kW, ctx, fcoh);
    else
      std::fill(fcoh, fcoh + n, 0.0);
    p_.tangential->forces(c, nf, n, h + ht_, kW, ctx, ft);
    if (rotation) p_.rolling->torques(c, nf, n, h + hr_, kW, ctx, mr);
    for (int m = 0; m < n; ++m) {
      if (update)
        for (int q = 0; q < kH; ++q) ch.h[q][m] = h[m * kW + q];
      const ContactParts parts = contact_parts(c[m], nf[m].Fn + fcoh[m], ft[m], rotation ? mr[m] : Vec3{});
      if (rotation)
        ch.template store<true>(m, parts);
      else
        ch.template store<false>(m, parts);
    }
  }
};

template <int... kHs>
std::unique_ptr<ContactKernel> of_width(ComposedParts& p, std::integer_sequence<int, kHs...>) {
  const int h = p.history();
  std::unique_ptr<ContactKernel> k;
  ((h == kHs ? (k = std::make_unique<ComposedKernel<kHs>>(std::move(p)), 0) : 0), ...);
  return k;
}

}  // namespace

std::unique_ptr<ContactKernel> make_composed_kernel(ComposedParts parts) {
  return of_width(parts, std::make_integer_sequence<int, kMaxLoopHistory + 1>{});
}

}  // namespace sable
