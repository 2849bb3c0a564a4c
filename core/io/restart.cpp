#include "core/io/restart.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>

#include "core/engine/contact_source.h"
#include "core/engine/error.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable::restart {

void Unpacker::truncated(std::uint64_t n) const {
  fail(what_ + " is truncated: " + std::to_string(n) + " more bytes needed where " + std::to_string(left()) +
       " remain (was the writer killed, or the copy incomplete?)");
}

namespace {

const std::string kMagic = "SABLE RESTART\n";
constexpr std::uint32_t kByteOrder = 0x01020304;

std::uint64_t fnv1a(const char* p, std::size_t n) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(p[i])) * 1099511628211ull;
  return h;
}

// Element types of per-atom arrays, stored so a reader can check what it gets.
enum Kind : std::uint8_t { kI64 = 0, kI32 = 1, kU32 = 2, kF64 = 3 };
static_assert(sizeof(long) == 8, "restart files store atom ids as 64-bit integers");
template <class T>
constexpr Kind kind_of() {
  if constexpr (std::is_same_v<T, long>)
    return kI64;
  else if constexpr (std::is_same_v<T, int>)
    return kI32;
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return kU32;
  else
    return kF64;
}

// Per-atom array: name, element kind, stride, is an extra column, values (n * stride).
template <class T>
void put_array(Packer& p, const std::string& name, const std::vector<T>& v, int stride, std::size_t n, bool column) {
  p.put_string(name);
  p.put<std::uint8_t>(kind_of<T>());
  p.put<std::int32_t>(stride);
  p.put<std::uint8_t>(column);
  p.put_vector(std::vector<T>(v.begin(), v.begin() + n * stride));
}

void put_section(Packer& file, const std::string& name, const Packer& body) {
  file.put_string(name);
  file.put_string(body.bytes);
}

std::string atoms_section(const Atoms& a) {
  Packer p;
  p.put<std::uint64_t>(a.n);
  p.put<std::int64_t>(a.max_id);
  p.put<std::uint64_t>(12 + a.ncolumns());
  put_array(p, "id", a.id, 1, a.n, false);
  put_array(p, "type", a.type, 1, a.n, false);
  put_array(p, "mask", a.mask, 1, a.n, false);
  put_array(p, "x", a.x, 3, a.n, false);
  put_array(p, "v", a.v, 3, a.n, false);
  put_array(p, "f", a.f, 3, a.n, false);
  put_array(p, "omega", a.omega, 3, a.n, false);
  put_array(p, "torque", a.torque, 3, a.n, false);
  put_array(p, "radius", a.radius, 1, a.n, false);
  put_array(p, "rmass", a.rmass, 1, a.n, false);
  put_array(p, "density", a.density, 1, a.n, false);
  put_array(p, "image", a.image, 3, a.n, false);
  Atoms& mut = const_cast<Atoms&>(a);  // column() has no const overload
  for (int c = 0; c < a.ncolumns(); ++c) put_array(p, a.column_name(c), mut.column(c), a.column_stride(c), a.n, true);
  return p.bytes;
}

// Several ranks: every rank's grains on rank 0 (in id order: the file does not depend
// on the rank count), with every column; other ranks get nothing.
void gather_atoms(const Simulation& sim, Atoms& out) {
  const Atoms& a = sim.atoms;
  std::vector<double> mine, all;
  for (std::size_t i = 0; i < a.n; ++i) a.pack(i, mine);
  sim.comm.gather(mine, all);
  for (int c = 0; c < a.ncolumns(); ++c) out.add_column(a.column_name(c), a.column_stride(c));
  out.ntypes = a.ntypes;
  out.max_id = static_cast<long>(sim.comm.highest(static_cast<double>(a.max_id)));
  if (sim.comm.rank() != 0) return;
  const std::size_t rec = a.record_size(), n = all.size() / rec;
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.unpack(i, all.data() + i * rec);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return out.id[p] < out.id[q]; });
  out.permute(order);
}

