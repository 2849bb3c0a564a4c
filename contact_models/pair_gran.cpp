#include "contact_models/pair_gran.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "contact_models/materials.h"
#include "contact_models/registry.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

std::uint32_t frozen_groupbits(const Simulation& sim) {
  std::uint32_t bits = 0;
  for (auto& f : sim.fixes)
    if (f->traits.freezes_group) bits |= f->groupbit;
  return bits;
}

PairGran::PairGran(Simulation& s, const Args& a) : Pair(s, a) {
  const ModelSelection sel = parse_model_selection(a, 2);
  kernel_ = make_kernel(sel, a, s);
  ModelSettings settings;
  kernel_->settings(settings);
  settings.on_off("historyResetAtRebuild", keep_history_until_rebuild_);  // sable addition, see pair_gran.h
  settings.parse(a, sel.next);
  if (!kernel_->history_slots().empty()) store_.configure(kernel_->history_slots());
}

void PairGran::coeff(const Args& a) {
  const int nt = sim.atoms.ntypes;
  for (std::size_t k = 1; k <= 2; ++k) {
    const std::string& w = a.word(k, "an atom type or *");
    if (w == "*") continue;
    const long t = a.integer(k, "an atom type or *");
    if (t < 1 || t > nt) a.fail(k, "an atom type between 1 and " + std::to_string(nt));
  }
  if (a.size() > 3) a.fail(3, "nothing more (pair gran takes its coefficients from fix property/global)");
  coeff_set_ = true;
}

void PairGran::init() {
  if (!coeff_set_) args.fail_line("pair_coeff * * is missing after this pair_style (LIGGGHTS requires it too)");
  auto mats = Materials::of(sim);
  kernel_->connect(mats, args);
  connected_ = true;
  freeze_bit_ = frozen_groupbits(sim);
  // Rayleigh time needs Y and nu per type; stiffness models may not define them (see rayleigh_time).
  shear_modulus_.clear();
  poisson_.clear();
  if (mats->has("youngsModulus") && mats->has("poissonsRatio")) {
    const double* Y = mats->type_vector("youngsModulus", "the Rayleigh time", args);
    const double* nu = mats->type_vector("poissonsRatio", "the Rayleigh time", args);
    for (int t = 0; t <= mats->ntypes(); ++t) {
      shear_modulus_.push_back(t ? Y[t] / (2.0 * (1.0 + nu[t])) : 0.0);
      poisson_.push_back(t ? nu[t] : 0.0);
    }
  }
  setup_pass_ = true;
}

PairBatch PairGran::batch() {
  Atoms& at = sim.atoms;
  const NeighborList& list = sim.neighbor.list;
  PairBatch b;
  // Atoms inserted since the last build have no list entries yet: the list covers its first n atoms.
  b.a = atom_view(at, list.first.empty() ? 0 : list.first.size() - 1, freeze_bit_);
  b.first = list.first.data();
  b.jlist = list.j.data();
  b.span = list.span;
  b.shift = list.shift.data();
  b.shift_vec = list.shift_vec;
  b.list_version = sim.neighbor.builds;
  b.split = &at.split;
  if (history()) {
    b.store = &store_;
    b.row = store_.row.data();
    b.hist = store_.rows();
  }
  b.ctx.dt = sim.dt;
  return b;
}

// The list must describe the current atoms (deletions and sorting rebuild it).
static bool list_usable(const Simulation& sim) {
  const auto& first = sim.neighbor.list.first;
  return !first.empty() && first.size() - 1 <= sim.atoms.n;
}

void PairGran::compute_then(const RangeTail& tail) {
  if (!list_usable(sim)) {
    if (tail) sim.atoms.for_ranges(tail);
    return;
  }
  if (history()) store_.make_room();  // before batch(): it may move the rows
  PairBatch b = batch();
  b.ctx.update = !setup_pass_;
  setup_pass_ = false;
  b.keep_until_rebuild = keep_history_until_rebuild_;
  b.rebuilt = sim.neighbor.builds != last_builds_;
  last_builds_ = sim.neighbor.builds;
  b.tail = tail ? &tail : nullptr;
  kernel_->pair_forces(b);
}

void PairGran::records(std::uint32_t groupbit, ContactRecords& out) {
  out.clear();
  if (!list_usable(sim)) return;
  PairBatch b = batch();
  b.ctx.update = false;
  b.groupbit = groupbit;
  kernel_->pair_records(b, out);
}

double PairGran::contact_time(std::size_t i, std::size_t j, double v) const {
  if (!connected_) return std::numeric_limits<double>::infinity();  // before the first run: no coefficients yet
  const Atoms& at = sim.atoms;
  const double ri = at.radius[i], rj = at.radius[j], mi = at.rmass[i], mj = at.rmass[j];
  return kernel_->contact_time({mi * mj / (mi + mj), ri * rj / (ri + rj), v, at.type[i] * (at.ntypes + 1) + at.type[j]});
}

// Rayleigh time pi r sqrt(rho/G) / (0.1631 nu + 0.8766), G = Y / (2 (1 + nu)) of the grain's type,
// rho the volume density of the grain's sphere.
// Stiffness models (kn, kt given directly) may define no youngsModulus/poissonsRatio: then
// there is no elastic wave speed to speak of and we return +infinity, so the check rests
// on the contact time (pi sqrt(m*/kn) for hooke/stiffness), which is the relevant bound there.
double PairGran::rayleigh_time(std::size_t i) const {
  if (shear_modulus_.empty()) return std::numeric_limits<double>::infinity();
  const Atoms& at = sim.atoms;
  const int t = at.type[i];
  const double r = at.radius[i];
  // In 2D `density` is per area (m = pi r^2 rho): take the volume density from the mass. 3D keeps
  // `density` bit for bit (m / (4/3 pi r^3) may differ from it in the last bit).
  const double rho =
      sim.domain.dimension == 2 ? at.rmass[i] / (4.0 / 3.0 * std::numbers::pi * r * r * r) : at.density[i];
  return std::numbers::pi * r * std::sqrt(rho / shear_modulus_[t]) / (0.1631 * poisson_[t] + 0.8766);
}

std::string PairGran::describe() const {
  std::string s = "pair_style gran " + kernel_->name();
  const auto& slots = kernel_->history_slots();
  if (slots.empty()) return s + " (no contact history)";
  s += " (" + std::to_string(slots.size()) + " history values per contact:";
  for (auto& h : slots) s += " " + h.name;
  return s + ")";
}

SABLE_PAIR("gran", PairGran);

}  // namespace sable
