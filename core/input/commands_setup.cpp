// Box, style-creation and run-control commands (the deck's skeleton).
#include <cctype>
#include <cmath>

#include "core/engine/error.h"
#include "core/input/removed_styles.h"
#include "core/engine/shrink_wrap.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

void cmd_units(Simulation& sim, const Args& a) {
  const std::string& u = a.word(1, "a unit style (si)");
  if (u != "si") a.fail(1, "'si' (the only unit style sable supports)");
  sim.units = u;
}

void cmd_atom_style(Simulation&, const Args& a) {
  const std::string& s = a.word(1, "an atom style (granular or sphere)");
  if (s != "granular" && s != "sphere") a.fail(1, "'granular' or 'sphere'");
}

void cmd_atom_modify(Simulation& sim, const Args& a) {
  for (std::size_t i = 1; i < a.size(); ++i) {
    if (a[i] == "map") {
      a.word(i + 1, "array or hash");
      ++i;
    } else if (a[i] == "sort") {
      // sort Nfreq binsize: sable sorts at every neighbour build; 0 turns it off
      sim.neighbor.sort = a.integer(i + 1, "the sort period (0 = off)") != 0;
      a.num(i + 2, "the sort bin size");
      i += 2;
    } else if (a[i] == "first" || a[i] == "id") {
      ++i;
    } else {
      a.fail(i, "an atom_modify keyword: map, sort, first, id");
    }
  }
}

void cmd_dimension(Simulation& sim, const Args& a) {
  if (sim.domain.box_exists) a.fail_line("dimension must come before create_box");
  const long d = a.integer(1, "2 or 3");
  if (d != 2 && d != 3) a.fail(1, "2 or 3");
  sim.domain.dimension = static_cast<int>(d);
  // 2D grains (sable addition after `dimension 2`): LIGGGHTS' default is a disk's
  // mass (density per area, m = pi r^2 rho) with a sphere's inertia 2/5 m r^2;
  // `grains disks`: I = 1/2 m r^2 as well; `grains spheres`: spheres in the
  // plane, m = 4/3 pi r^3 rho and I = 2/5 m r^2.
  sim.atoms.area_density = d == 2;
  sim.atoms.inertia_factor = 0.4;
  if (a.size() == 2) return;
  if (d != 2 || a[2] != "grains") a.fail(2, d == 2 ? "'grains disks' or 'grains spheres'" : "nothing after 'dimension 3'");
  const std::string& g = a.word(3, "disks or spheres");
  if (g == "disks") sim.atoms.inertia_factor = 0.5;
  else if (g == "spheres") sim.atoms.area_density = false;
  else a.fail(3, "disks or spheres");
  if (a.size() > 4) a.fail(4, "nothing after the grain shape");
}

// contact_kernels auto|full (sable addition): `full` keeps the full 3D contact
// kernel where the 2D or no-rotation kernels would do (same physics; for
// benchmarks and checks of those kernels).
void cmd_contact_kernels(Simulation& sim, const Args& a) {
  const std::string& w = a.word(1, "auto or full");
  if (w != "auto" && w != "full") a.fail(1, "auto or full");
  if (a.size() > 2) a.fail(2, "nothing after '" + w + "'");
  sim.reduced_kernels = w == "auto";
}

void cmd_boundary(Simulation& sim, const Args& a) {
  if (sim.domain.box_exists) a.fail_line("boundary must come before create_box");
  for (int k = 0; k < 3; ++k) {
    const std::string& s = a.word(1 + k, "a boundary style per axis: p, f, m or s");
    sim.domain.periodic[k] = s == "p";
    if (s == "p") continue;
    // One letter for both faces or one per face (LAMMPS): f fixed, s shrink-wrapped, m shrink-wrapped with a minimum.
    if (s.size() > 2 || s.find_first_not_of("fsm") != std::string::npos)
      a.fail(1 + k, "p (periodic) or f (fixed) per axis, or s or m (shrink-wrapped), one letter per face allowed");
    for (int side = 0; side < 2; ++side) {
      const char c = s[std::min<std::size_t>(side, s.size() - 1)];
      set_face_style(sim, k, side, c == 'f' ? FaceStyle::Fixed : c == 's' ? FaceStyle::Shrink : FaceStyle::ShrinkMin);
    }
  }
}