// Several ranks: every rank's rows of `h` on rank 0, after its own; a pair across two
// ranks is kept once, as (lower id, higher id) (each rank holds it from its side).
void gather_rows(const Simulation& sim, HistoryStore& h, const std::vector<char>& flip, bool pairs) {
  std::vector<std::vector<double>> out(1);
  HistoryStore copy = h;
  copy.migrate([](long) { return 0; }, flip, out);  // every row as a record for "rank 0"
  std::vector<double> all;
  sim.comm.gather(out[0], all);
  if (sim.comm.rank() != 0) return;
  HistoryStore merged;
  merged.configure(h.size());
  merged.receive(all.data(), all.size() / merged.record_size());
  if (pairs) {
    std::map<std::pair<long, long>, std::size_t> best;  // per pair: its row, the (lower, higher) one if any
    for (std::size_t r = 0; r < merged.count(); ++r) {
      const auto k = merged.key(r);
      const auto [at, fresh] = best.emplace(std::pair{std::min(k.tag, k.partner), std::max(k.tag, k.partner)}, r);
      if (!fresh && k.tag < k.partner) at->second = r;
    }
    HistoryStore kept;
    kept.configure(h.size());
    for (std::size_t r = 0; r < merged.count(); ++r)
      if (const auto k = merged.key(r); best[{std::min(k.tag, k.partner), std::max(k.tag, k.partner)}] == r) {
        kept.resize(kept.count() + 1);
        kept.set_key(kept.count() - 1, merged.key(r));
        std::copy_n(merged.row(r), h.size(), kept.row(kept.count() - 1));
      }
    merged = std::move(kept);
  }
  h = std::move(merged);
}

// Pair model and the history of touching contacts, keyed by atom ids. After
// read_restart and before the first run, the contacts are still pending: keep them.
std::string pair_section(Simulation& sim, std::size_t& ncontacts) {
  Packer p;
  const auto& pending = sim.restart;
  std::vector<HistorySlot> slots;
  HistoryStore c;
  std::string model;
  if (pending.contacts.count() > 0) {
    model = pending.pair_model;
    slots = pending.slots;
    c = pending.contacts;
  } else if (sim.pair) {
    model = sim.pair->describe();
    if (ContactStore* store = sim.pair->history()) {
      slots = store->slots;
      c = store->touching(sim.neighbor.list, sim.neighbor.built_ids());
      if (sim.comm.distributed) {
        std::vector<char> flip;
        for (const HistorySlot& s : slots) flip.push_back(s.flip);
        gather_rows(sim, c, flip, true);
      }
    }
  }
  p.put_string(model);
  p.put<std::uint64_t>(slots.size());
  for (auto& s : slots) {
    p.put_string(s.name);
    p.put<std::uint8_t>(s.flip);
  }
  c.write(p);
  ncontacts = c.count();
  return p.bytes;
}

std::string fixes_section(const Simulation& sim, std::size_t& nstates) {
  std::vector<std::array<std::string, 3>> states;  // id, style, bytes
  for (auto& f : sim.fixes) {
    std::string bytes;
    if (f->write_state(bytes)) states.push_back({f->id, f->style, bytes});
  }
  for (auto& [id, st] : sim.restart.fix_states)  // read but not yet claimed: pass them on
    if (!sim.find_fix(id)) states.push_back({id, st.style, st.bytes});
  Packer p;
  p.put<std::uint64_t>(states.size());
  for (auto& s : states)
    for (auto& w : s) p.put_string(w);
  nstates = states.size();
  return p.bytes;
}

// Write to a temporary file next to `path`, then rename: readers see the old file or the new one.
// A missing folder on the way is made, as LIGGGHTS does (the ParScale tutorial writes
// post/restart/ into a folder that has only post/).
void write_atomically(const std::string& path, const std::string& bytes) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::exists(parent, ec)) std::filesystem::create_directories(parent, ec);
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) fail("cannot write restart file '" + path + "': " + std::strerror(errno));
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      fail("writing restart file '" + path + "' failed: " + why);
    }
    done += static_cast<std::size_t>(w);
  }
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    fail("cannot write restart file '" + path + "': " + why);
  }
}

