// balance thresh shift dimstr Niter stopthresh (LAMMPS): when the imbalance factor (the most
// grains a rank would own over the mean) exceeds thresh, the processor grid's inner cuts
// along the axes of dimstr move to where each slab holds as many grains (one pass over a
// histogram of all ranks' grains; Niter and stopthresh are read, LAMMPS iterates), no slab
// thinner than the ghost cutoff. The next run moves the grains (its set-up's exchange).
// Styles x and rcb (Zoltan) are not done yet; on one rank it only reports the factor 1.
#include <algorithm>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

// Grains each rank owns, or would own, at the current cuts: every rank alike.
std::vector<double> grains_per_rank(const Simulation& sim) {
  std::vector<double> c(static_cast<std::size_t>(sim.comm.size()), 0.0);
  for (std::size_t i = 0; i < sim.atoms.n; ++i) c[static_cast<std::size_t>(sim.comm.owner_of(&sim.atoms.x[3 * i], sim.domain))] += 1;
  sim.comm.total(c.data(), static_cast<int>(c.size()));
  return c;
}

double factor(const std::vector<double>& c) {
  const double sum = std::accumulate(c.begin(), c.end(), 0.0);
  return sum > 0 ? *std::max_element(c.begin(), c.end()) / (sum / static_cast<double>(c.size())) : 1.0;
}

void cmd_balance(Simulation& sim, const Args& a) {
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before balance)");
  const double thresh = a.num(1, "the imbalance threshold (>= 1)");
  if (!(thresh >= 1)) a.fail(1, "an imbalance threshold >= 1");
  const std::string& style = a.word(2, "shift");
  if (style != "shift") a.fail(2, "shift (sable has no balance x or rcb yet)");
  const std::string& dims = a.word(3, "the axes to balance: letters x, y, z");
  for (std::size_t q = 0; q < dims.size(); ++q)
    if (dims[q] < 'x' || dims[q] > 'z' || dims.find(dims[q]) != q || (dims[q] == 'z' && sim.domain.dimension == 2))
      a.fail(3, std::string("axes x, y") + (sim.domain.dimension == 2 ? "" : ", z") + ", each once");
  if (a.integer(4, "the iteration count Niter") < 1) a.fail(4, "Niter >= 1");
  if (!(a.num(5, "the stop threshold") >= 1)) a.fail(5, "a stop threshold >= 1");
  if (a.size() > 6) a.fail(6, "nothing more (balance keywords out and weight are not supported)");
  const std::vector<double> before = grains_per_rank(sim);
  const double f0 = factor(before);
  char buf[256];
  if (sim.comm.size() == 1 || f0 <= thresh) {
    std::snprintf(buf, sizeof buf, "Balance: imbalance factor %.4g (threshold %g): the cuts stay", f0, thresh);
    sim.print(buf);
    return;
  }
  double rmax = 0;
  for (std::size_t i = 0; i < sim.atoms.n; ++i) rmax = std::max(rmax, sim.atoms.radius[i]);
  const double skin = sim.neighbor.skin_set ? sim.neighbor.skin : 0.001;  // the run's default (Simulation::setup)
  sim.comm.balance_shift(sim, dims, 2 * sim.comm.highest(rmax) + skin);
  const std::vector<double> after = grains_per_rank(sim);
  std::snprintf(buf, sizeof buf, "Balance: initial/final max grains per rank = %.0f %.0f\n  initial/final imbalance factor = %.4g %.4g",
                *std::max_element(before.begin(), before.end()), *std::max_element(after.begin(), after.end()), f0,
                factor(after));
  sim.print(buf);
  for (int k = 0; k < 3; ++k) {
    if (sim.comm.grid[k] == 1) continue;
    std::string line = std::string("  ") + char('x' + k) + " cuts:";
    for (int c = 0; c <= sim.comm.grid[k]; ++c) {
      std::snprintf(buf, sizeof buf, " %.6g", (sim.comm.face_at(sim.domain, k, c) - sim.domain.lo[k]) / sim.domain.length(k));
      line += buf;
    }
    sim.print(line);
  }
}

}  // namespace

SABLE_COMMAND("balance", cmd_balance);

}  // namespace sable
