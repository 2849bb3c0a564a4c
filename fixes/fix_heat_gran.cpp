// fix ID group heat/gran initial_temperature T0 [contact_area overlap|projection|constant A]
//     [area_correction no] [store_contact_data no]
// fix ID group heat/gran/conduction ... (the same fix, LIGGGHTS 3.8's two names)
//
// Grain temperatures with conduction through grain-grain contacts, as
// LIGGGHTS 3.8 (fix heat/gran/conduction + the transportequation/scalar it
// creates): per-atom Temp (T0 for every grain without one, inserted grains
// too), heatFlux (the conducted heat flow into the grain this step) and
// heatSource (set by `set ... property/atom heatSource Q`); each step
//   T += (heatFlux + heatSource) dt / (m c)      (grains of the group, |c| > 1e-5)
// with c the thermalCapacity of the grain's type; the flow of each contact is
// contact_models/heat_conduction.h (thermalConductivity per type). f_ID is
// the total thermal energy sum c m T over all grains; f_Temp, f_heatFlux,
// f_heatSource are per-atom values for dumps and compute reduce.
//
// LIGGGHTS computes the flows after the force pass and updates T in
// final_integrate; neither reads or changes what the other passes use, so
// sable does both before the force pass (pre_force, positions already those of
// the step): the same numbers, and the integrator's passes stay fused.
// heatFlux is zeroed for every grain each step (LIGGGHTS: for the group's).
// Not here: LIGGGHTS' directionalHeatFlux, heat through walls (wall/gran `temperature`).
#include <cmath>
#include <string>
#include <vector>

#include "contact_models/heat_conduction.h"
#include "contact_models/materials.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

constexpr double kSmallCapacity = 1e-5;  // LIGGGHTS' SMALL: a grain of no capacity keeps its temperature

class FixHeatGran : public Fix {
 public:
  FixHeatGran(Simulation& s, const Args& a) : Fix(s, a) {
    if (a.word(4, "initial_temperature") != "initial_temperature") a.fail(4, "initial_temperature (obligatory)");
    t0_ = a.num(5, "the initial temperature T0");
    for (std::size_t i = 6; i < a.size(); i += 2) {
      const std::string& k = a[i];
      if (k == "contact_area") {
        const std::string& m = a.word(i + 1, "overlap, projection or constant");
        if (m == "overlap") law_.area_mode = HeatConduction::Area::Overlap;
        else if (m == "projection") law_.area_mode = HeatConduction::Area::Projection;
        else if (m == "constant") {
          law_.area_mode = HeatConduction::Area::Constant;
          law_.constant_area = a.num(i + 2, "the contact area (> 0)");
          if (!(law_.constant_area > 0)) a.fail(i + 2, "a contact area > 0");
          ++i;
        } else {
          a.fail(i + 1, "overlap, projection or constant");
        }
      } else if (k == "area_correction" || k == "store_contact_data") {
        if (a.yes_no(i + 1, "yes or no"))
          a.fail(i + 1, "no (sable does not implement " + k + " yes)");
      } else {
        a.fail(i, "a heat/gran keyword: contact_area, area_correction, store_contact_data");
      }
    }
    // Per-atom values as Atoms columns named f_<name>: dumps and compute reduce
    // read them as f_Temp etc. Columns that exist already (restart, an earlier
    // fix property/atom of that name) keep their values.
    Atoms& at = s.atoms;
    temp_col_ = at.add_column("f_Temp", 1, t0_);
    flux_col_ = at.add_column("f_heatFlux", 1, 0.0);
    source_col_ = at.add_column("f_heatSource", 1, 0.0);
    hooks = PRE_FORCE;
    scalar_flag = 1;
  }

  void init() override {
    int mine = 0;
    for (auto& f : sim.fixes) mine += dynamic_cast<FixHeatGran*>(f.get()) != nullptr;
    if (mine > 1) args.fail_line("only one fix heat/gran or heat/gran/conduction is allowed (as in LIGGGHTS)");
    if (!sim.pair) args.fail_line("fix " + style + " needs a granular pair style (pair_style gran ...) first");
    if (sim.atoms.pair_exclusion >= 0)
      args.fail_line("fix " + style + " may not be used with clumps or rigid bodies (as in LIGGGHTS)");
    load_tables();
  }

  // Conductivity and capacity per type from fix property/global (errors name this fix's line).
  void load_tables() {
    auto mats = Materials::of(sim);
    const std::string who = "fix " + style;
    const double* k = mats->type_vector("thermalConductivity", who, args);
    const double* c = mats->type_vector("thermalCapacity", who, args);
    conductivity_.assign(k, k + mats->stride());
    capacity_.assign(c, c + mats->stride());
    for (int t = 1; t < mats->stride(); ++t)
      if (conductivity_[t] < 0)
        args.fail_line("thermalConductivity of type " + std::to_string(t) + " is negative (it must be >= 0)");
  }

  void pre_force() override {
    conduct();
    integrate();
  }

  // heatFlux = the heat conducted into each grain this step.
  void conduct() {
    Atoms& at = sim.atoms;
    std::vector<double>& flux = at.column(flux_col_);
    std::fill(flux.begin(), flux.end(), 0.0);
    const NeighborList& list = sim.neighbor.list;
    // Grains inserted since the last build have no list entries yet (as in the force pass).
    if (!list.first.empty() && list.first.size() - 1 <= at.n)
      law_.flows(at, list, sim.neighbor.builds, at.column(temp_col_).data(), conductivity_.data(), groupbit, flux);
  }

  // T += (heatFlux + heatSource) dt / (m c) for the group's grains (LIGGGHTS' transport equation).
  void integrate() {
    Atoms& at = sim.atoms;
    std::vector<double>& temp = at.column(temp_col_);
    const std::vector<double>& flux = at.column(flux_col_);
    const std::vector<double>& source = at.column(source_col_);
    for (std::size_t i = 0; i < at.n; ++i) {
      const double c = capacity_[at.type[i]];
      if ((at.mask[i] & groupbit) && std::fabs(c) > kSmallCapacity)
        temp[i] += (flux[i] + source[i]) * sim.dt / (at.rmass[i] * c);
    }
  }

  double compute_scalar() override {
    const Atoms& at = sim.atoms;
    if (capacity_.empty()) load_tables();  // asked before the first run
    const std::vector<double>& temp = at.column(temp_col_);
    double sum = 0.0;
    for (std::size_t i = 0; i < at.n; ++i) sum += capacity_[at.type[i]] * at.rmass[i] * temp[i];
    return sum;
  }

 private:
  double t0_ = 0;
  int temp_col_ = -1, flux_col_ = -1, source_col_ = -1;
  HeatConduction law_;
  std::vector<double> conductivity_, capacity_;  // by atom type (index 0 unused)
};

}  // namespace

SABLE_FIX("heat/gran", FixHeatGran);
SABLE_FIX("heat/gran/conduction", FixHeatGran);

}  // namespace sable
