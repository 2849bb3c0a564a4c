#include "core/engine/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <limits>
#include <numeric>

#include "core/engine/error.h"
#include "core/engine/rigid_bodies.h"
#include "core/io/h5_series.h"
#include "core/input/input.h"
#include "core/engine/shrink_wrap.h"
#include "core/engine/threads.h"
#include "core/io/thermo.h"
#include "core/input/variable.h"

namespace sable {

Simulation::Simulation()
    : variables(std::make_unique<Variables>(*this)), thermo(std::make_unique<Thermo>(*this)),
      t0_(std::chrono::steady_clock::now()) {}

Simulation::~Simulation() {
  forget_face_styles(*this);
  if (logfile) std::fclose(logfile);
}

double Simulation::wall_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

void Simulation::print(const std::string& line) { print_to(line, true, true); }

void Simulation::print_to(const std::string& line, bool to_screen, bool to_log) {
  if (comm.rank() != 0) return;  // several ranks: rank 0 speaks for all
  if (screen && to_screen) {
    std::fprintf(screen, "%s\n", line.c_str());
    std::fflush(screen);
  }
  if (logfile && to_log) {
    std::fprintf(logfile, "%s\n", line.c_str());
    std::fflush(logfile);
  }
}

void Simulation::warn(const std::string& line) { print("WARNING: " + line); }

void Simulation::print_once(const std::string& line) {
  if (printed_once.insert(line).second) print(line);
}

void Simulation::open_log(const std::string& path) {
  if (logfile) std::fclose(logfile);
  logfile = nullptr;
  if (path == "none" || comm.rank() != 0) return;
  logfile = std::fopen(path.c_str(), "w");
  if (!logfile) fail("cannot open log file '" + path + "' for writing");
}

Fix* Simulation::find_fix(const std::string& id) const {
  for (auto& f : fixes)
    if (f->id == id) return f.get();
  return nullptr;
}

std::pair<const RigidBodies*, int> Simulation::body_of(std::size_t i) const {
  for (auto& f : fixes)
    if (const RigidBodies* rb = f->rigid_bodies())
      if (const int b = rb->body_of(i); b >= 0) return {rb, b};
  return {nullptr, -1};
}

Compute* Simulation::find_compute(const std::string& id) const {
  for (auto& c : computes)
    if (c->id == id) return c.get();
  return nullptr;
}

Region* Simulation::find_region(const std::string& id) const {
  auto it = regions.find(id);
  return it == regions.end() ? nullptr : it->second.get();
}

void Simulation::add_fix(std::unique_ptr<Fix> f) {
  // After read_restart, a fix defined with a stored ID and style resumes its state (LIGGGHTS).
  auto st = restart.fix_states.find(f->id);
  if (st != restart.fix_states.end()) {
    if (st->second.style == f->style) {
      f->read_state(st->second.bytes);
      print("INFO: fix " + f->id + " (" + f->style + ") resumes its state from restart file '" + restart.file + "'");
    } else {
      warn("fix " + f->id + " was style " + st->second.style + " in restart file '" + restart.file +
           "'; its stored state does not apply to style " + f->style + " and is discarded");
    }
    restart.fix_states.erase(st);
  }
  // A fix with an existing ID replaces it in place (LAMMPS semantics).
  for (auto& old : fixes)
    if (old->id == f->id) {
      old = std::move(f);
      ++config_epoch;
      return;
    }
  fixes.push_back(std::move(f));
  ++config_epoch;
}

void Simulation::remove_fix(const std::string& id) {
  fixes.erase(std::remove_if(fixes.begin(), fixes.end(), [&](auto& f) { return f->id == id; }), fixes.end());
  ++config_epoch;
}

void Simulation::add_compute(std::unique_ptr<Compute> c) {
  for (auto& old : computes)
    if (old->id == c->id) fail("compute ID '" + c->id + "' already exists (uncompute it first)");
  computes.push_back(std::move(c));
}

void Simulation::remove_compute(const std::string& id) {
  computes.erase(std::remove_if(computes.begin(), computes.end(), [&](auto& c) { return c->id == id; }),
                 computes.end());
}

void Simulation::flush_outputs() {
  if (screen) std::fflush(screen);
  if (logfile) std::fflush(logfile);
  for (auto& d : dumps) d->flush();
  H5Series::flush_all();  // buffered HDF5 rows (core/io/h5_series.h)
}

// True when every velocity (and, with `positions`, every position) is finite.
// x - x is 0 for a finite x and NaN otherwise, so the sum is 0 exactly when all
// are finite: a branch-free pass (vectorised; each thread's partial sum is 0 or
// NaN whatever the order).
static bool all_finite(const Atoms& a, bool positions) {
  const double *x = a.x.data(), *v = a.v.data();
  std::vector<double> part(atom_pass_threads(), 0.0);
  a.for_ranges([&](int t, std::size_t lo, std::size_t hi) {
    double s = 0.0;
    if (positions) {
#pragma omp simd reduction(+ : s)
      for (std::size_t k = 3 * lo; k < 3 * hi; ++k) s += (x[k] - x[k]) + (v[k] - v[k]);
    } else {
#pragma omp simd reduction(+ : s)
      for (std::size_t k = 3 * lo; k < 3 * hi; ++k) s += v[k] - v[k];
    }
    part[t] = s;
  });
  for (double s : part)
    if (s != 0.0) return false;
  return true;
}

namespace {
// The deepest overlap among the pairs of the current neighbour list, relative to the
// smaller radius, and the fastest grain; atoms with a non-finite state are skipped.
struct Extremes {
  double overlap = 0, rel = 0, speed = 0;
  long i = -1, j = -1, fastest = -1;
  std::size_t deep = 0;  // pairs overlapping by more than kDeepOverlap of the smaller radius
};
constexpr double kDeepOverlap = 0.1;

bool finite3(const double* x) { return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]); }

