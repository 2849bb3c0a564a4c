// region ID mesh/tet file F scale S move dx dy dz rotate ax ay az [side in|out] [units box]
// (LIGGGHTS): the inside of a tetrahedral mesh read from a legacy ASCII VTK
// unstructured grid. Cells other than tetrahedra (VTK type 10: Gmsh also writes
// the surface triangles, edges and vertices) are skipped. As LIGGGHTS documents
// it: the offset first, then the scale, then rotations about x, y and z (degrees).
// Points on faces are outside (in_tet).
// Coordinates are in box units whatever `units` says (the file sets them).
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "core/geometry/region.h"
#include "core/input/style_registry.h"

namespace sable {

class RegionMeshTet : public Region {
 public:
  RegionMeshTet(Simulation& s, const Args& a) : Region(s, a) {
    a.need(15, "region ID mesh/tet file F scale S move dx dy dz rotate ax ay az");
    expect(a, 3, "file");
    expect(a, 5, "scale");
    expect(a, 7, "move");
    expect(a, 11, "rotate");
    parse_options(a, 15);
    const double scale = a.num(6, "the scale factor");
    if (!(scale > 0) || !std::isfinite(scale)) a.fail(6, "a scale factor > 0");
    double move[3], angle[3];
    for (int k = 0; k < 3; ++k) {
      move[k] = a.num(8 + k, "an offset");
      angle[k] = a.num(12 + k, "a rotation angle in degrees");
      if (!std::isfinite(move[k])) a.fail(8 + k, "a finite offset");
      if (!std::isfinite(angle[k])) a.fail(12 + k, "a finite angle");
    }
    std::vector<double> pts;
    read_vtk(a, a.word(4, "a VTK file name"), pts);
    for (std::size_t p = 0; p < pts.size(); p += 3) place(&pts[p], move, scale, angle);
    build(a, pts);
  }

  bool inside(const double* x) const override {
    for (int k = 0; k < 3; ++k)
      if (x[k] < lo[k] || x[k] > hi[k]) return false;
    for (const Tet& t : tets_)
      if (in_tet(t, x)) return true;
    return false;
  }
  double volume() const override { return volume_; }

 private:
  struct Tet {
    double v[4][3];
    double lo[3], hi[3];
  };
  std::vector<Tet> tets_;
  double volume_ = 0.0;

  static void expect(const Args& a, std::size_t i, const char* kw) {
    if (a[i] != kw) a.fail(i, std::string("'") + kw + "' (LIGGGHTS' obligatory keyword order: file scale move rotate)");
  }

  // Offset, scale, then rotations about x, y, z.
  static void place(double* p, const double* move, double scale, const double* angle) {
    for (int k = 0; k < 3; ++k) p[k] = (p[k] + move[k]) * scale;
    for (int ax = 0; ax < 3; ++ax) {
      const double t = angle[ax] * std::numbers::pi / 180.0, c = std::cos(t), s = std::sin(t);
      const int i = (ax + 1) % 3, j = (ax + 2) % 3;
      const double u = p[i], w = p[j];
      p[i] = c * u - s * w;
      p[j] = s * u + c * w;
    }
  }

