// What runs on several MPI ranks so far (docs/parallel.md, "What runs on several
// ranks"): everything else stops at its deck line, on every rank alike, before it
// could give a wrong answer.
#include <algorithm>
#include <set>
#include <string>

#include "core/input/args.h"
#include "core/input/input.h"
#include "core/engine/simulation.h"

namespace sable {
namespace {

const std::set<std::string> kFixes = {
    "property/global", "wall/gran", "gravity", "nve/sphere", "nve", "enforce2d", "viscous", "damping/cundall",
    "freeze", "setforce", "addforce", "halt", "ave/time", "move", "property/atom",
    "mesh/surface", "mesh/surface/stress", "move/mesh",  // every rank holds every triangle
    "insert/pack", "insert/rate/region",  // the same grains whatever the rank count
    "balance",
    "particletemplate/sphere", "particledistribution/discrete"};  // the last two: definitions (insertion stops)
const std::set<std::string> kComputes = {"ke", "erotate/sphere", "reduce", "property/atom", "unbalanced/force"};
// Commands that write or read every grain, or change grains, after the atoms are split.
const std::set<std::string> kWholeSystem = {"write_data"};
const std::set<std::string> kDumps = {"custom"};  // gathered to rank 0, which writes
const std::set<std::string> kReplicatedOnly = {"create_atoms", "read_data", "read_restart", "create_box"};

std::string list(const std::set<std::string>& s) {
  std::string out;
  for (const std::string& w : s) out += (out.empty() ? "" : ", ") + w;
  return out;
}

const char* kOneRank = "; run it on one rank (OMP_NUM_THREADS=N sable -in DECK) until the domain decomposition supports it";

}  // namespace

void check_several_ranks(const Simulation& sim, const Args& a) {
  if (sim.comm.size() == 1) return;
  const std::string& c = a.command();
  const std::string ranks = " on " + std::to_string(sim.comm.size()) + " MPI ranks";
  if (c == "fix" && a.size() > 3) {  // fix ID group style ...
    if (!kFixes.count(a[3])) a.fail(3, "a fix style that runs" + ranks + " (" + list(kFixes) + ")" + kOneRank);
  }
  if (c == "compute" && a.size() > 3 && !kComputes.count(a[3]))
    a.fail(3, "a compute style that runs" + ranks + " (" + list(kComputes) + ")" + kOneRank);
  if (c == "pair_style" && a.size() > 1 && a[1] != "gran" && a[1] != "none")
    a.fail(1, "pair_style gran" + ranks + std::string(kOneRank));
  if ((c == "dump" || c == "write_dump") && a.size() > 3 && !kDumps.count(a[c == "dump" ? 3 : 2]))
    a.fail(c == "dump" ? 3 : 2, "a dump style that runs" + ranks + " (" + list(kDumps) + ")" + kOneRank);
  if (kWholeSystem.count(c)) a.fail(0, "a command that runs" + ranks + " (data files do not yet)" + kOneRank);
  if (sim.comm.distributed && c == "velocity" && a.size() > 2 && a[2] == "zero")
    a.fail(2, "set or ramp" + ranks + " after the first run (zero needs the group's momentum over all ranks, not done "
              "yet)" + kOneRank);
  if (sim.comm.distributed && kReplicatedOnly.count(c))
    a.fail(0, "a command that runs" + ranks + " after the first run (before it, every rank holds every grain; " + c +
                  " after it does not run there yet)" + kOneRank);
}

}  // namespace sable
