#pragma once
// Per-atom state as a structure of arrays (vectors stored xyz-interleaved per
// quantity). Fixes may attach extra per-atom columns; every column follows the
// atoms through sorting, deletion and growth.
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "core/engine/threads.h"

namespace sable {

class Atoms {
 public:
  Atoms();
  std::size_t n = 0;  // owned atoms (one rank: all atoms), at [0, n)
  // Several ranks: copies of other ranks' atoms near this subdomain at [n, n + nghost)
  // in every column (core/engine/comm_atoms.cpp). Every pass runs over [0, n); only
  // the neighbour list and the pair pass read ghosts.
  std::size_t nghost = 0;
  std::size_t nall() const { return n + nghost; }
  std::vector<long> id;
  std::vector<int> type;
  std::vector<std::uint32_t> mask;  // group bits
  std::vector<double> x, v, f;      // 3 per atom
  std::vector<double> omega, torque;
  std::vector<double> radius, rmass, density;
  std::vector<int> image;  // 3 per atom: periodic image counters

  int ntypes = 1;
  // Extra column holding the mass contacts see (rigid bodies: the body's); -1: rmass.
  int mass_override = -1;
  // Extra column: grains with the same nonzero value never pair (the grains of one rigid body).
  int pair_exclusion = -1;

  // Grain shape for mass and moment of inertia, one place for every user
  // (integrators, rigid bodies, damping, erotate): mass = pi r^2 rho when
  // area_density (2D, as LIGGGHTS: `density` is per area), else 4/3 pi r^3 rho;
  // I = inertia_factor m r^2 (2/5 sphere, 1/2 disk). Set by `dimension 2 [grains
  // disks|spheres]` and `fix nve/sphere ... disc` (docs/commands, "2D").
  bool area_density = false;
  double inertia_factor = 0.4;
  double mass_of(double r, double rho) const;
  double inertia(std::size_t i) const { return inertia_factor * rmass[i] * radius[i] * radius[i]; }

  // What the contact kernels may leave out (Simulation::setup decides each run):
  // plane_2d: every grain in the x-y plane, spin about z only (dimension 2);
  // rotation: false when no grain turns (no integrator of spin, all omega 0):
  // contacts then neither read omega nor make torque.
  bool plane_2d = false;
  bool rotation = true;
  long max_id = 0;
  AtomSplit split;  // thread ranges of the per-atom passes (set by the pair pass)

  // Runs body(t, lo, hi) on each thread's range of the atoms (core/engine/threads.h).
  template <class Body>
  void for_ranges(Body&& body) const {
    for_atom_ranges(split, n, body);
  }
  // A pass over a list of scattered atoms (a wall's near grains) at place c
  // asks for the state of the atom a few places ahead (position, radius, mask,
  // velocities, forces, mass): far from each other, they are out of cache in
  // large systems.
  void prefetch_ahead(const std::vector<int>& list, std::size_t c) const {
    constexpr std::size_t kAhead = 16;
    if (c + kAhead >= list.size()) return;
    const std::size_t i = static_cast<std::size_t>(list[c + kAhead]);
    __builtin_prefetch(&x[3 * i]);
    __builtin_prefetch(&radius[i]);
    __builtin_prefetch(&mask[i]);
    __builtin_prefetch(&v[3 * i]);
    __builtin_prefetch(&omega[3 * i]);
    __builtin_prefetch(&f[3 * i]);
    __builtin_prefetch(&torque[3 * i]);
    __builtin_prefetch(&rmass[i]);
  }
  // The atoms i with keep(i), in increasing order, into out: each thread of the
  // atom passes looks at its own range (a fix's search at neighbour builds).
  template <class Keep>
  void select(Keep&& keep, std::vector<int>& out) const {
    std::vector<std::vector<int>> parts(static_cast<std::size_t>(atom_pass_threads()));
    for_ranges([&](int t, std::size_t lo, std::size_t hi) {
      for (std::size_t i = lo; i < hi; ++i)
        if (keep(i)) parts[t].push_back(static_cast<int>(i));
    });
    out.clear();
    for (const std::vector<int>& p : parts) out.insert(out.end(), p.begin(), p.end());
  }

  // Ghosts: drop them all (every column back to n atoms), or append `count` zeroed
  // ones (returns the first's index).
  void drop_ghosts();
  std::size_t add_ghosts(std::size_t count);
  // Every column of atom i as doubles (ids, types, masks and image counters are
  // exact in a double), appended to out; unpack() writes such a record into atom i.
  // Which columns, in which order: for_each_array.
  std::size_t record_size() const;
  void pack(std::size_t i, std::vector<double>& out) const;
  void unpack(std::size_t i, const double* in);

  // Append one atom, returns its index. Mass from density and radius (mass_of).
  std::size_t add(long id, int type, const double xyz[3], double radius, double density);
  void remove_if(const std::vector<char>& doomed);
  void permute(const std::vector<std::size_t>& order);  // new[i] = old[order[i]]
  void set_radius_density(std::size_t i, double r, double rho);
  // The atom with this id, owned if this rank owns it, else a ghost copy; npos when
  // absent (linear map rebuilt lazily).
  std::size_t index_of(long atom_id) const;
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  // Extra per-atom columns (history of walls, fix state): stride doubles per atom.
  // A column of the same name is re-attached, not duplicated: a fix defined again
  // with the same ID (after read_restart, or replacing itself) finds its data.
  // With a different stride the old data is meaningless and the column restarts at init.
  int add_column(const std::string& name, int stride, double init = 0.0);
  std::vector<double>& column(int handle) { return extra_[handle].data; }
  const std::vector<double>& column(int handle) const { return extra_[handle].data; }
  int column_stride(int handle) const { return extra_[handle].stride; }
  int ncolumns() const { return static_cast<int>(extra_.size()); }
  const std::string& column_name(int handle) const { return extra_[handle].name; }
  int find_column(const std::string& name) const;  // -1 when absent
  // Set the atom count, growing (new entries zero, extra columns at init) or shrinking every array.
  void resize(std::size_t count);
  void clear_forces();

 private:
  struct Column {
    std::string name;
    int stride;
    double init;
    std::vector<double> data;
  };
  std::vector<Column> extra_;
  // permute()'s buffers, by element type and stride
  std::tuple<std::map<int, std::vector<long>>, std::map<int, std::vector<int>>,
             std::map<int, std::vector<std::uint32_t>>, std::map<int, std::vector<double>>>
      scratch_;
  mutable std::vector<std::size_t> map_;  // id -> index
  mutable bool map_valid_ = false;
  void invalidate() { map_valid_ = false; }
  template <class F>
  void for_each_array(F&& f);
  template <class F>
  void for_each_array(F&& f) const;
};

}  // namespace sable