Extremes extremes(const Simulation& sim) {
  const Atoms& a = sim.atoms;
  const NeighborList& l = sim.neighbor.list;
  Extremes e;
  const bool listed = sim.pair && l.first.size() == a.n + 1;
  for (std::size_t i = 0; i < a.n; ++i) {
    const double* xi = &a.x[3 * i];
    if (!finite3(xi) || !finite3(&a.v[3 * i])) continue;
    const double* v = &a.v[3 * i];
    const double sp = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (sp > e.speed) e.speed = sp, e.fastest = a.id[i];
    if (!listed) continue;
    for (int k = l.first[i]; k < l.first[i + 1]; ++k) {
      const std::size_t j = static_cast<std::size_t>(l.j[k]);
      if (j >= a.n || !finite3(&a.x[3 * j])) continue;
      double d2 = 0;
      for (int c = 0; c < 3; ++c) {
        const double dx = a.x[3 * j + c] + l.shift_vec[l.shift[k]][c] - xi[c];
        d2 += dx * dx;
      }
      const double ov = a.radius[i] + a.radius[j] - std::sqrt(d2);
      const double rmin = std::min(a.radius[i], a.radius[j]);
      if (ov <= 0 || !(rmin > 0)) continue;
      if (ov / rmin > kDeepOverlap) ++e.deep;
      if (ov / rmin > e.rel) e.rel = ov / rmin, e.overlap = ov, e.i = a.id[i], e.j = a.id[j];
    }
  }
  return e;
}

std::string describe(const Extremes& e) {
  char buf[256];
  std::string s;
  if (e.i >= 0) {
    std::snprintf(buf, sizeof buf, "largest overlap: atoms %ld and %ld by %g (%.0f%% of the smaller radius)", e.i, e.j,
                  e.overlap, 100 * e.rel);
    s = buf;
  }
  if (e.fastest >= 0) {
    std::snprintf(buf, sizeof buf, "%sfastest grain: atom %ld at %g", s.empty() ? "" : "; ", e.fastest, e.speed);
    s += buf;
  }
  return s;
}

// A deck that runs before `set diameter` leaves LIGGGHTS' 1 m grains: say so instead of
// crawling through an all-pairs neighbour search, or of missing every contact.
void check_grain_sizes(Simulation& sim) {
  const Atoms& a = sim.atoms;
  const Domain& d = sim.domain;
  double rmax = 0;
  std::size_t big = 0;
  for (std::size_t i = 0; i < a.n; ++i)
    if (a.radius[i] > rmax) rmax = a.radius[i], big = i;
  if (!sim.pair) return;  // grains that do not touch may be any size (LIGGGHTS' point-like decks)
  for (int k = 0; k < d.dimension; ++k)
    if (2 * rmax > d.length(k)) {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "atom %ld has diameter %g, larger than the box along %c (%g): were the diameters set "
                    "(set ... diameter, or the particle template) before the run?",
                    a.id[big], 2 * rmax, 'x' + k, d.length(k));
      sim.warn(buf);
      break;
    }
  // Only when the cutoff spans the box on every axis is the search truly all-pairs.
  const double cut = 2 * rmax + sim.neighbor.skin;
  bool spans = a.n > 1;
  for (int k = 0; k < d.dimension; ++k) spans = spans && cut >= d.length(k);
  if (spans) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "neighbour cutoff %g (largest diameter %g + skin %g) is as large as the box on every axis: "
                  "every grain is searched against every other",
                  cut, 2 * rmax, sim.neighbor.skin);
    sim.warn(buf);
  }
}
}  // namespace

