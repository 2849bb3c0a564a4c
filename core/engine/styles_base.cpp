// Constructors and shared helpers of the style base classes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "core/engine/compute.h"
#include "core/io/dump.h"
#include "core/engine/error.h"
#include "core/engine/fix.h"
#include "core/engine/pair.h"
#include "core/geometry/region.h"
#include "core/engine/simulation.h"

namespace sable {

GlobalOutput* find_global_output(Simulation& sim, char kind, const std::string& id) {
  if (kind == 'c') return sim.find_compute(id);
  if (kind == 'f') return sim.find_fix(id);
  return nullptr;
}

std::string global_output_name(char kind, const std::string& id) { return (kind == 'c' ? "compute " : "fix ") + id; }

void Pair::compute_then(const RangeTail& tail) {
  compute();
  sim.atoms.for_ranges(tail);
}

void Fix::run_task(FixHook h) {
  if (!(atom_tasks & h)) return;
  begin(h);
  const bool phases = two_phase_tasks & h;
  sim.atoms.for_ranges([&](int t, std::size_t lo, std::size_t hi) {
    AtomRange r;
    r.thread = t, r.lo = lo, r.hi = hi;
    range(h, r);
    if (phases) {
      atom_pass_barrier();
      r.phase = 1;
      range(h, r);
    }
  });
  end(h);
}

std::vector<const Fix*> Fix::later_force_fixes() const {
  std::vector<const Fix*> out;
  bool after = false;
  for (auto& f : sim.fixes) {
    if (after && (f->hooks & POST_FORCE) && !f->traits.keeps_plane) out.push_back(f.get());
    if (f.get() == this) after = true;
  }
  return out;
}

const char* role_name(FixRole r) {
  switch (r) {
    case FixRole::None: return "";
    case FixRole::Integrator: return "integrator";
    case FixRole::RigidBodies: return "rigid-body integrator";
    case FixRole::PrescribedMotion: return "prescribed motion";
    case FixRole::ForceContributor: return "force contributor";
    case FixRole::Constraint: return "constraint";
  }
  return "";
}

double FixTraits::acceleration_norm() const {
  const double* a = acceleration;
  return accelerates ? std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) : 0.0;
}

FixRole Fix::role(FixHook h) const {
  if (!((hooks | atom_tasks) & h)) return FixRole::None;
  if (h & (INITIAL_INTEGRATE | FINAL_INTEGRATE | FINAL_THEN_INITIAL)) {
    if (rigid_bodies()) return FixRole::RigidBodies;
    return traits.prescribes_motion ? FixRole::PrescribedMotion : FixRole::Integrator;
  }
  if (h == POST_FORCE) return traits.constraint ? FixRole::Constraint : FixRole::ForceContributor;
  return FixRole::None;
}

double Region::depth(const double*, int) const { return std::numeric_limits<double>::quiet_NaN(); }

Fix::Fix(Simulation& s, const Args& a) : sim(s), args(a) {
  id = a.word(1, "a fix ID");
  group = s.groups.existing(a, 2);
  groupbit = s.groups.bit(group);
  style = a.word(3, "a fix style");
}

Compute::Compute(Simulation& s, const Args& a) : sim(s), args(a) {
  id = a.word(1, "a compute ID");
  group = s.groups.existing(a, 2);
  groupbit = s.groups.bit(group);
  style = a.word(3, "a compute style");
}

void Compute::init_now() {
  init();
  init_epoch_ = sim.config_epoch;
}

void Compute::ready() {
  if (init_epoch_ != sim.config_epoch) init_now();
}

double Compute::scalar() {
  ready();
  if (scalar_step_ != sim.step || invoked_step != sim.step) {
    scalar_cache_ = compute_scalar();
    scalar_step_ = invoked_step = sim.step;
  }
  return scalar_cache_;
}

double Compute::vector(int i) {
  if (i < 1 || i > vector_size)
    args.fail_line("c_" + id + "[" + std::to_string(i) + "]: index out of range 1.." + std::to_string(vector_size));
  ready();
  return compute_vector(i);
}

