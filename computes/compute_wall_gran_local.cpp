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
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "fixes/fix_wall_gran.h"
#include "fixes/fix_wall_gran_mesh.h"

namespace sable {

class ComputeWallGranLocal : public Compute {
 public:
  ComputeWallGranLocal(Simulation& s, const Args& a) : Compute(s, a) {
    local_flag = true;
    cols_.parse(a, 4);
    init();
  }
  void init() override {
    walls_.clear();
    meshes_.clear();
    for (auto& f : sim.fixes) {
      if (auto* w = dynamic_cast<FixWallGran*>(f.get())) walls_.push_back(w);
      if (auto* w = dynamic_cast<FixWallGranMesh*>(f.get())) meshes_.push_back(w);
    }
    if (walls_.empty() && meshes_.empty()) args.fail_line("compute wall/gran/local needs a fix wall/gran defined before it");
    // Columns follow the first wall's model; walls with a different history size fill with zeros / are cut.
    ContactKernel& first = walls_.empty() ? meshes_[0]->kernel() : walls_[0]->kernel();
    const auto& slots = first.history_slots();
    if (cols_.history_explicit && slots.empty())
      args.fail_line("'history' asked, but " + first.name() + " keeps no contact history");
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
    auto rows = [&](auto* wall, std::size_t w, auto second_id) {
      wall->records(groupbit, rec_);
      for (std::size_t r = 0; r < rec_.rows.size(); ++r) {
        const ContactRecord& c = rec_.rows[r];
        for (int m = 0; m < nh_; ++m) h[m] = m < rec_.hist_size ? rec_.hist[r * rec_.hist_size + m] : 0.0;
        const double ids[3] = {static_cast<double>(w), second_id(c.shift), static_cast<double>(at.id[c.i])};
        const double ri = at.radius[c.i], d = ri - c.delta;
        const double area = std::numbers::pi * (ri * ri - d * d);  // sphere-plane intersection
        cols_.row(local, wall->point(c.shift), &at.x[3 * c.i], wall->vwall(c.shift), &at.v[3 * c.i], ids, c.f, c.t,
                  c.en, h.data(), nh_, area, c.delta);
      }
    };
    for (std::size_t w = 0; w < walls_.size(); ++w) rows(walls_[w], w, [](int) { return 0.0; });
    for (std::size_t w = 0; w < meshes_.size(); ++w)
      rows(meshes_[w], walls_.size() + w, [&](int k) { return static_cast<double>(meshes_[w]->triangle(k)); });
  }

 private:
  GranLocalColumns cols_;
  std::vector<FixWallGran*> walls_;
  std::vector<FixWallGranMesh*> meshes_;
  ContactRecords rec_;
  int nh_ = 0;
};

SABLE_COMPUTE("wall/gran/local", ComputeWallGranLocal);

}  // namespace sable
