#pragma once
// Triangle-mesh walls (LIGGGHTS fix mesh/surface): STL reading, load-time
// transforms, welding and edge adjacency, per-edge/corner "active" flags,
// closest point of a sphere centre on a triangle, a bin grid for near-triangle
// search, rigid motion and the velocity of any surface point.
//
// Geometry is kept in the body frame (the mesh as loaded and transformed at
// load); the rigid pose x_world = R x_body + T moves it. Searches transform
// the query point into the body frame, so a moving mesh never re-bins.
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sable {

using Vec3d = std::array<double, 3>;

class TriMesh {
 public:
  // ---- loading (errors: std::runtime_error naming the file)
  // ASCII or binary STL (binary when the size is 84 + 50 n for the n in its header).
  static TriMesh read_stl(const std::string& path);
  // Triangles as 9 numbers each (tests, extrusions); not yet built.
  static TriMesh from_triangles(const std::vector<double>& xyz9);
  void scale(double s);
  void translate(const Vec3d& d);
  void rotate(const Vec3d& axis, double degrees);  // about the origin, right-handed
  // Welds vertices closer than `precision`, finds edge neighbours, marks edges
  // and corners active (curvature: the largest angle in degrees between the
  // normals of two triangles of one surface) and bins the triangles.
  void build(double curvature_deg, double precision = 1e-8);

  // ---- body-frame geometry
  std::size_t ntri() const { return tri.size() / 3; }
  std::vector<double> vert;          // welded vertices, 3 per vertex
  std::vector<int> tri;              // 3 vertex indices per triangle; edge k joins corners k and k+1
  std::vector<int> nbr;              // 3 per triangle: the triangle across edge k (-1: none or non-manifold)
  std::vector<std::uint8_t> edge_active, corner_active;  // 3 per triangle
  std::vector<double> normal;        // unit normal per triangle (from the winding)
  double cos_curvature = 1;          // cos of the curvature angle (build)
  Vec3d corner(int t, int k) const {
    const double* v = &vert[3 * tri[3 * t + k]];
    return {v[0], v[1], v[2]};
  }
  // Triangles t and u are one surface: they share an inactive edge, or an inactive corner.
  bool same_surface(int t, int u) const;

  enum class Region : std::uint8_t { Face, Edge, Corner };
  struct Closest {
    Vec3d p;        // closest point on the triangle
    double dist2;   // squared distance to it
    Region region;
    int k;          // edge or corner index (0..2) for Edge / Corner
  };
  Closest closest(int t, const Vec3d& x) const;
  // Triangles within distance r of x (strictly), sorted: the bin grid, or every triangle.
  void near(const Vec3d& x, double r, std::vector<int>& out) const;
  // The same with their closest points. `seen` is the caller's scratch (one
  // per thread: searches may run concurrently).
  struct Near {
    int tri;
    Closest c;
  };
  struct Scratch {
    std::vector<std::uint32_t> seen;  // stamp per triangle: no sort to deduplicate
    std::uint32_t stamp = 0;
  };
  void near_closest(const Vec3d& x, double r, std::vector<Near>& out, Scratch& seen) const;
  // The two tests near_closest makes, for callers that keep their own candidate
  // triangles (fix wall/gran): the same arithmetic, so they find the same contacts.
  // x within r of the body box on every axis (else no triangle is):
  bool box_reaches(const Vec3d& x, double r) const {
    for (int q = 0; q < 3; ++q)
      if (x[q] + r < bbox_lo[q] || x[q] - r > bbox_hi[q]) return false;
    return true;
  }
  // Triangle t within r of x (strictly), its plane tested first; `out` its closest point.
  bool closest_within(int t, const Vec3d& x, double r, Closest& out) const {
    const double* n = &normal[3 * t];
    if (std::fabs(n[0] * x[0] + n[1] * x[1] + n[2] * x[2] - plane_[t]) >= r) return false;  // its plane is out of reach
    out = closest(t, x);
    return out.dist2 < r * r;
  }
  void near_brute(const Vec3d& x, double r, std::vector<int>& out) const;
  Vec3d bbox_lo{}, bbox_hi{};        // body frame

  // ---- rigid pose and motion (move/mesh)
  double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3d T{0, 0, 0};
  Vec3d to_body(const Vec3d& xw) const;
  Vec3d to_world(const Vec3d& xb) const;
  Vec3d dir_to_world(const Vec3d& db) const;
  struct Motion {
    bool rotate = false;
    Vec3d v{0, 0, 0};                          // linear
    Vec3d origin{0, 0, 0}, axis{0, 0, 1};      // rotate: unit axis
    double omega = 0;
    // A motion owned by a fix (move/mesh) ends with it (unfix): the pose stays where it got to.
    bool owned = false;
    std::weak_ptr<const void> owner;
    bool ended() const { return owned && owner.expired(); }
  };
  std::vector<Motion> motions;  // applied in order each step (several move/mesh fixes superpose)
  long pose_step = -1;          // step the pose is at (-1: not yet started)
  // Advances the pose to `step`, one dt increment of each motion per step.
  void advance_to(long step, double dt);
  Vec3d velocity(const Vec3d& pw) const;  // velocity of the rigid motion at world point pw
  // LIGGGHTS surface_vel (conveyor belt): each triangle's surface moves in its
  // plane along the projection of `belt`, at |belt|.
  Vec3d belt{0, 0, 0};
  // The wall velocity at world point pw of triangle t: rigid motion plus belt.
  Vec3d velocity(const Vec3d& pw, int t) const;
  Vec3d ref_body{0, 0, 0};                // reference point for torques, moves with the mesh

  // ---- force and torque of the grains on the mesh (this pass), and per triangle
  Vec3d force{0, 0, 0}, torque{0, 0, 0};
  std::vector<double> tri_force;  // 3 per triangle (dump mesh/vtk stress, stresscomponents)
  // LIGGGHTS' `wear finnie`: per triangle, the Finnie eroded mass per area summed
  // over the run (fix wall/gran mesh adds it); empty when the mesh has no wear model.
  std::vector<double> wear;
  void clear_load();
  void add_force_torque(const Vec3d& f, const Vec3d& t);
  void add_triangle_load(int t, const Vec3d& f);  // force f on triangle t (stress outputs)
  double area(int t) const;

 private:
  // Uniform bin grid over the body-frame box: triangles per cell (CSR).
  double cell_ = 1;
  int nb_[3] = {1, 1, 1};
  std::vector<int> cell_first_, cell_tri_;
  std::vector<double> plane_;               // n . (a corner) per triangle: a one-product distance filter
  void bin();
  void find_adjacency(double curvature_deg);
};

// What other parts ask of a fix that owns a mesh (fix mesh/surface): dumps
// find meshes through this, without knowing the fix.
class MeshHolder {
 public:
  virtual ~MeshHolder() = default;
  virtual TriMesh& mesh() = 0;
  virtual int wall_type() const = 0;
  virtual void update_pose() = 0;  // brings the pose to the current step (move/mesh motions)
};

}  // namespace sable