void Compute::peratom_now() {
  ready();
  if (peratom_step_ == sim.step && peratom.size() >= sim.atoms.n * std::max(1, peratom_cols)) return;
  compute_peratom();
  peratom_step_ = sim.step;
}

void Compute::local_now() {
  ready();
  if (local_step_ == sim.step) return;
  compute_local();
  local_step_ = sim.step;
}

Region::Region(Simulation& s, const Args& a) : sim(s) {
  id = a.word(1, "a region ID");
  style = a.word(2, "a region style");
}

void Region::parse_options(const Args& a, std::size_t i) {
  bool lattice_units = true;  // LAMMPS default is lattice units
  for (; i < a.size(); i += 2) {
    if (a[i] == "side") {
      interior = a.choice(i + 1, {"in", "out"}) == 0;
    } else if (a[i] == "units") {
      lattice_units = a.choice(i + 1, {"box", "lattice"}) == 1;
    } else {
      a.fail(i, "a region option: side in|out or units box|lattice");
    }
  }
  if (lattice_units && sim.lattice.style != "none") {
    xscale = sim.lattice.a[0];
    yscale = sim.lattice.a[1];
    zscale = sim.lattice.a[2];
  }
}

double Region::coord(const Args& a, std::size_t i, int axis, bool upper) const {
  const std::string& w = a.word(i, "a coordinate");
  const double big = std::numeric_limits<double>::max() / 4;
  if (w == "INF" || w == "EDGE") {
    if (w == "EDGE" && !sim.domain.box_exists) a.fail(i, "a number (EDGE needs a box)");
    if (w == "EDGE") return upper ? sim.domain.hi[axis] : sim.domain.lo[axis];
    return upper ? big : -big;
  }
  if (w == "-INF") return -big;
  return a.num(i, "a coordinate, INF or EDGE");
}

Dump::Dump(Simulation& s, const Args& a) : sim(s), args(a) {
  id = a.word(1, "a dump ID");
  group = s.groups.existing(a, 2);
  groupbit = s.groups.bit(group);
  style = a.word(3, "a dump style");
  every = a.integer(4, "the dump period N (steps)");
  if (every <= 0) a.fail(4, "a period > 0");
  file = a.word(5, "a dump file name");
  multifile = file.find('*') != std::string::npos;
}

bool Dump::modify_param(const Args& a, std::size_t& i) {
  if (a[i] == "sort") {
    const std::string& v = a.word(i + 1, "id or off");
    if (v == "id") sort_by_id = true;
    else if (v == "off") sort_by_id = false;
    else a.fail(i + 1, "id or off");
  } else if (a[i] == "every") {
    every = a.integer(i + 1, "the dump period N (v_name is not supported)");
    if (every <= 0) a.fail(i + 1, "a period > 0");
  } else if (a[i] == "first") {
    if (a.yes_no(i + 1, "no")) a.fail(i + 1, "'no' (first yes is not supported)");
  } else {
    return false;
  }
  i += 2;
  return true;
}

std::vector<std::size_t> Dump::selected_atoms() const {
  std::vector<std::size_t> sel;
  for (std::size_t i = 0; i < sim.atoms.n; ++i)
    if (sim.atoms.mask[i] & groupbit) sel.push_back(i);
  if (sort_by_id)
    std::sort(sel.begin(), sel.end(), [&](std::size_t p, std::size_t q) { return sim.atoms.id[p] < sim.atoms.id[q]; });
  return sel;
}

void Dump::write(long step) {
  if (multifile) {
    std::string path = file;
    path.replace(path.find('*'), 1, std::to_string(step));
    const std::string tmp = path + ".tmp";
    write_snapshot(step, tmp, false);
    if (sim.comm.rank() == 0) std::filesystem::rename(tmp, path);  // atomic: readers never see a partial file
  } else {
    write_snapshot(step, file, !first_);
  }
  first_ = false;
}

}  // namespace sable