// The sections of a restart file by name, after checking header, byte order and hash.
std::map<std::string, std::string> read_sections(const std::string& path) {
  const std::string what = "restart file '" + path + "'";
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(what + " cannot be opened: " + std::strerror(errno));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.compare(0, kMagic.size(), kMagic) != 0) {
    if (bytes.size() < kMagic.size() && kMagic.compare(0, bytes.size(), bytes) == 0)
      fail(what + " is truncated: it ends inside its 'SABLE RESTART' header");
    const std::string head = bytes.substr(0, 256);
    const std::size_t v = head.find("Version ");
    if (head.find("LIGGGHTS") != std::string::npos || head.find("LAMMPS") != std::string::npos)
      fail(what + " is a LIGGGHTS/LAMMPS restart file (" +
           (v == std::string::npos ? std::string("binary") : std::string(head.c_str() + v)) +
           "), not a sable one: sable reads only files written by its own write_restart");
    fail(what + " is not a sable restart file: it does not start with 'SABLE RESTART' (wrong file name?)");
  }
  const std::size_t eol = bytes.find('\n', kMagic.size());
  if (eol == std::string::npos) fail(what + " is truncated: it ends inside its header");
  const std::string line = bytes.substr(kMagic.size(), eol - kMagic.size());
  long format = 0;
  if (line.rfind("format ", 0) != 0 || !parse_long(line.substr(7), format))
    fail(what + " has a damaged header: expected 'format N' on its second line, found '" + line.substr(0, 40) + "'");
  if (format != static_cast<long>(kFormat))
    fail(what + " has restart format " + std::to_string(format) + ", but this sable reads format " +
         std::to_string(kFormat) + " (read it with the sable version that wrote it)");
  const std::size_t body = eol + 1;
  const std::string rest = bytes.substr(body);  // Unpacker points into it
  Unpacker u(rest, what);
  const auto order = u.get<std::uint32_t>();
  if (order != kByteOrder)
    fail(what + (order == 0x04030201 ? " was written on a machine with the other byte order"
                                     : " has a damaged byte-order mark"));
  std::map<std::string, std::string> sections;
  while (u.left() > 0) {
    const std::size_t at = bytes.size() - u.left();
    const std::string name = u.get_string();
    std::string payload = u.get_string();
    if (name == "end") {
      Unpacker e(payload, what + ", section 'end'");
      if (e.get<std::uint64_t>() != fnv1a(bytes.data(), at))
        fail(what + " is corrupt: its checksum does not match its contents");
      return sections;
    }
    sections[name] = std::move(payload);
  }
  fail(what + " is truncated: it ends before its 'end' section (was the writer killed, or the copy incomplete?)");
}

const std::string& need(const std::map<std::string, std::string>& s, const std::string& name, const std::string& path) {
  auto it = s.find(name);
  if (it == s.end()) fail("restart file '" + path + "' has no '" + name + "' section");
  return it->second;
}

template <class T>
void get_array(Unpacker& u, Kind kind, int stride, int want_stride, std::vector<T>& out, std::size_t n,
               const std::string& what) {
  if (kind != kind_of<T>() || stride != want_stride)
    fail(what + ": unexpected element type or stride " + std::to_string(stride));
  std::vector<T> v = u.get_vector<T>();
  if (v.size() != n * stride)
    fail(what + ": " + std::to_string(v.size()) + " values for " + std::to_string(n) + " atoms");
  out = std::move(v);
}

void read_atoms(Simulation& sim, const std::string& bytes, const std::string& path,
                const std::vector<std::uint32_t>& group_bit) {
  const std::string what = "restart file '" + path + "', section 'atoms'";
  Unpacker u(bytes, what);
  Atoms& a = sim.atoms;
  const std::size_t n = u.get<std::uint64_t>();
  const long max_id = u.get<std::int64_t>();
  const std::size_t narrays = u.get<std::uint64_t>();
  a.resize(n);
  std::map<std::string, bool> seen;
  for (std::size_t q = 0; q < narrays; ++q) {
    const std::string name = u.get_string();
    const Kind kind = static_cast<Kind>(u.get<std::uint8_t>());
    const int stride = u.get<std::int32_t>();
    const bool column = u.get<std::uint8_t>();
    const std::string aw = what + ", array '" + name + "'";
    if (column) {
      if (stride < 1) fail(aw + ": stride " + std::to_string(stride));
      const int h = a.add_column(name, stride);  // a fix defined later re-attaches by name
      get_array(u, kind, stride, stride, a.column(h), n, aw);
      continue;
    }
    seen[name] = true;
    if (name == "id")
      get_array(u, kind, stride, 1, a.id, n, aw);
    else if (name == "type")
      get_array(u, kind, stride, 1, a.type, n, aw);
    else if (name == "mask")
      get_array(u, kind, stride, 1, a.mask, n, aw);
    else if (name == "x")
      get_array(u, kind, stride, 3, a.x, n, aw);
    else if (name == "v")
      get_array(u, kind, stride, 3, a.v, n, aw);
    else if (name == "f")
      get_array(u, kind, stride, 3, a.f, n, aw);
    else if (name == "omega")
      get_array(u, kind, stride, 3, a.omega, n, aw);
    else if (name == "torque")
      get_array(u, kind, stride, 3, a.torque, n, aw);
    else if (name == "radius")
      get_array(u, kind, stride, 1, a.radius, n, aw);
    else if (name == "rmass")
      get_array(u, kind, stride, 1, a.rmass, n, aw);
    else if (name == "density")
      get_array(u, kind, stride, 1, a.density, n, aw);
    else if (name == "image")
      get_array(u, kind, stride, 3, a.image, n, aw);
    else {
      sim.warn(aw + " is unknown to this sable and is skipped");
      if (kind == kF64)
        u.get_vector<double>();
      else if (kind == kI64)
        u.get_vector<long>();
      else
        u.get_vector<std::uint32_t>();  // 4-byte kinds
    }
  }
  for (const char* req : {"id", "type", "mask", "x", "v", "omega", "radius", "rmass", "density", "image"})
    if (!seen[req]) fail(what + " lacks the per-atom array '" + std::string(req) + "'");
  // Group bits of the file -> bits of this simulation (equal unless groups existed before).
  for (auto& m : a.mask) {
    std::uint32_t out = 0;
    for (std::size_t g = 0; g < group_bit.size(); ++g)
      if (m & (1u << g)) out |= group_bit[g];
    m = out;
  }
  a.max_id = max_id;
  for (long id : a.id)
    if (id <= 0 || id > max_id)
      fail(what + ": atom id " + std::to_string(id) + " outside 1.." + std::to_string(max_id));
}

}  // namespace