void cmd_newton(Simulation& sim, const Args& a) {
  sim.newton = a.yes_no(1, "on or off");
}

void cmd_ignore(Simulation&, const Args&) {}  // communicate: no ghosts to send yet

// processors Px Py Pz (LAMMPS): the processor grid, each count a number or '*' (sable
// chooses, core/engine/comm.h). Checked here against the ranks, used when the box is created.
void cmd_processors(Simulation& sim, const Args& a) {
  if (sim.domain.box_exists) a.fail_line("processors must come before the box is created (create_box, read_data, read_restart)");
  Grid g{0, 0, 0};
  long product = 1;
  for (int k = 0; k < 3; ++k) {
    if (a.word(1 + k, "a processor count or *") == "*") continue;
    const long n = a.integer(1 + k, "a processor count or *");
    if (n < 1) a.fail(1 + k, "a processor count >= 1 or *");
    g[k] = static_cast<int>(n);
    product *= n;
  }
  if (a.size() > 4) a.fail(4, "nothing after Px Py Pz (sable has no grid, map, part or file keywords)");
  if (sim.domain.dimension == 2 && g[2] > 1) a.fail(3, "1 or * (Pz of a 2D box)");
  const int ranks = sim.comm.size();
  const bool all_given = g[0] && g[1] && g[2];
  if (all_given ? product != ranks : ranks % product != 0) {
    const std::size_t word = g[0] ? 1 : g[1] ? 2 : 3;  // the first explicit count
    a.fail(word, std::string(all_given ? "counts whose product is " : "counts whose product divides ") +
                     "the number of MPI ranks, " + std::to_string(ranks) + " (" + a[1] + " x " + a[2] + " x " + a[3] +
                     "; '*' lets sable choose)");
  }
  sim.comm.requested = g;
  sim.comm.requested_at = a.where().file + ":" + std::to_string(a.where().line);
}

// soft_particles yes|no (LIGGGHTS): yes allows youngsModulus below 5e6 in SI units.
void cmd_soft_particles(Simulation& sim, const Args& a) {
  sim.soft_particles = a.yes_no(1, "yes or no");
  if (a.size() > 2) a.fail(2, "nothing after yes/no");
}

void cmd_create_box(Simulation& sim, const Args& a) {
  if (sim.domain.box_exists) a.fail_line("the box already exists");
  const long nt = a.integer(1, "the number of atom types");
  if (nt < 1) a.fail(1, "a number of atom types >= 1");
  Region* r = sim.find_region(a.word(2, "a region ID"));
  if (!r) a.fail(2, "an existing region ID");
  for (int k = 0; k < 3; ++k) {
    sim.domain.lo[k] = r->lo[k];
    sim.domain.hi[k] = r->hi[k];
    if (!(r->hi[k] > r->lo[k]) || std::isinf(r->hi[k] - r->lo[k]))
      a.fail(2, "a region with finite extent on every axis");
  }
  sim.domain.box_exists = true;
  sim.atoms.ntypes = static_cast<int>(nt);
  box_created(sim);
}

void cmd_region(Simulation& sim, const Args& a) {
  const std::string& id = a.word(1, "a region ID");
  if (a.size() > 2 && a[2] == "delete") {
    sim.regions.erase(id);
    return;
  }
  const std::string& style = a.word(2, "a region style (block, cylinder, sphere)");
  const auto* make = RegionRegistry::find(style);
  if (!make) a.fail(2, "a region style: " + RegionRegistry::names());
  if (sim.regions.count(id)) a.fail(1, "a new region ID ('" + id + "' exists)");
  sim.regions[id] = (*make)(sim, a);
}

