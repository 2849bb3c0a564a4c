// read_data FILE (LAMMPS/LIGGGHTS, atom_style granular|sphere): creates the box
// and the atoms of a data file. Header: "N atoms", "N atom types", "xlo xhi",
// "ylo yhi", "zlo zhi"; sections "Atoms" (id type diameter density x y z
// [ix iy iz]) and "Velocities" (id vx vy vz omegax omegay omegaz). What sable
// has no use for (bonds, tilt, other sections, the keywords after FILE) is an
// error naming the data file's line, rather than silently dropped.
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

constexpr std::size_t kAbsent = static_cast<std::size_t>(-1);  // Atoms::index_of's npos

struct DataFile {
  const Args& cmd;
  std::string name;
  std::ifstream in;
  int line = 0;

  [[noreturn]] void fail(const std::string& what) const {
    cmd.fail_line("data file " + name + ", line " + std::to_string(line) + ": " + what);
  }
  // The next line with its comment cut; false at the end of the file.
  bool next(std::string& s) {
    if (!std::getline(in, s)) return false;
    ++line;
    const auto hash = s.find('#');
    if (hash != std::string::npos) s.erase(hash);
    return true;
  }
  static bool blank(const std::string& s) { return s.find_first_not_of(" \t\r") == std::string::npos; }
  std::vector<std::string> words(const std::string& s) const {
    std::istringstream is(s);
    std::vector<std::string> w;
    for (std::string x; is >> x;) w.push_back(x);
    return w;
  }
  double number(const std::string& w, const char* what) const {
    double v;
    if (!parse_double(w, v) || !std::isfinite(v)) fail(std::string("expected ") + what + ", got '" + w + "'");
    return v;
  }
  long integer(const std::string& w, const char* what) const {
    long v;
    if (!parse_long(w, v)) fail(std::string("expected ") + what + ", got '" + w + "'");
    return v;
  }
};

struct Header {
  long atoms = -1, types = -1;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  bool axis[3] = {false, false, false};
};

// Header lines up to the first section keyword, which is returned in `section`.
void read_header(DataFile& f, Header& h, std::string& section) {
  std::string s;
  f.next(s);  // the title line
  while (f.next(s)) {
    if (DataFile::blank(s)) continue;
    const auto w = f.words(s);
    if (w.size() == 1 || (w.size() >= 1 && !std::isdigit(static_cast<unsigned char>(w[0][0])) && w[0][0] != '-' &&
                          w[0][0] != '+' && w[0][0] != '.')) {
      section = w[0];
      return;
    }
    if (w.size() == 2 && w[1] == "atoms") h.atoms = f.integer(w[0], "a number of atoms");
    else if (w.size() == 3 && w[1] == "atom" && w[2] == "types") h.types = f.integer(w[0], "a number of atom types");
    else if (w.size() == 4 && (w[2] == "xlo" || w[2] == "ylo" || w[2] == "zlo")) {
      const int k = w[2][0] - 'x';
      if (w[3] != std::string(1, w[2][0]) + "hi") f.fail("expected '" + w[2] + " " + w[2][0] + "hi'");
      h.lo[k] = f.number(w[0], "a lower box bound");
      h.hi[k] = f.number(w[1], "an upper box bound");
      if (!(h.hi[k] > h.lo[k])) f.fail("expected an upper box bound greater than the lower one");
      h.axis[k] = true;
    } else if (w.size() >= 2 && f.integer(w[0], "a count") == 0) {
      continue;  // "0 bonds", "0 bond types", ...: nothing to read
    } else {
      f.fail("'" + s + "': sable reads atoms, atom types and box bounds (no bonds, angles, tilt or extra per-atom data)");
    }
  }
  f.fail("expected an Atoms section");
}

// One section's N lines (blank lines first, as LAMMPS writes them).
template <class Row>
void read_rows(DataFile& f, long n, Row&& row) {
  std::string s;
  for (long k = 0; k < n;) {
    if (!f.next(s)) f.fail("the file ends inside a section (" + std::to_string(k) + " of " + std::to_string(n) + " lines read)");
    if (DataFile::blank(s)) {
      if (k == 0) continue;
      f.fail("a blank line inside a section (" + std::to_string(k) + " of " + std::to_string(n) + " lines read)");
    }
    row(f.words(s));
    ++k;
  }
}