// Velocities are checked after a step (unless the rebuild check scanned the
// positions, see run()); a position only turns non-finite through a velocity
// that was, or by overflow, which the rebuild check catches: it treats a NaN
// displacement as a rebuild, and rebuilds check positions too.
void Simulation::check_atoms(bool positions) {
  const Atoms& a = atoms;
  if (all_finite(a, positions)) return;
  for (std::size_t i = 0; i < a.n; ++i) {
    const double* x = &a.x[3 * i];
    const double* v = &a.v[3 * i];
    bool ok = true;
    for (int k = 0; k < 3; ++k) ok = ok && std::isfinite(x[k]) && std::isfinite(v[k]);
    if (ok) continue;
    flush_outputs();
    const double* f = &a.f[3 * i];
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "step %ld: atom %ld has a non-finite state (x = %g %g %g, v = %g %g %g, f = %g %g %g); "
                  "usually the time step is too large for the stiffness or two grains overlap deeply",
                  step, a.id[i], x[0], x[1], x[2], v[0], v[1], v[2], f[0], f[1], f[2]);
    const std::string seen = describe(extremes(*this));
    fail(std::string(buf) + (seen.empty() ? "" : " (" + seen + ")"));
  }
}

// Whether an atom lies beyond a fixed boundary, on the per-atom passes' ranges
// (atom_pass_threaded), not serially.
static bool any_outside(const Atoms& a, const Domain& d) {
  const double* x = a.x.data();
  std::vector<char> part(atom_pass_threads(), 0);
  a.for_ranges([&](int t, std::size_t lo, std::size_t hi) {
    bool out = false;
    for (int k = 0; k < d.dimension; ++k) {
      if (d.periodic[k]) continue;
      const double lo_k = d.lo[k], hi_k = d.hi[k];
      for (std::size_t i = lo; i < hi; ++i) out |= x[3 * i + k] < lo_k || x[3 * i + k] > hi_k;
    }
    part[t] = out;
  });
  return std::find(part.begin(), part.end(), 1) != part.end();
}

// Atoms beyond a fixed boundary are lost: stop (or delete them with thermo_modify lost ignore).
static void handle_lost(Simulation& sim) {
  shrink_wrap(sim);  // s and m faces follow the atoms first (LAMMPS resets such a box at each rebuild)
  Atoms& a = sim.atoms;
  const Domain& d = sim.domain;
  if (!any_outside(a, d)) return;
  std::vector<char> lost(a.n, 0);
  bool any = false;
  for (std::size_t i = 0; i < a.n; ++i)
    for (int k = 0; k < d.dimension; ++k) {
      if (d.periodic[k]) continue;
      const double xk = a.x[3 * i + k];
      if (xk < d.lo[k] || xk > d.hi[k]) {
        if (!sim.lost_ignore) {
          sim.flush_outputs();
          char buf[256];
          std::snprintf(buf, sizeof buf,
                        "step %ld: atom %ld left the box through the fixed boundary on axis %c (%c = %g, box %g .. %g); "
                        "lost atoms (use 'thermo_modify lost ignore' to delete such atoms instead)",
                        sim.step, a.id[i], 'x' + k, 'x' + k, xk, d.lo[k], d.hi[k]);
          const std::string seen = describe(extremes(sim));
          fail(std::string(buf) + (seen.empty() ? "" : " (" + seen + ")"));
        }
        lost[i] = 1;
        any = true;
      }
    }
  if (any) a.remove_if(lost);
}

void Simulation::rebuild_if_due() {
  if (comm.decomposed()) {
    if (comm.any(neighbor.decide(atoms, step))) rebuild_decomposed();
    return;
  }
  if (!neighbor.decide(atoms, step)) return;
  check_atoms(true);
  handle_lost(*this);
  neighbor.build(atoms, domain, pair ? pair->history() : nullptr, step);
}

// The pair's history is saved before the grains move (it is kept by grain id); the
// ghost layer is as wide as the widest pair anywhere: twice the largest radius of
// all ranks plus the skin.
void Simulation::rebuild_decomposed() {
  check_atoms(true);
  handle_lost(*this);
  ContactStore* store = pair ? pair->history() : nullptr;
  neighbor.save_history(store);
  const auto t0 = std::chrono::steady_clock::now();
  comm.exchange(*this);
  double rmax = 0.0;
  for (std::size_t i = 0; i < atoms.n; ++i) rmax = std::max(rmax, atoms.radius[i]);
  const double cutoff = 2.0 * comm.max(rmax) + neighbor.skin;
  Neighbor::Ghosted& g = neighbor.ghosted;
  g.on = true;
  g.cutoff = cutoff;
  g.bins = domain;
  Domain sub = domain;  // this rank's subdomain
  for (int k = 0; k < 3; ++k)
    if (comm.grid[k] > 1) {
      sub.lo[k] = comm.sublo[k], sub.hi[k] = comm.subhi[k];
      g.bins.lo[k] = comm.sublo[k] - cutoff;
      g.bins.hi[k] = comm.subhi[k] + cutoff;
      g.bins.periodic[k] = false;  // its images are ghosts
    }
  neighbor.sort_owned(atoms, sub, cutoff);
  comm.borders(*this, cutoff);
  const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  timers.comm += spent, timers.neigh -= spent;  // the stage's time counts in neigh
  neighbor.build(atoms, domain, store, step);
}

