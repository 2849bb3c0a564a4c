// compute ID group unbalanced/force (sable addition; LIGGGHTS has no such style)
// YADE's utils.unbalancedForce(): the mean over grains of |net force| divided
// by the mean over contacts of |contact force|; 0 in static equilibrium.
//   grains    those of the group, less the grains of fix freeze (YADE skips
//             non-dynamic bodies; give the group of the free grains); a rigid
//             body (fix rigid) with a grain in the group counts once, with its
//             summed force, as YADE counts a clump, and its members' contacts
//             with each other are not counted
//   net force the force the step applied to the grain: contacts, gravity and
//             every other fix's force (YADE adds the integrator's gravity),
//             without what fix damping/cundall added (YADE's forces are read
//             before its integrator damps them)
//   contacts  every grain-grain contact with at least one grain in the group
//             and every wall/gran contact (primitive or mesh) of a group grain;
//             |normal + tangential force| with the contact's own dashpot, as
//             compute pair/gran/local reports it: re-evaluated at the state
//             when the compute is invoked (velocities of the full step)
// Global scalar c_ID = the ratio; c_ID[1..4] = the ratio, max |net force| /
// mean |contact force| (unbalancedForce(useMaxForce=True)), mean |net force|,
// mean |contact force|. No contact: +inf (NaN with no net force either).
// Evaluated only when asked: the force pass does nothing for it, except that a
// fix damping/cundall keeps what it added (3 doubles per grain per step).
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "contact_models/pair_gran.h"  // frozen_groupbits
#include "core/engine/contact_source.h"
#include "core/engine/rigid_bodies.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "fixes/fix_damping_cundall.h"

namespace sable {

class ComputeUnbalancedForce : public Compute {
 public:
  ComputeUnbalancedForce(Simulation& s, const Args& a) : Compute(s, a) {
    scalar_flag = true;
    vector_size = 4;
    if (a.size() > 4) a.fail(4, "nothing after 'unbalanced/force'");
  }
  void init() override {
    for (auto& f : sim.fixes)
      if (auto* d = dynamic_cast<FixDampingCundall*>(f.get())) d->keep_added();
  }
  double compute_scalar() override {
    evaluate();
    return out_[0];
  }
  double compute_vector(int i) override {
    evaluate();
    return out_[i - 1];
  }

 private:
  double out_[4] = {0, 0, 0, 0};
  long out_step_ = -2;
  ContactRecords rec_;

  void evaluate() {
    if (out_step_ == sim.step && invoked_step == sim.step) return;
    invoked_step = out_step_ = sim.step;
    init();  // fixes may have been added since; a new damping fix keeps from its next pass
    double fsum = 0, fmax = 0, csum = 0, nc = 0;
    long ng = 0;
    net_forces(fsum, fmax, ng);
    contact_forces(csum, nc);
    if (sim.comm.distributed) {  // every rank's grains and contacts
      double t[4] = {fsum, static_cast<double>(ng), csum, nc};
      sim.comm.total(t, 4);
      fsum = t[0], ng = static_cast<long>(t[1]), csum = t[2], nc = t[3];
      fmax = sim.comm.highest(fmax);
    }
    const double fmean = ng ? fsum / ng : 0.0, cmean = nc > 0 ? csum / nc : 0.0;
    const double none = fmax > 0 ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
    out_[0] = nc > 0 ? fmean / cmean : none;
    out_[1] = nc > 0 ? fmax / cmean : none;
    out_[2] = fmean;
    out_[3] = cmean;
  }

  // |f - what damping added| over the group's free grains, in atom order.
  void net_forces(double& sum, double& max, long& n) const {
    const Atoms& at = sim.atoms;
    std::vector<const FixDampingCundall*> damp;
    for (auto& f : sim.fixes)
      if (auto* d = dynamic_cast<const FixDampingCundall*>(f.get())) damp.push_back(d);
    const std::uint32_t frozen = frozen_groupbits(sim);
    std::set<std::pair<const RigidBodies*, int>> bodies_seen;
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit) || (at.mask[i] & frozen)) continue;
      double f[3] = {at.f[3 * i], at.f[3 * i + 1], at.f[3 * i + 2]};
      if (const auto [rb, b] = sim.body_of(i); rb) {
        if (!bodies_seen.insert({rb, b}).second) continue;
        std::copy(rb->body_force(b), rb->body_force(b) + 3, f);
      }
      for (const FixDampingCundall* d : damp)
        if (const double* add = d->added(at.n, sim.step); add && (at.mask[i] & d->groupbit))
          for (int k = 0; k < 3; ++k) f[k] -= add[3 * i + k];
      const double m = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
      sum += m;
      max = std::max(max, m);
      ++n;
    }
  }

  // Several ranks: a pair with a ghost grain is counted by both ranks, half each.
  void contact_forces(double& sum, double& n) {
    const Atoms& at = sim.atoms;
    auto add = [&](bool pair) {
      for (const ContactRecord& c : rec_.rows) {
        if (pair && !((at.mask[c.i] | at.mask[c.j]) & groupbit)) continue;
        if (pair && sim.body_of(c.i).first && sim.body_of(c.i) == sim.body_of(c.j)) continue;  // inside one body
        const double w = pair && static_cast<std::size_t>(c.j) >= at.n ? 0.5 : 1.0;
        sum += w * std::sqrt(c.f[0] * c.f[0] + c.f[1] * c.f[1] + c.f[2] * c.f[2]);
        n += w;
      }
    };
    for (ContactSource* s : contact_sources(sim)) {
      const bool pair = s->contact_kind() == ContactSource::Kind::Pairs;
      s->records(pair ? sim.groups.bit(0) : groupbit, rec_);  // pairs: every contact; the group test is "either grain"
      add(pair);
    }
  }
};

SABLE_COMPUTE("unbalanced/force", ComputeUnbalancedForce);

}  // namespace sable