void write(Simulation& sim, const std::string& path) {
  if (!sim.domain.box_exists) fail("no simulation box to write yet (create_box or read_restart first)");
  const Domain& d = sim.domain;
  Packer file;
  file.bytes = kMagic + "format " + std::to_string(kFormat) + "\n";
  file.put(kByteOrder);

  Packer info;
  std::ostringstream text;
  Atoms gathered;  // several ranks: every rank's grains, on rank 0
  if (sim.comm.distributed) gather_atoms(sim, gathered);
  const Atoms& atoms_all = sim.comm.distributed ? gathered : sim.atoms;
  text << "sable restart: step " << sim.step << ", " << atoms_all.n << " atoms, units " << sim.units
       << ", atom_style granular, dimension " << d.dimension;
  info.put_string(text.str());
  put_section(file, "info", info);

  Packer box;
  box.put<std::int32_t>(d.dimension);
  for (int k = 0; k < 3; ++k) box.put<std::uint8_t>(d.periodic[k]);
  for (int k = 0; k < 3; ++k) box.put(d.lo[k]);
  for (int k = 0; k < 3; ++k) box.put(d.hi[k]);
  put_section(file, "box", box);

  Packer grains;  // the mass and inertia convention (dimension 2 grains ..., fix nve/sphere disc)
  grains.put<std::uint8_t>(sim.atoms.area_density);
  grains.put(sim.atoms.inertia_factor);
  put_section(file, "grains", grains);

  Packer time;
  time.put<std::int64_t>(sim.step);
  time.put(sim.time);
  time.put(sim.dt);
  time.put<std::uint8_t>(sim.dt_set);
  put_section(file, "time", time);

  Packer types;
  types.put<std::int32_t>(sim.atoms.ntypes);
  types.put_string(sim.units);
  put_section(file, "types", types);

  Packer groups;
  groups.put<std::uint64_t>(sim.groups.size());
  for (std::size_t g = 0; g < sim.groups.size(); ++g) groups.put_string(sim.groups.name(static_cast<int>(g)));
  put_section(file, "groups", groups);

  Packer atoms;
  atoms.bytes = atoms_section(atoms_all);
  put_section(file, "atoms", atoms);

  std::size_t ncontacts = 0, nstates = 0;
  Packer pair;
  pair.bytes = pair_section(sim, ncontacts);
  put_section(file, "pair", pair);

  Packer fixes;
  {
    // Several ranks: each wall's history of every rank on rank 0 while its state is
    // written, then its own rows again.
    std::vector<std::pair<HistoryStore*, HistoryStore>> own;
    if (sim.comm.distributed)
      for (ContactSource* src : contact_sources(sim)) {
        if (src->contact_kind() == ContactSource::Kind::Pairs) continue;
        for (HistoryStore* h : src->histories_by_grain()) {
          own.emplace_back(h, *h);
          gather_rows(sim, *h, std::vector<char>(static_cast<std::size_t>(h->size()), 0), false);
          h->sort();
        }
      }
    fixes.bytes = fixes_section(sim, nstates);
    for (auto& [h, rows] : own) *h = std::move(rows);
  }
  put_section(file, "fixes", fixes);

  Packer end;
  end.put(fnv1a(file.bytes.data(), file.bytes.size()));
  put_section(file, "end", end);
  if (sim.comm.rank() == 0) write_atomically(path, file.bytes);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "Restart file '%s' written: step %ld, %zu atoms, %zu contacts with history, %zu fix states",
                path.c_str(), sim.step, atoms_all.n, ncontacts, nstates);
  sim.print(buf);
}