void Simulation::force_and_history() {
  atoms.clear_forces();
  if (comm.distributed) comm.forward(atoms);  // set-up (not timed)
  if (pair) pair->compute();
}

Simulation::StepBounds Simulation::step_bounds(double vmin) const {
  StepBounds b;
  const long total = comm.total(static_cast<long>(atoms.n));
  if (!pair || total == 0) return b;
  const Atoms& a = atoms;
  // Speed scale: fastest grain, fastest moving wall, free fall across the box
  // (along non-periodic axes only: a grain falling along a periodic axis hits nothing).
  double vmax = vmin, g = 0.0;
  for (std::size_t i = 0; i < a.n; ++i) {
    const double* v = &a.v[3 * i];
    vmax = std::max(vmax, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  for (auto& f : fixes) {
    vmax = std::max(vmax, f->max_speed());
    g = std::max(g, f->traits.acceleration_norm());
  }
  double hmax = 0.0;
  for (int k = 0; k < domain.dimension; ++k)
    if (!domain.periodic[k]) hmax = std::max(hmax, domain.length(k));
  b.speed = std::max({comm.highest(vmax), std::sqrt(2.0 * g * hmax), 1e-3});
  // Rayleigh time per grain; Hertz time of the lightest grain hitting itself (LIGGGHTS' recipe).
  std::size_t ismall = 0;
  b.rayleigh = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < a.n; ++i) {
    if (a.rmass[i] < a.rmass[ismall]) ismall = i;
    b.rayleigh = std::min(b.rayleigh, pair->rayleigh_time(i));
  }
  b.rayleigh = comm.lowest(b.rayleigh);
  // Grains approach each other at up to twice the fastest speed (LIGGGHTS uses the relative speed too).
  b.hertz = comm.lowest(a.n ? pair->contact_time(ismall, ismall, 2.0 * b.speed) : std::numeric_limits<double>::max());
  b.skin_ratio = neighbor.skin / (2.0 * b.speed * dt);
  b.valid = true;
  return b;
}

// The setup time-step check. Measured bound (input_scripts/stability/REPORT.md): above 30% of
// the contact time collisions and settled beds go wrong (energy created from 40%, beds lost
// from 45%), so that stops; between the usual rule of thumb (20% of the Rayleigh time, 10% of
// the contact time) and that bound the run goes on with one warning.
void Simulation::stability_check(bool mid_run) {
  constexpr double kRuleRayleigh = 0.2, kRuleContact = 0.1, kStopContact = 0.3;
  const StepBounds b = step_bounds();
  stability_pending_ = pair && !b.valid;
  if (!b.valid) return;
  char ray[128] = "no Rayleigh time (no youngsModulus: stiffness model)";
  if (b.rayleigh < 1e300)
    std::snprintf(ray, sizeof ray, "%.1f%% of the Rayleigh time %g s (rule of thumb 20%%)", 100 * dt / b.rayleigh,
                  b.rayleigh);
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "Time-step check: dt = %g s is %s and %.1f%% of the contact time %g s at v_rel = %g m/s "
                "(rule of thumb 10%%, stability bound 30%%); skin / (2 v dt) = %.3g",
                dt, ray, 100 * dt / b.hertz, b.hertz, 2 * b.speed, b.skin_ratio);
  print_to(mid_run ? "Step " + std::to_string(step) + ", the first with grains: " + buf : std::string(buf), true,
           !mid_run);
  const std::string where = dt_where.file + ":" + std::to_string(dt_where.line) + ": '" + dt_line + "' ";
  if (dt > kStopContact * b.hertz) {
    char why[512];
    std::snprintf(why, sizeof why,
                  "exceeds sable's stability bound, 30%% of the contact time (%.1f%% of %g s at v_rel = %g m/s): "
                  "beyond it collisions gain energy and beds blow up (input_scripts/stability/REPORT.md)",
                  100 * dt / b.hertz, b.hertz, 2 * b.speed);
    const std::string msg = where + why;
    if (step_policy == StepPolicy::Accept) {
      warn(msg + "; accepted because of 'timestep_check accept'");
      return;
    }
    char fix[128];
    std::snprintf(fix, sizeof fix, ". Reduce the time step to %.3g s or less", kStopContact * b.hertz);
    fail(msg + fix + ", or add 'timestep_check accept' to run anyway.");
  }
  std::string over;
  if (dt > kRuleRayleigh * b.rayleigh) over = "20% of the Rayleigh time";
  if (dt > kRuleContact * b.hertz) over += std::string(over.empty() ? "" : " and ") + "10% of the contact time";
  if (!over.empty())
    print_once("WARNING: " + where + "is above the usual rule of thumb (" + over +
               ") but within sable's stability bound (30% of the contact time): it runs; expect collisions to "
               "lose or gain up to a few % of their energy (input_scripts/stability/REPORT.md)");
  if (b.skin_ratio >= 1.0) return;
  // A list checked at every step misses no contact, only rebuilds often; one checked less often can miss them.
  const std::string skin = "lets grains approach each other by more than the skin per step (skin / (2 v dt) = " +
                           std::to_string(b.skin_ratio) + ")";
  if (neighbor.delay == 0 && neighbor.every <= 1 && neighbor.check) {
    print_once("WARNING: " + where + skin + ": the neighbour list is rebuilt at almost every step (slow; no contact "
               "is missed, the list being checked at every step); a larger skin (neighbor) avoids it");
    return;
  }
  const std::string msg = where + skin + " between list checks (neigh_modify delay/every): contacts can be missed";
  if (step_policy == StepPolicy::Accept) {
    warn(msg + "; accepted because of 'timestep_check accept'");
    return;
  }
  fail(msg + ". Reduce the time step, enlarge the skin or check the list every step (neigh_modify delay 0 every 1 "
       "check yes), or add 'timestep_check accept' to run anyway.");
}

