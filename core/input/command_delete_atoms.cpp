// delete_atoms group G | region R | porosity R FRACTION SEED   [compress yes|no] [mol no]
// LIGGGHTS 3.8 semantics. compress yes (the default, as in LIGGGHTS) renumbers
// the remaining atoms 1..N (in the order of their old IDs); with compress no the
// IDs are kept and new atoms continue after the largest remaining ID.
// porosity deletes each atom in R with probability FRACTION, drawn from (SEED, atom ID).
#include <algorithm>
#include <numeric>

#include "core/engine/error.h"
#include "core/engine/contact_source.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/engine/random.h"

namespace sable {
namespace {

void cmd_delete_atoms(Simulation& sim, const Args& a) {
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before delete_atoms)");
  Atoms& at = sim.atoms;
  const std::string& style = a.word(1, "group, region or porosity");
  std::vector<char> doomed(at.n, 0);
  std::size_t opt = 3;
  if (style == "group") {
    const int g = sim.groups.existing(a, 2);
    for (std::size_t i = 0; i < at.n; ++i) doomed[i] = (at.mask[i] & sim.groups.bit(g)) != 0;
  } else if (style == "region" || style == "porosity") {
    const Region* r = sim.find_region(a.word(2, "a region ID"));
    if (!r) a.fail(2, "an existing region ID (define it with 'region' first)");
    double frac = 1;
    long seed = 0;
    if (style == "porosity") {
      frac = a.num(3, "the fraction of atoms to delete");
      if (frac < 0 || frac > 1) a.fail(3, "a fraction between 0 and 1");
      seed = a.integer(4, "a random seed > 0");
      if (seed <= 0) a.fail(4, "a random seed > 0");
      opt = 5;
    }
    for (std::size_t i = 0; i < at.n; ++i)
      doomed[i] = r->match(&at.x[3 * i]) && (style == "region" || hashed_uniform(seed, at.id[i]) <= frac);
  } else if (style == "overlap") {
    a.fail(1, "group, region or porosity ('overlap' is not supported)");
  } else {
    a.fail(1, "group, region or porosity");
  }
  bool compress = true;
  for (std::size_t i = opt; i < a.size(); i += 2) {
    if (a[i] == "compress")
      compress = a.yes_no(i + 1, "yes or no");
    else if (a[i] == "mol") {
      if (a.yes_no(i + 1, "yes or no")) a.fail(i + 1, "'no' (atom_style granular has no molecules)");
    } else
      a.fail(i, "compress or mol");
  }

  const std::size_t before = at.n;
  at.remove_if(doomed);
  for (auto& c : sim.computes) c->reset_cache();  // values cached at this step counted the deleted grains
  if (compress) {
    std::vector<std::size_t> by_id(at.n);
    std::iota(by_id.begin(), by_id.end(), 0);
    std::sort(by_id.begin(), by_id.end(), [&](std::size_t p, std::size_t q) { return at.id[p] < at.id[q]; });
    // Several ranks: the surviving ids of all ranks, so that every rank renumbers its
    // grains and the history it keeps of grains on other ranks alike.
    std::vector<long> old_ids(by_id.size()), new_ids;
    for (std::size_t k = 0; k < by_id.size(); ++k) old_ids[k] = at.id[by_id[k]];
    if (sim.comm.distributed) {
      std::vector<double> mine(old_ids.begin(), old_ids.end()), all;
      sim.comm.all_gather(mine, all);
      old_ids.assign(all.begin(), all.end());
      std::sort(old_ids.begin(), old_ids.end());
    }
    new_ids.resize(old_ids.size());
    std::iota(new_ids.begin(), new_ids.end(), 1L);
    for (std::size_t i : by_id)
      at.id[i] = 1 + (std::lower_bound(old_ids.begin(), old_ids.end(), at.id[i]) - old_ids.begin());
    for (ContactSource* c : contact_sources(sim)) c->ids_renumbered(old_ids, new_ids);
    sim.neighbor.ids_renumbered(old_ids, new_ids);  // the list's grains, whose pair history the next rebuild carries
    sim.restart.contacts.renumber(old_ids, new_ids);  // read_restart's contacts not yet handed to the pair
    at.permute(by_id);  // also refreshes the ID -> index map; atoms now in ID order
  }
  // LIGGGHTS gives new atoms max(existing ID) + 1, so a deleted top ID is reused.
  at.max_id = 0;
  for (std::size_t i = 0; i < at.n; ++i) at.max_id = std::max(at.max_id, at.id[i]);
  at.max_id = static_cast<long>(sim.comm.highest(static_cast<double>(at.max_id)));  // several ranks: all grains'
  const long deleted = sim.comm.total(static_cast<long>(before - at.n)), total = sim.comm.total(static_cast<long>(at.n));
  sim.print("Deleted " + std::to_string(deleted) + " atoms, new total = " + std::to_string(total));
}

}  // namespace

SABLE_COMMAND("delete_atoms", cmd_delete_atoms);

}  // namespace sable