void read(Simulation& sim, const std::string& path) {
  if (sim.domain.box_exists)
    fail("the box already exists: read_restart must come before create_box (as in LIGGGHTS), and only once");
  const auto sections = read_sections(path);
  const std::string what = "restart file '" + path + "'";
  auto unpack = [&](const std::string& name) {
    return Unpacker(need(sections, name, path), what + ", section '" + name + "'");
  };

  Unpacker box = unpack("box");
  Domain& d = sim.domain;
  d.dimension = box.get<std::int32_t>();
  if (d.dimension != 2 && d.dimension != 3) fail(what + ": dimension " + std::to_string(d.dimension));
  for (int k = 0; k < 3; ++k) d.periodic[k] = box.get<std::uint8_t>();
  for (int k = 0; k < 3; ++k) d.lo[k] = box.get<double>();
  for (int k = 0; k < 3; ++k) d.hi[k] = box.get<double>();
  sim.atoms.area_density = d.dimension == 2;
  if (sections.count("grains")) {  // files written before it: the 2D default
    Unpacker grains = unpack("grains");
    sim.atoms.area_density = grains.get<std::uint8_t>();
    sim.atoms.inertia_factor = grains.get<double>();
  }

  Unpacker time = unpack("time");
  sim.step = time.get<std::int64_t>();
  sim.time = time.get<double>();
  sim.dt = time.get<double>();
  sim.dt_set = time.get<std::uint8_t>();
  char line[128];
  std::snprintf(line, sizeof line, "timestep %.17g (from restart file)", sim.dt);
  sim.dt_line = line;

  Unpacker types = unpack("types");
  sim.atoms.ntypes = types.get<std::int32_t>();
  const std::string units = types.get_string();
  if (units != sim.units) fail(what + " was written with units " + units + ", this deck uses " + sim.units);

  Unpacker groups = unpack("groups");
  const std::size_t ngroups = groups.get<std::uint64_t>();
  if (ngroups > 32) fail(what + ": " + std::to_string(ngroups) + " groups (32 at most)");
  std::vector<std::uint32_t> group_bit;
  for (std::size_t g = 0; g < ngroups; ++g)
    group_bit.push_back(sim.groups.bit(sim.groups.find_or_create(groups.get_string())));

  read_atoms(sim, need(sections, "atoms", path), path, group_bit);

  auto& pending = sim.restart;
  pending = Simulation::RestartPending{};
  pending.file = path;
  if (sections.count("pair")) {
    Unpacker p = unpack("pair");
    pending.pair_model = p.get_string();
    const std::size_t nslots = p.get<std::uint64_t>();
    for (std::size_t s = 0; s < nslots; ++s) {
      HistorySlot h;
      h.name = p.get_string();
      h.flip = p.get<std::uint8_t>();
      pending.slots.push_back(h);
    }
    pending.contacts.configure(static_cast<int>(nslots));
    if (!pending.contacts.read(p))
      fail(what + ", section 'pair': its contacts do not have " + std::to_string(nslots) + " history values each");
  }
  if (sections.count("fixes")) {
    Unpacker f = unpack("fixes");
    const std::size_t nf = f.get<std::uint64_t>();
    for (std::size_t q = 0; q < nf; ++q) {
      const std::string id = f.get_string();
      Simulation::RestartPending::FixState st;
      st.style = f.get_string();
      st.bytes = f.get_string();
      pending.fix_states[id] = std::move(st);
    }
  }
  d.box_exists = true;

  char buf[512];
  std::snprintf(buf, sizeof buf,
                "Reading restart file '%s': step %ld, %zu atoms, box (%g %g %g) to (%g %g %g), %zu contacts with "
                "history (%s), %zu fix states",
                path.c_str(), sim.step, sim.atoms.n, d.lo[0], d.lo[1], d.lo[2], d.hi[0], d.hi[1], d.hi[2],
                pending.contacts.count(), pending.pair_model.empty() ? "no pair style" : pending.pair_model.c_str(),
                pending.fix_states.size());
  sim.print(buf);
  box_created(sim);
}