// Restart data nobody claimed by the first run: pair history goes into the pair
// style's store (restored at the build below); unclaimed fix states are dropped
// (LIGGGHTS discards them at the first run too).
void Simulation::claim_restart_leftovers() {
  RestartPending& r = restart;
  if (r.contacts.count() > 0) {
    ContactStore* store = pair ? pair->history() : nullptr;
    if (!store) {
      warn("restart file '" + r.file + "' holds contact history of " + std::to_string(r.contacts.count()) +
           " contacts (" + r.pair_model + "), but " + (pair ? pair->describe() : std::string("no pair style")) +
           " keeps none: it is dropped");
    } else {
      const auto missing = store->inject(r.slots, r.contacts);
      for (auto& m : missing)
        warn("restart file '" + r.file + "' has no contact history slot '" + m + "' (written by " + r.pair_model +
             "); it starts at zero for the " + std::to_string(r.contacts.count()) + " stored contacts");
    }
  }
  r.contacts.clear();
  r.slots.clear();
  for (auto& [id, st] : r.fix_states)
    warn("restart file '" + r.file + "' holds a state for fix " + id + " (" + st.style +
         "), but no fix with that ID and style was defined before this run: the state is discarded");
  r.fix_states.clear();
}

void Simulation::setup() {
  if (!domain.box_exists) fail("run: no simulation box yet (use create_box or read_data before run)");
  if (!neighbor.skin_set) neighbor.skin = 0.001;  // LIGGGHTS default for SI units
  for (auto& f : fixes) f->init();
  for (auto& c : computes) {
    c->reset_cache();
    c->init_now();
  }
  for (auto& d : dumps) d->init();
  if (pair) pair->init();
  claim_restart_leftovers();
  handle_lost(*this);
  check_grain_sizes(*this);
  const bool first_build = neighbor.builds == 0;
  if (comm.decomposed())
    rebuild_decomposed();
  else
    neighbor.build(atoms, domain, pair ? pair->history() : nullptr, step);
  check_atoms(true);
  if (const Extremes e = first_build ? extremes(*this) : Extremes{}; e.deep > 0)
    warn(std::to_string(e.deep) + " pair(s) of grains overlap by more than " + std::to_string(int(100 * kDeepOverlap)) +
         "% of the smaller radius at setup; " + describe(e).substr(0, describe(e).find(';')));
  stability_check();
  choose_kinematics();
  force_and_history();
  for (auto& f : fixes)
    if (f->hooks & POST_FORCE) f->post_force();
  for (auto& f : fixes) f->setup();
}

