// The processor grid and this rank's subdomain (core/engine/comm.h).
#include "core/engine/comm.h"

#ifdef SABLE_HAVE_MPI
#include <mpi.h>
#endif

#include <cstdlib>

#include "core/engine/domain.h"
#include "core/engine/error.h"
#include "core/engine/simulation.h"

namespace sable {
namespace {

// Surface of one subdomain (a constant factor of the total, which is what matters):
// in 2D its perimeter in the xy plane.
double subdomain_surface(const std::array<double, 3>& length, const Grid& g, int dimension) {
  const double a = length[0] / g[0], b = length[1] / g[1], c = length[2] / g[2];
  return dimension == 2 ? a + b : a * b + b * c + c * a;
}

bool fits(int count, int fixed) { return fixed == 0 || count == fixed; }

}  // namespace

Grid choose_grid(int ranks, const std::array<double, 3>& length, const Grid& fixed, int dimension) {
  Grid best{0, 0, 0};
  double best_surface = 0;
  for (int px = 1; px <= ranks; ++px) {
    if (ranks % px || !fits(px, fixed[0])) continue;
    for (int py = 1; py <= ranks / px; ++py) {
      if ((ranks / px) % py || !fits(py, fixed[1])) continue;
      const Grid g{px, py, ranks / px / py};
      if (!fits(g[2], fixed[2]) || (dimension == 2 && g[2] != 1)) continue;
      const double s = subdomain_surface(length, g, dimension);
      // equal surfaces in other orders of the same sum differ in the last bit: keep the first
      if (best[0] == 0 || s < best_surface * (1 - 1e-12)) best = g, best_surface = s;
    }
  }
  return best;
}

#ifdef SABLE_HAVE_MPI
namespace {
bool mpi_up() {
  int up = 0, down = 0;
  MPI_Initialized(&up);
  MPI_Finalized(&down);
  return up && !down;
}

// A launcher's mark (OpenMPI's mpirun, PMIx/PMI launchers such as srun or hydra, MVAPICH).
bool launched() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "MV2_COMM_WORLD_SIZE"})
    if (std::getenv(var)) return true;
  return false;
}
}  // namespace

Comm::Comm() {
  if (!mpi_up()) return;  // unit tests and tools that never start MPI: one process
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

// Started directly, sable is one process and never calls MPI: OpenMPI's singleton start
// (a helper daemon, transport probing) costs ~0.4 s of wall time per run (docs/running.md).
void Comm::init(int* argc, char*** argv) {
  if (!launched()) return;
  int provided = 0;  // threads run inside a rank; only the main thread will call MPI
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
}

void Comm::finalize() {
  if (mpi_up()) MPI_Finalize();
}

bool Comm::built_with_mpi() { return true; }
#else
Comm::Comm() = default;
void Comm::init(int*, char***) {}
void Comm::finalize() {}
bool Comm::built_with_mpi() { return false; }
#endif

Comm::Comm(int rank, int size) : rank_(rank), size_(size) {}

double Comm::face(double lo, double hi, int c, int n) {
  if (c == 0) return lo;
  if (c == n) return hi;
  return lo + (hi - lo) * (static_cast<double>(c) / n);
}

#ifdef SABLE_HAVE_MPI
// A Comm made for a test (or before MPI starts) reduces nothing.
#define SABLE_MPI_ACTIVE (size_ > 1 && mpi_up())
void Comm::sum(double* v, int count) const {
  if (SABLE_MPI_ACTIVE) MPI_Allreduce(MPI_IN_PLACE, v, count, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}
long Comm::sum(long v) const {
  if (SABLE_MPI_ACTIVE) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return v;
}
double Comm::max(double v) const {
  if (SABLE_MPI_ACTIVE) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return v;
}
double Comm::min(double v) const {
  if (SABLE_MPI_ACTIVE) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  return v;
}
bool Comm::any(bool b) const {
  int v = b;
  if (SABLE_MPI_ACTIVE) MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
  return v != 0;
}
void Comm::all_to_all(const std::vector<std::vector<double>>& out, std::vector<double>& in, std::vector<int>& from,
                      bool known) const {
  if (!SABLE_MPI_ACTIVE) {
    in = out.empty() ? std::vector<double>{} : out[0];
    from.assign(1, static_cast<int>(in.size()));
    return;
  }
  std::vector<int> to(size_), sdispl(size_ + 1, 0), rdispl(size_ + 1, 0);
  for (int r = 0; r < size_; ++r) to[r] = static_cast<int>(out[r].size());
  if (!known) {
    from.assign(size_, 0);
    MPI_Alltoall(to.data(), 1, MPI_INT, from.data(), 1, MPI_INT, MPI_COMM_WORLD);
  }
  std::vector<double> flat;
  for (int r = 0; r < size_; ++r) {
    sdispl[r + 1] = sdispl[r] + to[r];
    rdispl[r + 1] = rdispl[r] + from[r];
    flat.insert(flat.end(), out[r].begin(), out[r].end());
  }
  in.resize(static_cast<std::size_t>(rdispl[size_]));
  MPI_Alltoallv(flat.data(), to.data(), sdispl.data(), MPI_DOUBLE, in.data(), from.data(), rdispl.data(), MPI_DOUBLE,
                MPI_COMM_WORLD);
}
void Comm::gather(const std::vector<double>& mine, std::vector<double>& all) const {
  if (!SABLE_MPI_ACTIVE) {
    all = mine;
    return;
  }
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(rank_ == 0 ? size_ : 0), displ(rank_ == 0 ? size_ + 1 : 0, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (rank_ == 0) {
    for (int r = 0; r < size_; ++r) displ[r + 1] = displ[r] + counts[r];
    all.resize(static_cast<std::size_t>(displ[size_]));
  } else {
    all.clear();
  }
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), displ.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
}
void Comm::all_gather(const std::vector<double>& mine, std::vector<double>& all) const {
  if (!SABLE_MPI_ACTIVE) {
    all = mine;
    return;
  }
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(size_), displ(size_ + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < size_; ++r) displ[r + 1] = displ[r] + counts[r];
  all.resize(static_cast<std::size_t>(displ[size_]));
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), displ.data(), MPI_DOUBLE, MPI_COMM_WORLD);
}
void Comm::abort(int status) {
  if (mpi_up()) MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}