void cmd_neighbor(Simulation& sim, const Args& a) {
  sim.neighbor.skin = a.num(1, "the skin distance");
  if (sim.neighbor.skin < 0) a.fail(1, "a skin >= 0");
  sim.neighbor.skin_set = true;
  const std::string& s = a.word(2, "the binning style 'bin'");
  if (s != "bin" && s != "multi" && s != "nsq") a.fail(2, "bin");
}

// neigh_modify exclude type M N | group G1 G2 | none; returns the index of its last word.
static std::size_t parse_exclusion(Simulation& sim, const Args& a, std::size_t i) {
  std::vector<Neighbor::Exclusion>& ex = sim.neighbor.exclusions;
  const std::string& how = a.word(i + 1, "type, group or none");
  if (how == "none") {
    ex.clear();
    return i + 1;
  }
  if (how == "type") {
    int t[2];
    for (int k = 0; k < 2; ++k) {
      const long v = a.integer(i + 2 + k, "an atom type");
      if (v < 1 || v > sim.atoms.ntypes) a.fail(i + 2 + k, "an atom type from 1 to " + std::to_string(sim.atoms.ntypes));
      t[k] = static_cast<int>(v);
    }
    ex.push_back({true, t[0], t[1], 0, 0});
    return i + 3;
  }
  if (how == "group") {
    std::uint32_t bit[2];
    for (int k = 0; k < 2; ++k) {
      const int g = sim.groups.find(a.word(i + 2 + k, "a group ID"));
      if (g < 0) a.fail(i + 2 + k, "the ID of a group defined before");
      bit[k] = sim.groups.bit(g);
    }
    ex.push_back({false, 0, 0, bit[0], bit[1]});
    return i + 3;
  }
  if (how == "molecule/intra" || how == "molecule/inter")
    a.fail(i + 1, "type, group or none (granular atoms have no molecule IDs)");
  a.fail(i + 1, "type, group or none");
}

void cmd_neigh_modify(Simulation& sim, const Args& a) {
  Neighbor& n = sim.neighbor;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const std::string& k = a[i];
    if (k == "delay") {
      const long d = a.integer(++i, "the delay in steps");
      if (d < 0 || d > 1000000000) a.fail(i, "a delay of 0 or more steps");
      n.delay = static_cast<int>(d);
    }
    else if (k == "every") {
      const long e = a.integer(++i, "the check period in steps");
      if (e < 1 || e > 1000000000) a.fail(i, "a check period of 1 or more steps");
      n.every = static_cast<int>(e);
    }
    else if (k == "check") n.check = a.yes_no(++i, "yes or no");
    else if (k == "once") {
      if (a.yes_no(++i, "yes or no")) a.fail(i, "no (sable rebuilds the list whenever grains move; 'once yes' is not supported)");
    }
    else if (k == "page" || k == "one" || k == "binsize") ++i;  // list memory and bin sizes: sable sizes its own
    else if (k == "include") a.fail(i, "a neigh_modify keyword sable supports: delay, every, check, exclude (not include: lists restricted to a group)");
    else if (k == "exclude") i = parse_exclusion(sim, a, i);
    else a.fail(i, "a neigh_modify keyword: delay, every, check, exclude");
  }
  if (n.every < 1) a.fail_line("every must be >= 1");
}

void cmd_timestep(Simulation& sim, const Args& a) {
  sim.dt = a.num(1, "the time step in seconds");
  if (!(sim.dt > 0)) a.fail(1, "a time step > 0");
  sim.dt_set = true;
  sim.dt_where = a.where();
  sim.dt_line = a.joined();
}

// sable addition: what the setup-time stability check does when dt is unsafe.
void cmd_timestep_check(Simulation& sim, const Args& a) {
  const std::string& p = a.word(1, "stop or accept");
  if (p == "stop") sim.step_policy = StepPolicy::Stop;
  else if (p == "accept") sim.step_policy = StepPolicy::Accept;
  else a.fail(1, "stop or accept");
}

// info plan: each following run prints its step plan (core/engine/step_plan.h) after its setup.
void cmd_info(Simulation& sim, const Args& a) {
  if (a.word(1, "'plan'") != "plan") a.fail(1, "'plan' (the only info keyword sable has)");
  if (a.size() > 2) a.fail(2, "nothing after 'plan'");
  sim.print_plan = true;
}