std::string summary(const std::string& path) {
  const auto sections = read_sections(path);
  std::string s;
  for (auto& [name, payload] : sections) {
    s += name + " (" + std::to_string(payload.size()) + " bytes)";
    if (name == "info" || name == "pair") s += ": " + Unpacker(payload, name).get_string();
    if (name == "pair") {
      Unpacker p(payload, name);
      p.get_string();
      const std::size_t nslots = p.get<std::uint64_t>();
      s += "; slots";
      for (std::size_t q = 0; q < nslots; ++q) {
        s += ' ';  // two += : GCC 12 warns falsely (-Wrestrict) on " " + string here
        s += p.get_string();
        p.get<std::uint8_t>();
      }
      HistoryStore contacts;
      contacts.configure(static_cast<int>(nslots));
      s += "; " + std::to_string(contacts.read(p) ? contacts.count() : 0) + " contacts";
    }
    if (name == "fixes") {
      Unpacker f(payload, name);
      const std::size_t nf = f.get<std::uint64_t>();
      for (std::size_t q = 0; q < nf; ++q) {
        const std::string id = f.get_string(), style = f.get_string();
        s += q ? ", " : ": ";
        s += id + " (" + style + ", " + std::to_string(f.get_string().size()) + " bytes)";
      }
    }
    s += "\n";
  }
  return s;
}

namespace {

// '*' in a file name stands for the step (write) or the largest step present (read, as LIGGGHTS).
std::string latest_matching(const std::string& pattern, const Args& a) {
  namespace fs = std::filesystem;
  const fs::path p(pattern);
  const std::string name = p.filename().string();
  const std::size_t star = name.find('*');
  if (star == std::string::npos) a.fail(1, "'*' in the file name part, not in a directory name");
  const std::string pre = name.substr(0, star), post = name.substr(star + 1);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  long best = -1;
  std::string found;
  std::error_code ec;
  for (auto& e : fs::directory_iterator(dir, ec)) {
    const std::string f = e.path().filename().string();
    if (f.size() <= pre.size() + post.size() || f.compare(0, pre.size(), pre) != 0 ||
        f.compare(f.size() - post.size(), post.size(), post) != 0)
      continue;
    long step;
    const std::string mid = f.substr(pre.size(), f.size() - pre.size() - post.size());
    if (mid.find_first_not_of("0123456789") != std::string::npos || !parse_long(mid, step)) continue;
    if (step > best) best = step, found = p.has_parent_path() ? (dir / f).string() : f;
  }
  if (best < 0) a.fail(1, "a restart file matching '" + pattern + "' ('*' = a step number); none exists");
  return found;
}

void cmd_write_restart(Simulation& sim, const Args& a) {
  std::string path = a.word(1, "a restart file name");
  if (path.find('%') != std::string::npos) a.fail(1, "a file name without '%' (one process writes one file)");
  for (std::size_t i = 2; i < a.size(); i += 2) {  // LIGGGHTS' MPI file splitting: one process, one file
    if (a[i] != "fileper" && a[i] != "nfile") a.fail(i, "fileper Np or nfile Nf");
    a.integer(i + 1, "a count");
  }
  const std::size_t star = path.find('*');
  if (star != std::string::npos) path.replace(star, 1, std::to_string(sim.step));
  try {
    write(sim, path);
  } catch (const SableError& e) {
    a.fail_line(e.what());
  }
}

void cmd_read_restart(Simulation& sim, const Args& a) {
  std::string path = a.word(1, "a restart file name");
  if (a.size() > 2) a.fail(2, "nothing more (read_restart FILE)");
  if (path.find('*') != std::string::npos) path = latest_matching(path, a);
  try {
    read(sim, path);
  } catch (const SableError& e) {
    a.fail_line(e.what());
  }
}

}  // namespace

SABLE_COMMAND("write_restart", cmd_write_restart);
SABLE_COMMAND("read_restart", cmd_read_restart);

}  // namespace sable::restart