// "Model only what the scene needs": a 2D run's contacts are in the plane; no
// grain turns when no fix may turn one (FixTraits::turns_grains) and every spin is 0
// (omega then stays 0, and contacts need neither spin nor torque).
void Simulation::choose_kinematics() {
  atoms.plane_2d = reduced_kernels && domain.dimension == 2;
  bool turns = !reduced_kernels;
  for (auto& f : fixes)
    turns = turns || f->traits.turns_grains.value_or((f->hooks & (INITIAL_INTEGRATE | FINAL_INTEGRATE)) != 0);
  for (std::size_t k = 0; k < 3 * atoms.n && !turns; ++k) turns = atoms.omega[k] != 0.0;
  atoms.rotation = turns;
}

// "pair 1.48 / 1.49 / 1.50 s of 1.69 s (88%)": each thread's busy seconds
// (min / mean / max) in the passes' wall seconds; the rest it waited for the others.
static std::string balance_text(const char* what, const ThreadBalance& b) {
  if (b.calls == 0 || b.busy.size() < 2 || b.wall <= 0) return "";
  const auto [lo, hi] = std::minmax_element(b.busy.begin(), b.busy.end());
  const double mean = std::accumulate(b.busy.begin(), b.busy.end(), 0.0) / b.busy.size();
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %.3g / %.3g / %.3g s of %.3g s (%.0f%%)", what, *lo, mean, *hi, b.wall,
                100 * mean / b.wall);
  return buf;
}

// Several ranks: how the run's seconds and grains spread over them (LAMMPS prints
// min / avg / max per section): each line is collective.
std::string Simulation::rank_balance() const {
  const double tot = std::max(timers.total, 1e-12);
  auto spread = [&](const char* what, double v, const char* unit) {
    char b[160];
    std::snprintf(b, sizeof b, "%s %.3g / %.3g / %.3g%s", what, comm.min(v), comm.sum(v) / comm.size(), comm.max(v), unit);
    return std::string(b);
  };
  char share[64];
  std::snprintf(share, sizeof share, " (comm %.1f%% of the loop on average)", 100 * comm.sum(timers.comm) / comm.size() / tot);
  return "Rank balance (" + std::to_string(comm.size()) + " ranks, min / mean / max): " +
         spread("pair", timers.pair, " s") + "; " + spread("neigh", timers.neigh, " s") + "; " +
         spread("comm", timers.comm, " s") + "; " + spread("grains", static_cast<double>(atoms.n), "") +
         "; " + spread("ghosts", static_cast<double>(atoms.nghost), "") + share;
}

void Simulation::explain_slow_path(const StepPlan& plan) {
  auto note = [&](const Fix* f, const std::string& what) {
    if (!slow_path_noted_.insert(f->id).second) return;
    print("Note: fix " + f->id + " (" + f->style + ") " + what);
  };
  if (!(plan_rewrites & kFuse)) return;
  std::vector<const Fix*> integrators, post;
  int initial = 0, final = 0;  // fixes holding each integration hook
  bool pipelined = false;
  for (const Stage& s : plan.stages) {
    if (s.kind == Stage::Hook && (s.hook == INITIAL_INTEGRATE || s.hook == FINAL_INTEGRATE)) {
      integrators.push_back(s.fix);
      (s.hook == INITIAL_INTEGRATE ? initial : final) += 1;
    }
    if (s.kind == Stage::Hook && s.hook == POST_FORCE) post.push_back(s.fix);
    pipelined = pipelined || (s.kind == Stage::ForcePass && !s.ops.empty());
  }
  constexpr unsigned kBoth = INITIAL_INTEGRATE | FINAL_INTEGRATE;
  if (!plan.integrator) {
    const bool several = initial > 1 || final > 1;  // as the plan's fuse() refuses
    for (const Fix* f : integrators)
      if (several || (f->atom_tasks & kBoth) != kBoth || f->traits.prescribes_motion)
        note(f, std::string(several                         ? "is one of several integrating fixes"
                            : f->traits.prescribes_motion ? "prescribes motion by the step's time"
                                                          : "integrates outside the step plan") +
                    ": the two half steps and the force clear run as separate passes over every grain, and "
                    "the post-force fixes after the force pass (3-4 parallel regions a step instead of 1)");
    return;
  }
  if (pipelined || !pair) return;
  for (const Fix* f : post)
    if (!(f->atom_tasks & POST_FORCE) || (f->two_phase_tasks & POST_FORCE))
      note(f, std::string(f->atom_tasks & POST_FORCE ? "has a post_force in two phases (every grain's force first)"
                                                     : "has a post_force that is not a per-atom task") +
                  ": the force pass, the post-force fixes and the "
              "integrator run as separate passes over every grain (3 parallel regions a step instead of 1)");
}

void Simulation::request_stop(const std::string& why) {
  stop_ = true;
  if (!why.empty()) skip_runs_ = why;
}

