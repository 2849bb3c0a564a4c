#include "core/io/thermo.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <map>

#include <unistd.h>

#include "core/engine/error.h"
#include "core/engine/rigid_bodies.h"
#include "core/input/number_format.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"

namespace sable {

bool parse_reference(const std::string& w, char& kind, std::string& id, int& index, int* column) {
  if (w.size() < 3 || w[1] != '_' || (w[0] != 'c' && w[0] != 'f' && w[0] != 'v')) return false;
  kind = w[0];
  id = w.substr(2);
  index = 0;
  if (column) {
    *column = 0;
    const std::size_t b2 = id.find("][");
    if (b2 != std::string::npos && id.back() == ']') {
      *column = std::atoi(id.substr(b2 + 2, id.size() - b2 - 3).c_str());
      if (*column < 1) return false;
      id = id.substr(0, b2 + 1);
    }
  }
  const std::size_t b = id.find('[');
  if (b != std::string::npos) {
    if (id.back() != ']') return false;
    index = std::atoi(id.substr(b + 1, id.size() - b - 2).c_str());
    if (index < 1) return false;
    id = id.substr(0, b);
  }
  return !id.empty();
}

Thermo::Thermo(Simulation& sim) : sim_(sim) {}

// Translational: 1/2 m v^2 per grain, and 1/2 M vcm^2 once per body whose members
// carry the body's mass (fix multisphere, as LIGGGHTS 3.8 prints it).
double Thermo::kinetic_energy() const {
  const Atoms& a = sim_.atoms;
  double ke = 0.0;
  std::vector<const RigidBodies*> owners;
  for (const auto& f : sim_.fixes) {
    double k;
    if (const RigidBodies* rb = f->rigid_bodies(); rb && rb->body_kinetic_energy(k)) {
      ke += k;
      owners.push_back(rb);
    }
  }
  for (std::size_t i = 0; i < a.n; ++i) {
    if (std::any_of(owners.begin(), owners.end(), [i](const RigidBodies* rb) { return rb->body_of(i) >= 0; }))
      continue;
    const double* v = &a.v[3 * i];
    ke += 0.5 * a.rmass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return ke;
}

bool Thermo::keyword(const std::string& k, double& out) {
  const Domain& d = sim_.domain;
  if (k == "step") out = static_cast<double>(sim_.step);
  else if (k == "elapsed") out = static_cast<double>(sim_.step - sim_.run_first);
  else if (k == "elaplong") out = static_cast<double>(sim_.step - sim_.run_first);
  else if (k == "dt") out = sim_.dt;
  else if (k == "beginstep") out = static_cast<double>(sim_.run_first);
  else if (k == "endstep") out = static_cast<double>(sim_.run_last);
  else if (k == "time") out = sim_.time;
  else if (k == "cpu") out = sim_.wall_seconds();
  else if (k == "atoms") out = static_cast<double>(sim_.comm.total(static_cast<long>(sim_.atoms.n)));
  else if (k == "ke") {
    const long n = sim_.comm.total(static_cast<long>(sim_.atoms.n));
    out = sim_.comm.total(kinetic_energy()) / ((norm_ && n) ? n : 1);
  }
  else if (k == "xlo") out = d.lo[0];
  else if (k == "xhi") out = d.hi[0];
  else if (k == "ylo") out = d.lo[1];
  else if (k == "yhi") out = d.hi[1];
  else if (k == "zlo") out = d.lo[2];
  else if (k == "zhi") out = d.hi[2];
  else if (k == "lx") out = d.length(0);
  else if (k == "ly") out = d.length(1);
  else if (k == "lz") out = d.length(2);
  else if (k == "vol") out = d.volume();
  else return false;
  return true;
}

double Thermo::column(const std::string& w, const Args& where) {
  double v;
  if (keyword(w, v)) return v;
  char kind;
  std::string id;
  int index, col;
  if (!parse_reference(w, kind, id, index, &col))
    where.fail_line("thermo column '" + w + "' is not a keyword (step, atoms, ke, time, dt, cpu, xlo..zhi, lx, ly, lz, vol) nor c_ID, f_ID, v_name");
  if (kind == 'v') {
    if (!sim_.variables->numeric(id, v)) where.fail_line("thermo column '" + w + "': variable '" + id + "' is not defined or not equal-style");
    return v;
  }
  GlobalOutput* g = find_global_output(sim_, kind, id);
  if (!g) where.fail_line("thermo column '" + w + "': no " + (kind == 'c' ? "compute" : "fix") + " with ID '" + id + "'");
  return g->global(index, col);
}

void Thermo::set_style(const Args& a) {
  const std::string& s = a.word(1, "a thermo style (custom, one)");
  if (s == "one") {
    columns = {"step", "atoms", "ke"};
  } else if (s == "custom") {
    a.need(3, "at least one thermo keyword after 'custom'");
    columns.assign(a.words().begin() + 2, a.words().end());
  } else {
    a.fail(1, "'custom' or 'one'");
  }
  columns_where = a;
  // Validate references now so a typo fails at its line, not mid-run.
  for (std::size_t i = 2; i < a.size() && s == "custom"; ++i) {
    double v;
    char kind;
    std::string id;
    int index, col;
    if (keyword(a[i], v)) continue;
    if (!parse_reference(a[i], kind, id, index, &col))
      a.fail(i, "a thermo keyword (step, atoms, ke, time, dt, cpu, xlo, ..., vol) or c_ID, f_ID, f_ID[i][j], v_name");
    if (kind == 'c' && !sim_.find_compute(id)) a.fail(i, "an existing compute ID");
    if (kind == 'f' && !sim_.find_fix(id)) a.fail(i, "an existing fix ID");
    if (kind == 'c' && col) a.fail(i, "c_ID or c_ID[i] (sable computes have no global arrays)");
    if (kind == 'f' && col) {
      const Fix* f = sim_.find_fix(id);
      if (index > f->array_rows || col > f->array_cols)
        a.fail(i, "an element of fix " + id + "'s global array, within [1.." + std::to_string(f->array_rows) + "][1.." +
                      std::to_string(f->array_cols) + "]");
    }
    if (kind == 'v' && !sim_.variables->exists(id)) a.fail(i, "a defined variable");
  }
}

void Thermo::modify(const Args& a) {
  for (std::size_t i = 1; i < a.size(); i += 2) {
    const std::string& k = a[i];
    const std::string& val = a.word(i + 1, "a value for thermo_modify " + k);
    if (k == "lost") {
      if (val != "ignore" && val != "error" && val != "warn") a.fail(i + 1, "ignore, warn or error");
      sim_.lost_ignore = val != "error";
    } else if (k == "norm") {
      norm_ = a.yes_no(i + 1, "yes or no");
    } else if (k == "format") {
      if (val == "float" || val == "int") {
        const std::string& fmt = a.word(i + 2, "a printf format");
        const std::string bad = number_format_problem(fmt, val == "int");
        if (!bad.empty()) a.fail(i + 2, "a printf format with " + bad);
        (val == "float" ? float_fmt_ : int_fmt_) = fmt;
      }
      ++i;
    } else if (k == "flush" || k == "line" || k == "every") {
      // accepted for LIGGGHTS compatibility; output is flushed every line anyway
    } else {
      a.fail(i, "a thermo_modify keyword: lost, norm, format, flush, line");
    }
  }
}

// The header word LAMMPS and LIGGGHTS print for a thermo keyword (Step, KinEng, Volume, ...);
// references (c_ID, f_ID[2], v_name) and sable's own keywords as written in the deck.
static std::string header_word(const std::string& k) {
  static const std::map<std::string, std::string> lammps{
      {"step", "Step"}, {"elapsed", "Elapsed"}, {"elaplong", "Elaplong"}, {"dt", "Dt"}, {"time", "Time"},
      {"cpu", "CPU"}, {"atoms", "Atoms"}, {"ke", "KinEng"}, {"vol", "Volume"}, {"lx", "Lx"}, {"ly", "Ly"},
      {"lz", "Lz"}, {"xlo", "Xlo"}, {"xhi", "Xhi"}, {"ylo", "Ylo"}, {"yhi", "Yhi"}, {"zlo", "Zlo"}, {"zhi", "Zhi"}};
  const auto it = lammps.find(k);
  return it == lammps.end() ? k : it->second;
}

// The process's resident memory in MB (Linux /proc; 0 where unknown).
static double resident_mbytes() {
  long pages = 0, resident = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// A run's thermo table opens as in LIGGGHTS: the memory line, which LAMMPS log readers
// (lammps-logfile, pymatgen) take as a run's start, then the header, starting with Step.
void Thermo::header() {
  char buf[96];
  std::snprintf(buf, sizeof buf, "Memory usage per processor = %.4g Mbytes", resident_mbytes());
  sim_.print(buf);
  std::string s;
  for (auto& c : columns) {
    std::snprintf(buf, sizeof buf, "%14s ", header_word(c).c_str());
    s += buf;
  }
  sim_.print(s);
}

void Thermo::line(long) {
  std::string s;
  char buf[64];
  for (auto& c : columns) {
    const double v = column(c, columns_where);
    if ((c == "step" || c == "atoms" || c == "elapsed") && v == static_cast<long>(v))
      std::snprintf(buf, sizeof buf, "%14ld ", static_cast<long>(v));
    else {
      char tmp[48];
      std::snprintf(tmp, sizeof tmp, float_fmt_.c_str(), v);
      std::snprintf(buf, sizeof buf, "%14s ", tmp);
    }
    s += buf;
  }
  sim_.print(s);
}

static void cmd_thermo(Simulation& sim, const Args& a) {
  sim.thermo->every = a.integer(1, "the thermo output period N (steps)");
  if (sim.thermo->every < 0) a.fail(1, "a period >= 0");
}
static void cmd_thermo_style(Simulation& sim, const Args& a) { sim.thermo->set_style(a); }
static void cmd_thermo_modify(Simulation& sim, const Args& a) { sim.thermo->modify(a); }
SABLE_COMMAND("thermo", cmd_thermo);
SABLE_COMMAND("thermo_style", cmd_thermo_style);
SABLE_COMMAND("thermo_modify", cmd_thermo_modify);

}  // namespace sable