#undef SABLE_MPI_ACTIVE
#else
void Comm::sum(double*, int) const {}
long Comm::sum(long v) const { return v; }
double Comm::max(double v) const { return v; }
double Comm::min(double v) const { return v; }
bool Comm::any(bool b) const { return b; }
void Comm::all_to_all(const std::vector<std::vector<double>>& out, std::vector<double>& in, std::vector<int>& from,
                      bool) const {
  in = out.empty() ? std::vector<double>{} : out[0];
  from.assign(1, static_cast<int>(in.size()));
}
void Comm::gather(const std::vector<double>& mine, std::vector<double>& all) const { all = mine; }
void Comm::all_gather(const std::vector<double>& mine, std::vector<double>& all) const { all = mine; }
void Comm::abort(int status) { std::exit(status); }
#endif
double Comm::sum(double v) const {
  sum(&v, 1);
  return v;
}

void Comm::decompose(const Domain& box) {
  const std::array<double, 3> length{box.length(0), box.length(1), box.length(2)};
  if (box.dimension == 2 && requested[2] > 1)
    fail(requested_at + ": Pz = " + std::to_string(requested[2]) + " in a 2D box: expected 1 or *");
  grid = choose_grid(size_, length, requested, box.dimension);
  if (grid[0] == 0)  // `processors` checked the counts against the ranks: only 2D can leave none
    fail(requested_at + ": no grid of " + std::to_string(size_) + " ranks with Pz = 1 fits these counts");
  coord = {rank_ % grid[0], rank_ / grid[0] % grid[1], rank_ / (grid[0] * grid[1])};
  for (auto& c : cut) c.clear();
  split(box);
}

void Comm::split(const Domain& box) {
  for (int k = 0; k < 3; ++k) {
    sublo[k] = face_at(box, k, coord[k]);
    subhi[k] = face_at(box, k, coord[k] + 1);
  }
}

double Comm::face_at(const Domain& box, int k, int c) const {
  const double lo = box.lo[k], hi = box.hi[k];
  if (cut[k].empty() || c == 0 || c == grid[k]) return face(lo, hi, c, grid[k]);
  return lo + (hi - lo) * cut[k][static_cast<std::size_t>(c - 1)];
}

std::string Comm::grid_line() const {
  return "  " + std::to_string(grid[0]) + " by " + std::to_string(grid[1]) + " by " + std::to_string(grid[2]) +
         " MPI processor grid";
}

void box_created(Simulation& sim) {
  sim.comm.decompose(sim.domain);
  sim.print(sim.comm.grid_line());
}

}  // namespace sable