void read_atoms(Simulation& sim, DataFile& f, const Header& h) {
  Atoms& at = sim.atoms;
  std::unordered_set<long> seen;  // (Atoms::index_of would rebuild its map after every add)
  read_rows(f, h.atoms, [&](const std::vector<std::string>& w) {
    if (w.size() != 7 && w.size() != 10)
      f.fail("expected 'id type diameter density x y z [ix iy iz]' (atom_style granular/sphere), got " +
             std::to_string(w.size()) + " words");
    const long id = f.integer(w[0], "an atom id");
    const long type = f.integer(w[1], "an atom type");
    const double d = f.number(w[2], "a diameter"), rho = f.number(w[3], "a density");
    if (id < 1) f.fail("expected an atom id >= 1");
    if (type < 1 || type > h.types) f.fail("expected an atom type from 1 to " + std::to_string(h.types));
    if (!(d > 0)) f.fail("expected a diameter > 0 (sable's grains are spheres)");
    if (!(rho > 0)) f.fail("expected a density > 0");
    if (!seen.insert(id).second) f.fail("atom id " + std::to_string(id) + " appears twice");
    double x[3];
    for (int k = 0; k < 3; ++k) x[k] = f.number(w[4 + k], "a coordinate");
    const std::size_t i = at.add(id, static_cast<int>(type), x, 0.5 * d, rho);
    if (w.size() == 10)
      for (int k = 0; k < 3; ++k) at.image[3 * i + k] = static_cast<int>(f.integer(w[7 + k], "an image flag"));
  });
}

void read_velocities(Simulation& sim, DataFile& f, long n) {
  Atoms& at = sim.atoms;
  read_rows(f, n, [&](const std::vector<std::string>& w) {
    if (w.size() != 7) f.fail("expected 'id vx vy vz omegax omegay omegaz', got " + std::to_string(w.size()) + " words");
    const long id = f.integer(w[0], "an atom id");
    const std::size_t i = at.index_of(id);
    if (i == kAbsent) f.fail("atom id " + std::to_string(id) + " is not in the Atoms section");
    for (int k = 0; k < 3; ++k) {
      at.v[3 * i + k] = f.number(w[1 + k], "a velocity component");
      at.omega[3 * i + k] = f.number(w[4 + k], "an angular velocity component");
    }
  });
}

void cmd_read_data(Simulation& sim, const Args& a) {
  if (sim.domain.box_exists) a.fail_line("read_data creates the box: it must come before create_box or another read_data");
  if (a.size() > 2) a.fail(2, "nothing after the file name (sable's read_data takes no keywords)");
  DataFile f{a, a.word(1, "a data file name"), {}, 0};
  f.in.open(f.name);
  if (!f.in) a.fail(1, "a readable data file (cannot open '" + f.name + "')");
  Header h;
  std::string section;
  read_header(f, h, section);
  if (h.atoms < 0) f.fail("expected the header line 'N atoms' before the sections");
  if (h.types < 1) f.fail("expected the header line 'N atom types' (N >= 1) before the sections");
  for (int k = 0; k < 3; ++k)
    if (!h.axis[k]) f.fail(std::string("expected the header line '") + char('x' + k) + "lo " + char('x' + k) + "hi'");
  for (int k = 0; k < 3; ++k) sim.domain.lo[k] = h.lo[k], sim.domain.hi[k] = h.hi[k];
  sim.domain.box_exists = true;
  sim.atoms.ntypes = static_cast<int>(h.types);
  box_created(sim);
  bool atoms_read = false;
  std::string s;
  do {
    if (section == "Atoms") {
      read_atoms(sim, f, h);
      atoms_read = true;
    } else if (section == "Velocities") {
      if (!atoms_read) f.fail("expected the Atoms section before Velocities");
      read_velocities(sim, f, h.atoms);
    } else {
      f.fail("'" + section + "': sable reads the Atoms and Velocities sections only");
    }
    section.clear();
    while (section.empty() && f.next(s))
      if (!DataFile::blank(s)) section = f.words(s)[0];
  } while (!section.empty());
  if (!atoms_read) f.fail("expected an Atoms section");
}

}  // namespace

SABLE_COMMAND("read_data", cmd_read_data);

}  // namespace sable
