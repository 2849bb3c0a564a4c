#pragma once
// The processes of a run (LAMMPS' Comm): this rank, the rank count, the processor
// grid laid over the box and this rank's subdomain. Built with MPI (SABLE_HAVE_MPI)
// it reads MPI_COMM_WORLD once MPI is initialised; otherwise it is rank 0 of 1.
// mpi.h stays in comm.cpp: no other source sees MPI.
#include <array>
#include <string>
#include <vector>

namespace sable {

class Atoms;
class Domain;
class Simulation;

using Grid = std::array<int, 3>;

// The factorisation Px*Py*Pz = ranks with the least subdomain surface for a box of
// these edge lengths (LAMMPS' default for `processors * * *`): `fixed` holds the
// deck's explicit counts (0 where '*'); in 2D, Pz = 1 and the perimeter counts.
// Ties go to the first in the order Px, then Py, ascending. {0,0,0}: none exists.
Grid choose_grid(int ranks, const std::array<double, 3>& length, const Grid& fixed, int dimension);

class Comm {
 public:
  Comm();                    // MPI_COMM_WORLD's place when MPI is up, else rank 0 of 1
  Comm(int rank, int size);  // a given place (tests)

  int rank() const { return rank_; }
  int size() const { return size_; }

  // The deck's `processors Px Py Pz` (0 for '*') and where it stood, for later errors.
  Grid requested{0, 0, 0};
  std::string requested_at;

  // Set by decompose(): the grid, this rank's place in it (x fastest: rank =
  // cx + Px (cy + Py cz)) and its subdomain, a regular split of the box.
  Grid grid{1, 1, 1};
  Grid coord{0, 0, 0};
  double sublo[3] = {0, 0, 0}, subhi[3] = {0, 0, 0};

  // Chooses the grid for the new box and this rank's subdomain in it.
  void decompose(const Domain& box);
  // This rank's subdomain of `box` on the current grid (again after the box changes:
  // shrink-wrapped faces). Neighbouring subdomains share their face to the bit.
  void split(const Domain& box);
  // LAMMPS' line after the box is created: "  1 by 1 by 1 MPI processor grid".
  std::string grid_line() const;

  // Collective over the ranks (every rank calls them in the same order); on one
  // rank they return their argument.
  void sum(double* v, int count) const;
  double sum(double v) const;
  long sum(long v) const;
  double max(double v) const;
  double min(double v) const;
  bool any(bool b) const;
  // Over the atoms of all ranks: reduced once the atoms are split (distributed),
  // the value itself before (every rank then holds every atom).
  double total(double v) const { return distributed ? sum(v) : v; }
  long total(long v) const { return distributed ? sum(v) : v; }
  void total(double* v, int count) const {
    if (distributed) sum(v, count);
  }
  double highest(double v) const { return distributed ? max(v) : v; }
  double lowest(double v) const { return distributed ? min(v) : v; }
  // All to all: out[r] goes to rank r; in gets what every rank sent here, in rank
  // order, from[r] doubles from rank r. With `known`, from already holds the counts.
  void all_to_all(const std::vector<std::vector<double>>& out, std::vector<double>& in, std::vector<int>& from,
                  bool known = false) const;
  // Rank 0 gets every rank's `mine`, in rank order (other ranks: `all` left empty).
  void gather(const std::vector<double>& mine, std::vector<double>& all) const;
  // Every rank gets every rank's `mine`, in rank order.
  void all_gather(const std::vector<double>& mine, std::vector<double>& all) const;
  // Ends every rank now (an error met by this rank alone, after the atoms were split).
  [[noreturn]] static void abort(int status);

  // ---- The atoms split over the ranks (core/engine/comm_atoms.cpp) ----
  // False until the first run's set-up: every rank then holds every atom (the deck's
  // set-up commands run on each rank alike); from it on, each rank owns the atoms in
  // its subdomain and holds ghost copies of those within the cutoff of it.
  bool distributed = false;
  bool decomposed() const { return size_ > 1; }
  // The rank whose subdomain holds position x (inside the box).
  int owner_of(const double* x, const Domain& box) const;
  // At a neighbour rebuild with several ranks (Simulation::rebuild_decomposed): the
  // owned atoms remapped into the box and sent to the rank that owns their position,
  // with their contact history (the pair's saved rows, each wall's store); the first
  // time, each rank keeps its own and drops the rest.
  void exchange(Simulation& sim);
  // Ghost copies of owned atoms within `cutoff` of a neighbouring subdomain, shifted
  // across periodic faces; appended at [n, n + nghost) on the receiving rank.
  void borders(Simulation& sim, double cutoff);
  // Before each force pass: the ghosts' positions, velocities and spins from their owners.
  void forward(Atoms& atoms) const;
  // Boundary c of n slices of [lo, hi]: the ends exactly, so that subdomains tile the box.
  static double face(double lo, double hi, int c, int n);
  // The grid's cut c along axis k in `box`: uniform, or where `balance` moved it
  // (cut[k]: fractions of the box, one per inner cut; empty: uniform).
  std::array<std::vector<double>, 3> cut;
  double face_at(const Domain& box, int k, int c) const;
  // `balance ... shift`: the inner cuts along the axes of `dims` ("xyz" letters) moved to
  // where the grains split evenly, no slab thinner than `min_width`; every rank alike.
  void balance_shift(Simulation& sim, const std::string& dims, double min_width);
  // The grains each rank owns, or would own at the current cuts (every rank alike), and
  // the imbalance factor of such counts (the most over the mean).
  std::vector<double> grains_per_rank(const Simulation& sim) const;
  static double imbalance(const std::vector<double>& per_rank);
  // `balance`/`fix balance`: the imbalance now, and, when above thresh, the cuts shifted;
  // returns {before, after} (after = before when nothing moved).
  std::array<double, 2> rebalance(Simulation& sim, double thresh, const std::string& dims);

  // The program's MPI lifetime (app/main.cpp); no-ops without MPI.
  static void init(int* argc, char*** argv);
  static void finalize();
  static bool built_with_mpi();

 private:
  int rank_ = 0, size_ = 1;
  int rank_at(const Grid& c) const { return c[0] + grid[0] * (c[1] + grid[1] * c[2]); }
  // borders(): per rank, the owned atoms it holds as ghosts and their periodic shifts;
  // the ghosts received from each rank, counted (they lie in rank order).
  struct Sent {
    std::vector<int> atom;
    std::vector<double> shift;  // 3 per atom
  };
  std::vector<Sent> sent_;
  std::vector<int> ghosts_from_;
};

// A box was created (create_box, read_data, read_restart): choose the grid, print its line.
void box_created(Simulation& sim);

}  // namespace sable
