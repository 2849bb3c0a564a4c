// compute ID group wall/gran/local [pos vel id force force_normal force_tangential
//                                   torque history contactArea delta]
// One row per grain-wall contact of every fix wall/gran (LIGGGHTS supports
// only mesh walls here; sable also reports primitive walls). Columns as
// pair/gran/local with side 1 = the wall: pos = wall point then grain centre,
// vel = wall velocity then grain velocity, id = (wall index among the
// wall/gran fixes, 0, grain id); mesh walls (listed after the primitive ones)
// give (wall index, triangle index, grain id). Values are re-evaluated at invocation time,
// history read but not advanced.
#include <cmath>
#include <numbers>

#include "contact_models/gran_local.h"
#include "core/engine/contact_source.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

class ComputeWallGranLocal : public Compute {
 public:
  ComputeWallGranLocal(Simulation& s, const Args& a) : Compute(s, a) {
    local_flag = true;
    cols_.parse(a, 4);
    init();
  }
  void init() override {
    walls_.clear();  // primitive walls, then mesh walls, each in the deck's order
    for (auto kind : {ContactSource::Kind::Wall, ContactSource::Kind::Mesh})
      for (ContactSource* w : contact_sources(sim))
        if (w->contact_kind() == kind) walls_.push_back(w);
    if (walls_.empty()) args.fail_line("compute wall/gran/local needs a fix wall/gran defined before it");
    // Columns follow the first wall's model; walls with a different history size fill with zeros / are cut.
    const auto& slots = walls_[0]->history_slots();
    if (cols_.history_explicit && slots.empty())
      args.fail_line("'history' asked, but " + walls_[0]->law_name() + " keeps no contact history");
    if (slots.empty()) cols_.history = false;
    nh_ = static_cast<int>(slots.size());
    local_names = cols_.names(slots);
    local_cols = static_cast<int>(local_names.size());
  }
  void compute_local() override {
    init();  // walls may have been added or removed since
    local.clear();
    const Atoms& at = sim.atoms;
    std::vector<double> h(nh_);
    for (std::size_t w = 0; w < walls_.size(); ++w) {
      ContactSource& wall = *walls_[w];
      wall.records(groupbit, rec_);
      for (std::size_t r = 0; r < rec_.rows.size(); ++r) {
        const ContactRecord& c = rec_.rows[r];
        for (int m = 0; m < nh_; ++m) h[m] = m < rec_.hist_size ? rec_.hist[r * rec_.hist_size + m] : 0.0;
        const double ids[3] = {static_cast<double>(w), static_cast<double>(wall.element(c.shift)),
                               static_cast<double>(at.id[c.i])};
        const double ri = at.radius[c.i], d = ri - c.delta;
        const double area = std::numbers::pi * (ri * ri - d * d);  // sphere-plane intersection
        cols_.row(local, wall.wall_point(c.shift), &at.x[3 * c.i], wall.wall_velocity(c.shift), &at.v[3 * c.i], ids,
                  c.f, c.t, c.en, h.data(), nh_, area, c.delta);
      }
    }
  }

 private:
  GranLocalColumns cols_;
  std::vector<ContactSource*> walls_;
  ContactRecords rec_;
  int nh_ = 0;
};

SABLE_COMPUTE("wall/gran/local", ComputeWallGranLocal);

}  // namespace sable
