// compute ID group pair/gran/local [pos vel id force force_normal force_tangential
//                                   torque history contactArea delta]
// One row per touching pair with both grains in the group (LIGGGHTS
// compute_pair_gran_local.txt). As in LIGGGHTS, the values are re-evaluated by
// the pair's contact kernel at the time the compute is invoked (usually output
// time), with history read but not advanced; the force loop itself never
// produces records, so a run without this compute pays nothing for it.
#include <cmath>
#include <numbers>

#include "contact_models/gran_local.h"
#include "core/engine/contact_source.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

class ComputePairGranLocal : public Compute {
 public:
  ComputePairGranLocal(Simulation& s, const Args& a) : Compute(s, a) {
    local_flag = true;
    cols_.parse(a, 4);
    init();
  }
  void init() override {
    pair_ = pair_contacts(sim);
    if (!pair_) args.fail_line("compute pair/gran/local needs 'pair_style gran' defined before it");
    const auto& slots = pair_->history_slots();
    if (cols_.history_explicit && slots.empty())
      args.fail_line("'history' asked, but " + pair_->law_name() + " keeps no contact history");
    if (slots.empty()) cols_.history = false;
    local_names = cols_.names(slots);
    local_cols = static_cast<int>(local_names.size());
  }
  void compute_local() override {
    pair_->records(groupbit, rec_);
    local.clear();
    const Atoms& at = sim.atoms;
    for (std::size_t r = 0; r < rec_.rows.size(); ++r) {
      const ContactRecord& c = rec_.rows[r];
      double xi[3], xj[3];
      int img[3] = {0, 0, 0};
      for (int k = 0; k < 3; ++k) {
        xi[k] = at.x[3 * c.i + k];
        xj[k] = at.x[3 * c.j + k];
      }
      sim.domain.remap(xi, img);  // LIGGGHTS writes positions wrapped into the box
      sim.domain.remap(xj, img);
      const double ids[3] = {static_cast<double>(at.id[c.i]), static_cast<double>(at.id[c.j]),
                             c.shift != NeighborList::kNoShift ? 1.0 : 0.0};
      const double ri = at.radius[c.i], rj = at.radius[c.j], d = ri + rj - c.delta;
      // Sphere-sphere intersection area (LIGGGHTS' contactArea formula).
      const double area =
          -std::numbers::pi / 4 * ((d - ri - rj) * (d + ri - rj) * (d - ri + rj) * (d + ri + rj)) / (d * d);
      cols_.row(local, xi, xj, &at.v[3 * c.i], &at.v[3 * c.j], ids, c.f, c.t, c.en,
                rec_.hist.data() + r * rec_.hist_size, rec_.hist_size, area, c.delta);
    }
  }

 private:
  GranLocalColumns cols_;
  ContactSource* pair_ = nullptr;
  ContactRecords rec_;
};

SABLE_COMPUTE("pair/gran/local", ComputePairGranLocal);

}  // namespace sable
