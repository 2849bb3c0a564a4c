// balance thresh shift dimstr Niter stopthresh (LAMMPS): when the imbalance factor (the most
// grains a rank would own over the mean) exceeds thresh, the processor grid's inner cuts
// along the axes of dimstr move to where each slab holds as many grains (one pass over a
// histogram of all ranks' grains; Niter and stopthresh are read, LAMMPS iterates), no slab
// thinner than the ghost cutoff. The next run moves the grains (its set-up's exchange).
// Styles x and rcb (Zoltan) are not done yet; on one rank it only reports the factor 1.
// fixes/fix_balance.cpp redoes it every N steps of a run.
#include <cstdio>
#include <string>

#include "core/input/command_balance.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

BalanceShift parse_balance_shift(const Simulation& sim, const Args& a, std::size_t at) {
  BalanceShift b;
  b.thresh = a.num(at, "the imbalance threshold (>= 1)");
  if (!(b.thresh >= 1)) a.fail(at, "an imbalance threshold >= 1");
  const std::string& style = a.word(at + 1, "shift");
  if (style != "shift") a.fail(at + 1, "shift (sable has no balance x or rcb yet)");
  b.dims = a.word(at + 2, "the axes to balance: letters x, y, z");
  for (std::size_t q = 0; q < b.dims.size(); ++q)
    if (b.dims[q] < 'x' || b.dims[q] > 'z' || b.dims.find(b.dims[q]) != q || (b.dims[q] == 'z' && sim.domain.dimension == 2))
      a.fail(at + 2, std::string("axes x, y") + (sim.domain.dimension == 2 ? "" : ", z") + ", each once");
  if (a.integer(at + 3, "the iteration count Niter") < 1) a.fail(at + 3, "Niter >= 1");
  if (!(a.num(at + 4, "the stop threshold") >= 1)) a.fail(at + 4, "a stop threshold >= 1");
  if (a.size() > at + 5) a.fail(at + 5, "nothing more (balance keywords out and weight are not supported)");
  return b;
}

std::string cuts_text(const Simulation& sim) {
  std::string out;
  char buf[64];
  for (int k = 0; k < 3; ++k) {
    if (sim.comm.grid[k] == 1) continue;
    out += std::string(out.empty() ? "" : "\n") + "  " + char('x' + k) + " cuts:";
    for (int c = 0; c <= sim.comm.grid[k]; ++c) {
      std::snprintf(buf, sizeof buf, " %.6g", (sim.comm.face_at(sim.domain, k, c) - sim.domain.lo[k]) / sim.domain.length(k));
      out += buf;
    }
  }
  return out;
}

namespace {

void cmd_balance(Simulation& sim, const Args& a) {
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before balance)");
  const BalanceShift b = parse_balance_shift(sim, a, 1);
  const auto [before, after] = sim.comm.rebalance(sim, b.thresh, b.dims);
  char buf[256];
  if (after == before && (sim.comm.size() == 1 || before <= b.thresh)) {
    std::snprintf(buf, sizeof buf, "Balance: imbalance factor %.4g (threshold %g): the cuts stay", before, b.thresh);
    sim.print(buf);
    return;
  }
  std::snprintf(buf, sizeof buf, "Balance: initial/final imbalance factor = %.4g %.4g", before, after);
  sim.print(buf);
  sim.print(cuts_text(sim));
}

}  // namespace

SABLE_COMMAND("balance", cmd_balance);

}  // namespace sable