void cmd_run(Simulation& sim, const Args& a) {
  long n = a.integer(1, "the number of steps");
  for (std::size_t i = 2; i < a.size(); ++i) {
    if (a[i] == "upto") {
      n -= sim.step;
    } else if (a[i] == "pre" || a[i] == "post") {
      a.yes_no(++i, "yes or no");
    } else if (a[i] == "start" || a[i] == "stop" || a[i] == "every") {
      a.fail(i, "upto, pre or post ('" + a[i] + "' is not supported yet)");
    } else {
      a.fail(i, "upto, pre or post");
    }
  }
  if (n < 0) a.fail(1, "a step count that is not in the past");
  try {
    sim.run(n);
  } catch (const SableError& e) {
    // An error that names its own deck line (a fix's or pair style's check at set-up)
    // keeps it and adds the run; one found while stepping (a lost grain, a blow-up) has
    // no line but the run's, so it leads with "FILE:LINE: 'run N':" as a command's error.
    const std::string msg = e.what();
    const std::size_t c = msg.find(':');
    std::size_t d = c + 1;
    while (c != std::string::npos && d < msg.size() && std::isdigit(static_cast<unsigned char>(msg[d]))) ++d;
    const bool located = c != std::string::npos && c > 0 && d > c + 1 && d < msg.size() && msg[d] == ':' &&
                         msg.find_first_of(" \n") > c;
    if (!located) a.fail_line(msg);
    throw SableError(msg + "\n  (during '" + a.joined() + "' at " + a.where().file + ":" +
                     std::to_string(a.where().line) + ")");
  }
}

void cmd_fix(Simulation& sim, const Args& a) {
  a.need(4, "fix ID group-ID style args");
  const auto* make = FixRegistry::find(a[3]);
  if (const std::string hint = removed_style_hint("fix", a[3]); !make && !hint.empty()) a.fail(3, hint);
  if (!make) a.fail(3, "a fix style: " + FixRegistry::names());
  sim.add_fix((*make)(sim, a));
}

void cmd_unfix(Simulation& sim, const Args& a) {
  const std::string& id = a.word(1, "a fix ID");
  if (!sim.find_fix(id)) a.fail(1, "an existing fix ID");
  sim.remove_fix(id);
}

void cmd_fix_modify(Simulation& sim, const Args& a) {
  Fix* f = sim.find_fix(a.word(1, "a fix ID"));
  if (!f) a.fail(1, "an existing fix ID");
  for (std::size_t i = 2; i < a.size();)
    if (!f->modify_param(a, i)) a.fail(i, "a fix_modify keyword that fix " + f->style + " understands");
}

void cmd_compute(Simulation& sim, const Args& a) {
  a.need(4, "compute ID group-ID style args");
  const auto* make = ComputeRegistry::find(a[3]);
  if (!make) a.fail(3, "a compute style: " + ComputeRegistry::names());
  if (sim.find_compute(a[1])) a.fail(1, "a new compute ID");
  sim.add_compute((*make)(sim, a));
}

void cmd_uncompute(Simulation& sim, const Args& a) {
  const std::string& id = a.word(1, "a compute ID");
  if (!sim.find_compute(id)) a.fail(1, "an existing compute ID");
  sim.remove_compute(id);
}

void cmd_pair_style(Simulation& sim, const Args& a) {
  const auto* make = PairRegistry::find(a.word(1, "a pair style (gran)"));
  if (const std::string hint = removed_style_hint("pair_style", a[1]); !make && !hint.empty()) a.fail(1, hint);
  if (!make) a.fail(1, "a pair style: " + PairRegistry::names());
  sim.pair = (*make)(sim, a);
  ++sim.config_epoch;
}

void cmd_pair_coeff(Simulation& sim, const Args& a) {
  if (!sim.pair) a.fail_line("pair_coeff before pair_style");
  sim.pair->coeff(a);
}

