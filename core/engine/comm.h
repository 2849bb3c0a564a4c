#pragma once
// The processes of a run (LAMMPS' Comm): this rank, the rank count, the processor
// grid laid over the box and this rank's subdomain. Built with MPI (SABLE_HAVE_MPI)
// it reads MPI_COMM_WORLD once MPI is initialised; otherwise it is rank 0 of 1.
// mpi.h stays in comm.cpp: no other source sees MPI.
#include <array>
#include <string>

namespace sable {

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

  // The program's MPI lifetime (app/main.cpp); no-ops without MPI.
  static void init(int* argc, char*** argv);
  static void finalize();
  static bool built_with_mpi();

 private:
  int rank_ = 0, size_ = 1;
};

// A box was created (create_box, read_data, read_restart): choose the grid, print its line.
void box_created(Simulation& sim);

}  // namespace sable