  static double signed_volume(const double* a, const double* b, const double* c, const double* d) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) /
           6.0;
  }

  // Strictly inside: each of the four sub-volumes with x in place of a corner has
  // the whole tet's sign, beyond round-off. As in LIGGGHTS 3.8, a point on a face
  // (outer or shared by two tets) is outside: its mesh_tet tutorial then creates
  // the same 13 121 lattice grains.
  static bool in_tet(const Tet& t, const double* x) {
    for (int k = 0; k < 3; ++k)
      if (x[k] < t.lo[k] || x[k] > t.hi[k]) return false;
    const double whole = signed_volume(t.v[0], t.v[1], t.v[2], t.v[3]);
    const double tol = 1e-12 * std::fabs(whole);
    const double s = whole > 0 ? 1.0 : -1.0;
    return s * signed_volume(x, t.v[1], t.v[2], t.v[3]) > tol && s * signed_volume(t.v[0], x, t.v[2], t.v[3]) > tol &&
           s * signed_volume(t.v[0], t.v[1], x, t.v[3]) > tol && s * signed_volume(t.v[0], t.v[1], t.v[2], x) > tol;
  }

  void read_vtk(const Args& a, const std::string& name, std::vector<double>& pts) {
    std::ifstream in(name);
    if (!in) a.fail(4, "a readable VTK file (cannot open '" + name + "')");
    std::string word;
    std::vector<long> cells, types;
    long ncells = -1;
    while (in >> word) {
      if (word == "POINTS") {
        long n;
        std::string type;
        if (!(in >> n >> type) || n < 0) a.fail(4, "a VTK file with 'POINTS n type' ('" + name + "')");
        pts.resize(3 * static_cast<std::size_t>(n));
        for (double& v : pts)
          if (!(in >> v)) a.fail(4, "a VTK file with n points after POINTS ('" + name + "' ends early)");
      } else if (word == "CELLS") {
        long size;
        if (!(in >> ncells >> size) || ncells < 0 || size < 0) a.fail(4, "a VTK file with 'CELLS n size' ('" + name + "')");
        cells.resize(static_cast<std::size_t>(size));
        for (long& v : cells)
          if (!(in >> v)) a.fail(4, "a VTK file with its CELLS list complete ('" + name + "' ends early)");
      } else if (word == "CELL_TYPES") {
        long n;
        if (!(in >> n) || n != ncells) a.fail(4, "a VTK file whose CELL_TYPES count equals its CELLS count ('" + name + "')");
        types.resize(static_cast<std::size_t>(n));
        for (long& v : types)
          if (!(in >> v)) a.fail(4, "a VTK file with its CELL_TYPES list complete ('" + name + "' ends early)");
      } else if (word == "BINARY") {
        a.fail(4, "an ASCII VTK file ('" + name + "' is binary)");
      }
    }
    if (pts.empty() || types.empty()) a.fail(4, "a VTK unstructured grid with POINTS, CELLS and CELL_TYPES ('" + name + "')");
    const long npts = static_cast<long>(pts.size() / 3);
    std::size_t at = 0;
    for (long type : types) {
      if (at >= cells.size()) a.fail(4, "a VTK file whose CELLS sizes match its list ('" + name + "')");
      const long nv = cells[at];
      if (nv < 0 || at + 1 + static_cast<std::size_t>(nv) > cells.size())
        a.fail(4, "a VTK file whose CELLS sizes match its list ('" + name + "')");
      if (type == 10) {
        if (nv != 4) a.fail(4, "tetrahedra (VTK type 10) of 4 points ('" + name + "')");
        for (int c = 0; c < 4; ++c)
          if (cells[at + 1 + c] < 0 || cells[at + 1 + c] >= npts) a.fail(4, "point indices below POINTS' count ('" + name + "')");
        corners_.insert(corners_.end(), cells.begin() + static_cast<long>(at) + 1, cells.begin() + static_cast<long>(at) + 5);
      }
      at += 1 + static_cast<std::size_t>(nv);
    }
    if (corners_.empty()) a.fail(4, "a VTK file with tetrahedra (VTK cell type 10) ('" + name + "' has none)");
  }

  void build(const Args& a, const std::vector<double>& pts) {
    for (int k = 0; k < 3; ++k) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (std::size_t c = 0; c < corners_.size(); c += 4) {
      Tet t;
      for (int k = 0; k < 3; ++k) t.lo[k] = INFINITY, t.hi[k] = -INFINITY;
      for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) {
          t.v[v][k] = pts[3 * static_cast<std::size_t>(corners_[c + v]) + k];
          t.lo[k] = std::min(t.lo[k], t.v[v][k]);
          t.hi[k] = std::max(t.hi[k], t.v[v][k]);
        }
      const double vol = std::fabs(signed_volume(t.v[0], t.v[1], t.v[2], t.v[3]));
      if (!(vol > 0)) continue;  // a flat tet holds nothing
      volume_ += vol;
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], t.lo[k]), hi[k] = std::max(hi[k], t.hi[k]);
      tets_.push_back(t);
    }
    if (tets_.empty()) a.fail(4, "a VTK file with tetrahedra of non-zero volume");
    corners_.clear();
  }
  std::vector<long> corners_;
};

SABLE_REGION("mesh/tet", RegionMeshTet);

}  // namespace sable