void cmd_dump(Simulation& sim, const Args& a) {
  a.need(6, "dump ID group-ID style N file args");
  const auto* make = DumpRegistry::find(a[3]);
  if (!make) a.fail(3, "a dump style: " + DumpRegistry::names());
  for (auto& d : sim.dumps)
    if (d->id == a[1]) a.fail(1, "a new dump ID");
  sim.dumps.push_back((*make)(sim, a));
}

void cmd_undump(Simulation& sim, const Args& a) {
  const std::string& id = a.word(1, "a dump ID");
  auto& ds = sim.dumps;
  auto it = std::find_if(ds.begin(), ds.end(), [&](auto& d) { return d->id == id; });
  if (it == ds.end()) a.fail(1, "an existing dump ID");
  ds.erase(it);
}

void cmd_dump_modify(Simulation& sim, const Args& a) {
  const std::string& id = a.word(1, "a dump ID");
  for (auto& d : sim.dumps)
    if (d->id == id) {
      for (std::size_t i = 2; i < a.size();)
        if (!d->modify_param(a, i)) a.fail(i, "a dump_modify keyword for dump " + d->style + " (e.g. sort id)");
      return;
    }
  a.fail(1, "an existing dump ID");
}

// write_dump group style file args [modify keyword values]: one snapshot now.
void cmd_write_dump(Simulation& sim, const Args& a) {
  std::vector<std::string> w = {"dump", "write_dump_tmp", a.word(1, "a group ID"), a.word(2, "a dump style"), "1",
                                a.word(3, "a file name")};
  std::size_t i = 4;
  for (; i < a.size() && a[i] != "modify"; ++i) w.push_back(a[i]);
  Args da(w, a.where());
  const auto* make = DumpRegistry::find(w[3]);
  if (!make) a.fail(2, "a dump style: " + DumpRegistry::names());
  auto d = (*make)(sim, da);
  for (++i; i < a.size();)
    if (!d->modify_param(a, i)) a.fail(i, "a dump_modify keyword (e.g. sort id)");
  d->init();
  d->write(sim.step);
  d->flush();
}

}  // namespace

SABLE_COMMAND("units", cmd_units);
SABLE_COMMAND("atom_style", cmd_atom_style);
SABLE_COMMAND("atom_modify", cmd_atom_modify);
SABLE_COMMAND("dimension", cmd_dimension);
SABLE_COMMAND("contact_kernels", cmd_contact_kernels);
SABLE_COMMAND("boundary", cmd_boundary);
SABLE_COMMAND("newton", cmd_newton);
SABLE_COMMAND("communicate", cmd_ignore);
SABLE_COMMAND("comm_modify", cmd_ignore);
SABLE_COMMAND("processors", cmd_processors);
SABLE_COMMAND("soft_particles", cmd_soft_particles);
SABLE_COMMAND("create_box", cmd_create_box);
SABLE_COMMAND("region", cmd_region);
SABLE_COMMAND("neighbor", cmd_neighbor);
SABLE_COMMAND("neigh_modify", cmd_neigh_modify);
SABLE_COMMAND("timestep", cmd_timestep);
SABLE_COMMAND("timestep_check", cmd_timestep_check);
SABLE_COMMAND("run", cmd_run);
SABLE_COMMAND("info", cmd_info);
SABLE_COMMAND("fix", cmd_fix);
SABLE_COMMAND("unfix", cmd_unfix);
SABLE_COMMAND("fix_modify", cmd_fix_modify);
SABLE_COMMAND("compute", cmd_compute);
SABLE_COMMAND("uncompute", cmd_uncompute);
SABLE_COMMAND("pair_style", cmd_pair_style);
SABLE_COMMAND("pair_coeff", cmd_pair_coeff);
SABLE_COMMAND("dump", cmd_dump);
SABLE_COMMAND("undump", cmd_undump);
SABLE_COMMAND("dump_modify", cmd_dump_modify);
SABLE_COMMAND("write_dump", cmd_write_dump);

}  // namespace sable
