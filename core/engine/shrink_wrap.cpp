// Shrink-wrapped box faces; see core/engine/shrink_wrap.h.
#include "core/engine/shrink_wrap.h"

#include <algorithm>
#include <limits>
#include <map>
#include <mutex>

#include "core/engine/simulation.h"

namespace sable {
namespace {

struct Wrap {
  FaceStyle face[3][2] = {{FaceStyle::Fixed, FaceStyle::Fixed},
                          {FaceStyle::Fixed, FaceStyle::Fixed},
                          {FaceStyle::Fixed, FaceStyle::Fixed}};
  bool have_box = false;
  double lo[3], hi[3], small[3];  // the box at the first wrap (m's bounds) and LAMMPS' margin
};

std::mutex table_mutex;  // tests run Simulations side by side
std::map<const Simulation*, Wrap>& table() {
  static std::map<const Simulation*, Wrap> t;
  return t;
}

}  // namespace

void set_face_style(const Simulation& sim, int axis, int side, FaceStyle s) {
  std::lock_guard lock(table_mutex);
  table()[&sim].face[axis][side] = s;
}

void forget_face_styles(const Simulation& sim) {
  std::lock_guard lock(table_mutex);
  table().erase(&sim);
}

void shrink_wrap(Simulation& sim) {
  Wrap* w;
  {
    std::lock_guard lock(table_mutex);
    const auto it = table().find(&sim);
    if (it == table().end()) return;
    w = &it->second;
  }
  Domain& d = sim.domain;
  if (!w->have_box) {
    for (int k = 0; k < 3; ++k) w->lo[k] = d.lo[k], w->hi[k] = d.hi[k], w->small[k] = 1e-4 * d.length(k);
    w->have_box = true;
  }
  const Atoms& a = sim.atoms;
  if (sim.comm.total(static_cast<long>(a.n)) == 0) return;  // several ranks: all grains' extent
  for (int k = 0; k < 3; ++k) {
    if (d.periodic[k] || (w->face[k][0] == FaceStyle::Fixed && w->face[k][1] == FaceStyle::Fixed)) continue;
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (std::size_t i = 0; i < a.n; ++i) lo = std::min(lo, a.x[3 * i + k]), hi = std::max(hi, a.x[3 * i + k]);
    lo = sim.comm.lowest(lo), hi = sim.comm.highest(hi);
    if (w->face[k][0] == FaceStyle::Shrink) d.lo[k] = lo - w->small[k];
    if (w->face[k][0] == FaceStyle::ShrinkMin) d.lo[k] = std::min(lo - w->small[k], w->lo[k]);
    if (w->face[k][1] == FaceStyle::Shrink) d.hi[k] = hi + w->small[k];
    if (w->face[k][1] == FaceStyle::ShrinkMin) d.hi[k] = std::max(hi + w->small[k], w->hi[k]);
  }
  if (sim.comm.decomposed()) sim.comm.split(d);  // the subdomains follow the box
}

}  // namespace sable