bool Simulation::quiet(long s) const {
  if (s >= run_last || (thermo->every > 0 && s % thermo->every == 0)) return false;
  for (auto& f : fixes)
    if ((f->hooks & END_OF_STEP) && s % f->nevery == 0) return false;
  for (auto& d : dumps)
    if (s % d->every == 0) return false;
  return true;
}

// Several ranks: the ghosts' state, counted in comm (out of the pass's time).
void Simulation::forward_ghosts() {
  if (!comm.distributed) return;
  const auto t0 = std::chrono::steady_clock::now();
  comm.forward(atoms);
  const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  timers.comm += spent, timers.pair -= spent;
}

void Simulation::force_pass(const Stage& s) {
  forward_ghosts();
  if (s.ops.empty()) {
    if (pair) pair->compute();
    return;
  }
  const bool next_first = std::any_of(s.ops.begin(), s.ops.end(),
                                      [](auto& o) { return o.kind == AtomOp::FirstHalf || o.kind == AtomOp::BothHalves; });
  if (std::any_of(s.ops.begin(), s.ops.end(), [](auto& o) { return o.kind == AtomOp::Prescan; }))
    neighbor.expect_prescan(atoms, step + 1);
  begin_ops(s);
  double fix_s = 0.0, all_s = 0.0;  // thread 0's seconds in post_force tasks and in all ops (time split)
  pair->compute_then([&](int t, std::size_t lo, std::size_t hi) {
    if (t != 0) return run_ops_on_range(*this, s.ops, t, lo, hi);
    const auto t0 = std::chrono::steady_clock::now();
    run_ops_on_range(*this, s.ops, t, lo, hi, &fix_s);
    all_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  });
  end_ops(s);
  cleared_steps += next_first && std::any_of(s.ops.begin(), s.ops.end(), [](auto& o) { return o.kind == AtomOp::ClearForces; });
  timers.pair -= all_s;  // thread 0's share, as the time split counts
  timers.fixes += fix_s;
  timers.integrate += all_s - fix_s;
}

void Simulation::run_stage(const Stage& s) {
  switch (s.kind) {
    case Stage::Hook:
      switch (s.hook) {
        case INITIAL_INTEGRATE: return s.fix->initial_integrate();
        case POST_INTEGRATE: return s.fix->post_integrate();
        case PRE_FORCE: return s.fix->pre_force();
        case POST_FORCE: return s.fix->post_force();
        case FINAL_INTEGRATE: return s.fix->final_integrate();
        case END_OF_STEP:
          if (step % s.fix->nevery == 0) s.fix->end_of_step();
          return;
      }
      return;
    case Stage::AtomPass: {
      const auto has = [&](AtomOp::Kind k) {
        return std::any_of(s.ops.begin(), s.ops.end(), [&](auto& o) { return o.kind == k; });
      };
      if (has(AtomOp::Prescan)) neighbor.expect_prescan(atoms, step);
      run_atom_ops(*this, s);
      cleared_steps += (has(AtomOp::FirstHalf) || has(AtomOp::BothHalves)) && has(AtomOp::ClearForces);
      return;
    }
    case Stage::Rebuild: return rebuild_if_due();
    case Stage::ForcePass: return force_pass(s);
    case Stage::Check:
      // A velocity turned non-finite makes a position non-finite next step, which the
      // rebuild check catches: a separate pass only when it did not scan this step.
      if (neighbor.positions_scanned_step != step) check_atoms(false);
      return;
    case Stage::Output:
      if ((thermo->every > 0 && step % thermo->every == 0) || step == run_last || stop_) thermo->line(step);
      for (auto& d : dumps)
        if (step % d->every == 0) d->write(step);
      return;
  }
}

// Which part of the time split a stage counts in.
using TimerField = double Simulation::Timers::*;
static TimerField timer_of(const Stage& s) {
  switch (s.kind) {
    case Stage::Rebuild: return &Simulation::Timers::neigh;
    case Stage::ForcePass: return &Simulation::Timers::pair;
    case Stage::Check:
    case Stage::Output: return &Simulation::Timers::output;
    case Stage::AtomPass:
      return s.ops.size() == 1 && s.ops[0].kind == AtomOp::ClearForces ? &Simulation::Timers::pair
                                                                       : &Simulation::Timers::integrate;
    case Stage::Hook:
      if (s.hook == PRE_FORCE) return &Simulation::Timers::pair;
      if (s.hook == POST_FORCE || s.hook == END_OF_STEP) return &Simulation::Timers::fixes;
      return &Simulation::Timers::integrate;
  }
  return &Simulation::Timers::fixes;
}

static bool applies(When w, bool quiet, bool after_quiet) {
  switch (w) {
    case When::Always: return true;
    case When::Loud: return !quiet;
    case When::Quiet: return quiet;
    case When::AfterLoud: return !after_quiet;
    case When::AfterQuiet: return after_quiet;
  }
  return true;
}

void Simulation::run(long nsteps) {
  if (!skip_runs_.empty()) {
    print("run " + std::to_string(nsteps) + " skipped: " + skip_runs_);
    return;
  }
  stop_ = false;
  run_first = step;
  run_last = step + nsteps;
  setup();
  thermo->header();
  thermo->line(step);
  for (auto& d : dumps)
    if (step % d->every == 0) d->write(step);
  const StepPlan plan = build_plan(*this, plan_rewrites);
  if (print_plan) print(plan.describe());
  explain_slow_path(plan);

  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  auto t_last_progress = t_start;
  timers = Timers{};
  const long builds0 = neighbor.builds;
  thread_balance(PassKind::Pair).clear();
  thread_balance(PassKind::Atoms).clear();
  bool after_quiet = false;  // the last step deferred its second half kick
  const long grains_at_start = comm.total(static_cast<long>(atoms.n));  // the progress line's rate
  while (step < run_last && !stop_) {
    ++step;
    time += dt;
    const bool q = plan.defers && quiet(step);
    auto tic = clock::now();
    for (const Stage& s : plan.stages) {
      if (!applies(s.when, q, after_quiet)) continue;
      run_stage(s);
      const auto now = clock::now();
      timers.*timer_of(s) += std::chrono::duration<double>(now - tic).count();
      tic = now;
    }
    fused_steps += q;
    folded_steps += q && plan.folded;
    after_quiet = q;
    if (stability_pending_ && comm.total(static_cast<long>(atoms.n)) > 0) stability_check(true);  // the first grains were inserted

    const auto now = clock::now();
    if (progress && std::chrono::duration<double>(now - t_last_progress).count() >= progress_every_s &&
        step < run_last) {
      t_last_progress = now;
      const double el = std::chrono::duration<double>(now - t_start).count();
      const double done = static_cast<double>(step - run_first) / nsteps;
      char buf[256];
      std::snprintf(buf, sizeof buf, "Progress: step %ld, %.1f%% done, %.3g particle-steps/s, %.0f s left", step,
                    100 * done, static_cast<double>(comm.distributed ? grains_at_start : static_cast<long>(atoms.n)) * (step - run_first) / el, el / done * (1 - done));
      print_to(buf, true, false);  // the screen's: the log keeps the thermo table unbroken
    }
  }
  timers.total = std::chrono::duration<double>(clock::now() - t_start).count();
  if (stop_) nsteps = (run_last = step) - run_first;  // ended early: the run's bounds as they came out
  for (auto& f : fixes) f->post_run();
  const double tot = std::max(timers.total, 1e-12);
  const std::size_t natoms = static_cast<std::size_t>(comm.total(static_cast<long>(atoms.n)));  // all ranks'
  char buf[512];
  // LAMMPS' run marker, word for word (log readers end a run's thermo table at it); sable's rates below.
  std::snprintf(buf, sizeof buf,
                "Loop time of %g on %d procs for %ld steps with %zu atoms\nPerformance: %.3g particle-steps/s, %ld "
                "neighbor builds\nTime split: pair %.1f%%, neigh %.1f%%, integrate %.1f%%, fixes %.1f%%, output %.1f%%",
                timers.total, comm.size(), nsteps, natoms, natoms * nsteps / tot, neighbor.builds - builds0,
                100 * timers.pair / tot, 100 * timers.neigh / tot, 100 * timers.integrate / tot,
                100 * timers.fixes / tot, 100 * timers.output / tot);
  print(buf);
  if (comm.size() > 1) print(rank_balance());
  // LIGGGHTS' wording (half list: each pair once; builds during this run).
  const std::size_t entries = static_cast<std::size_t>(comm.total(static_cast<long>(neighbor.list.size())));
  std::snprintf(buf, sizeof buf, "Total # of neighbors = %zu, Ave neighs/atom = %.4g, Neighbor list builds = %ld",
                entries, natoms ? static_cast<double>(entries) / natoms : 0.0, neighbor.builds - builds0);
  print(buf);
  // Threaded runs: how evenly the threads shared the work (LIGGGHTS prints min/avg/max over MPI ranks).
  const ThreadBalance &tp = thread_balance(PassKind::Pair), &ta = thread_balance(PassKind::Atoms);
  const std::string pb = balance_text("pair", tp), ab = balance_text("per-atom passes", ta);
  if (!pb.empty() || !ab.empty())
    print("Thread balance (" + std::to_string(std::max(tp.busy.size(), ta.busy.size())) +
          " threads, busy min / mean / max): " + pb + (!pb.empty() && !ab.empty() ? "; " : "") + ab);
  flush_outputs();
}

}  // namespace sable
