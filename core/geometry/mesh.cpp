#include "core/geometry/mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace sable {

namespace {

Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3d add(const Vec3d& a, const Vec3d& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3d mul(const Vec3d& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Rotation matrix (row-major) of `angle` radians about the unit axis u (Rodrigues).
void rotation(const Vec3d& u, double angle, double Q[9]) {
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  Q[0] = c + u[0] * u[0] * t, Q[1] = u[0] * u[1] * t - u[2] * s, Q[2] = u[0] * u[2] * t + u[1] * s;
  Q[3] = u[1] * u[0] * t + u[2] * s, Q[4] = c + u[1] * u[1] * t, Q[5] = u[1] * u[2] * t - u[0] * s;
  Q[6] = u[2] * u[0] * t - u[1] * s, Q[7] = u[2] * u[1] * t + u[0] * s, Q[8] = c + u[2] * u[2] * t;
}
Vec3d mat_apply(const double Q[9], const Vec3d& x) {
  return {Q[0] * x[0] + Q[1] * x[1] + Q[2] * x[2], Q[3] * x[0] + Q[4] * x[1] + Q[5] * x[2],
          Q[6] * x[0] + Q[7] * x[1] + Q[8] * x[2]};
}
Vec3d unit(const Vec3d& a, const std::string& what) {
  const double n = std::sqrt(dot(a, a));
  if (!(n > 0)) throw std::runtime_error(what + ": zero-length axis");
  return mul(a, 1.0 / n);
}

// Binary STL: 80-byte header, uint32 count, then 50 bytes per triangle
// (normal, three vertices as float32, uint16 attribute).
bool is_binary_stl(const std::string& bytes) {
  if (bytes.size() < 84) return false;
  std::uint32_t n;
  std::memcpy(&n, bytes.data() + 80, 4);
  return bytes.size() == 84 + 50ull * n;
}

std::vector<double> parse_binary_stl(const std::string& bytes) {
  std::uint32_t n;
  std::memcpy(&n, bytes.data() + 80, 4);
  std::vector<double> xyz;
  xyz.reserve(9ull * n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* rec = bytes.data() + 84 + 50ull * t + 12;  // skip the stored normal
    for (int k = 0; k < 9; ++k) {
      float f;
      std::memcpy(&f, rec + 4 * k, 4);
      xyz.push_back(f);
    }
  }
  return xyz;
}

std::vector<double> parse_ascii_stl(const std::string& bytes, const std::string& path) {
  std::istringstream in(bytes);
  std::vector<double> xyz;
  std::string line;
  int lineno = 0, in_facet_vertices = -1;
  bool seen_solid = false;
  auto fail = [&](const std::string& msg) {
    throw std::runtime_error("STL file '" + path + "', line " + std::to_string(lineno) + ": " + msg);
  };
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string w;
    if (!(ls >> w)) continue;
    if (w == "solid") {
      seen_solid = true;
    } else if (w == "facet") {
      if (in_facet_vertices >= 0) fail("'facet' inside a facet (missing 'endfacet')");
      in_facet_vertices = 0;
    } else if (w == "vertex") {
      if (in_facet_vertices < 0) fail("'vertex' outside a facet");
      double v[3];
      if (!(ls >> v[0] >> v[1] >> v[2])) fail("'vertex' needs three numbers");
      if (++in_facet_vertices > 3) fail("more than three vertices in a facet");
      xyz.insert(xyz.end(), v, v + 3);
    } else if (w == "endfacet") {
      if (in_facet_vertices != 3) fail("a facet needs exactly three vertices");
      in_facet_vertices = -1;
    } else if (w == "outer" || w == "endloop" || w == "endsolid") {
    } else {
      fail("unexpected word '" + w + "' (expected solid, facet, outer loop, vertex, endloop, endfacet, endsolid)");
    }
  }
  if (!seen_solid) throw std::runtime_error("STL file '" + path + "': no 'solid' line (not an ASCII STL file?)");
  if (in_facet_vertices >= 0) fail("file ends inside a facet");
  if (xyz.empty()) throw std::runtime_error("STL file '" + path + "': no triangles");
  return xyz;
}

}  // namespace

TriMesh TriMesh::read_stl(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot open STL file '" + path + "'");
  std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const std::vector<double> xyz = is_binary_stl(bytes) ? parse_binary_stl(bytes) : parse_ascii_stl(bytes, path);
  if (xyz.empty()) throw std::runtime_error("STL file '" + path + "': no triangles");
  return from_triangles(xyz);
}

TriMesh TriMesh::from_triangles(const std::vector<double>& xyz9) {
  TriMesh m;
  m.vert = xyz9;  // unwelded until build()
  m.tri.resize(xyz9.size() / 3);
  for (std::size_t i = 0; i < m.tri.size(); ++i) m.tri[i] = static_cast<int>(i);
  return m;
}

void TriMesh::scale(double s) {
  for (double& v : vert) v *= s;
}

void TriMesh::translate(const Vec3d& d) {
  for (std::size_t i = 0; i < vert.size(); ++i) vert[i] += d[i % 3];
}

void TriMesh::rotate(const Vec3d& axis, double degrees) {
  double Q[9];
  rotation(unit(axis, "rotate"), degrees * std::numbers::pi / 180.0, Q);
  for (std::size_t i = 0; i < vert.size(); i += 3) {
    const Vec3d r = mat_apply(Q, {vert[i], vert[i + 1], vert[i + 2]});
    std::copy(r.begin(), r.end(), vert.begin() + i);
  }
}

void TriMesh::build(double curvature_deg, double precision) {
  // Weld: vertices within `precision` of an earlier one become it (hash grid of that cell size).
  const double cell = precision > 0 ? precision : 1e-300;
  std::map<std::array<long long, 3>, std::vector<int>> grid;
  std::vector<double> welded;
  std::vector<int> remap(vert.size() / 3);
  for (std::size_t i = 0; i < remap.size(); ++i) {
    const double* v = &vert[3 * i];
    std::array<long long, 3> c;
    for (int d = 0; d < 3; ++d) c[d] = static_cast<long long>(std::floor(v[d] / cell));
    int found = -1;
    for (int a = -1; a <= 1 && found < 0; ++a)
      for (int b = -1; b <= 1 && found < 0; ++b)
        for (int e = -1; e <= 1 && found < 0; ++e) {
          auto it = grid.find({c[0] + a, c[1] + b, c[2] + e});
          if (it == grid.end()) continue;
          for (int w : it->second) {
            const double* u = &welded[3 * w];
            if (std::fabs(u[0] - v[0]) <= precision && std::fabs(u[1] - v[1]) <= precision &&
                std::fabs(u[2] - v[2]) <= precision) {
              found = w;
              break;
            }
          }
        }
    if (found < 0) {
      found = static_cast<int>(welded.size() / 3);
      welded.insert(welded.end(), v, v + 3);
      grid[c].push_back(found);
    }
    remap[i] = found;
  }
  for (int& v : tri) v = remap[v];
  vert.swap(welded);
  // Normals from the winding.
  const std::size_t n = ntri();
  normal.assign(3 * n, 0.0);
  for (std::size_t t = 0; t < n; ++t) {
    const Vec3d a = corner(t, 0), nn = cross(sub(corner(t, 1), a), sub(corner(t, 2), a));
    const double len = std::sqrt(dot(nn, nn));
    if (!(len > 0)) throw std::runtime_error("triangle " + std::to_string(t) + " has zero area");
    for (int d = 0; d < 3; ++d) normal[3 * t + d] = nn[d] / len;
  }
  plane_.resize(n);
  for (std::size_t t = 0; t < n; ++t) plane_[t] = dot({normal[3 * t], normal[3 * t + 1], normal[3 * t + 2]}, corner(t, 0));
  find_adjacency(curvature_deg);
  bin();
}

// Edges shared by exactly two triangles whose normals differ by at most the
// curvature angle are inactive (one surface); boundary and non-manifold edges,
// and sharper ones, are active. A corner is active when any of its edges is.
void TriMesh::find_adjacency(double curvature_deg) {
  const std::size_t n = ntri();
  const double cosmax = std::cos(curvature_deg * std::numbers::pi / 180.0);
  cos_curvature = cosmax;
  std::map<std::pair<int, int>, std::vector<int>> edges;  // (lo, hi) vertex -> 3 t + k
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tri[3 * t + k], b = tri[3 * t + (k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(3 * t + k));
    }
  nbr.assign(3 * n, -1);
  edge_active.assign(3 * n, 1);
  std::vector<std::uint8_t> vert_active(vert.size() / 3, 0);
  for (auto& [key, list] : edges) {
    if (list.size() == 2) {
      const int t = list[0] / 3, u = list[1] / 3;
      // Consistent winding runs the shared edge in opposite directions; else flip u's normal.
      const bool same_dir = tri[list[0]] == tri[list[1]];
      const double c = (same_dir ? -1.0 : 1.0) * (normal[3 * t] * normal[3 * u] + normal[3 * t + 1] * normal[3 * u + 1] +
                                                  normal[3 * t + 2] * normal[3 * u + 2]);
      nbr[list[0]] = u;
      nbr[list[1]] = t;
      const bool active = c < cosmax;
      edge_active[list[0]] = edge_active[list[1]] = active;
      if (!active) continue;
    }
    vert_active[key.first] = vert_active[key.second] = 1;
  }
  corner_active.resize(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i) corner_active[i] = vert_active[tri[i]];
}

bool TriMesh::same_surface(int t, int u) const {
  for (int k = 0; k < 3; ++k)
    if (nbr[3 * t + k] == u && !edge_active[3 * t + k]) return true;
  for (int k = 0; k < 3; ++k) {
    if (corner_active[3 * t + k]) continue;
    for (int q = 0; q < 3; ++q)
      if (tri[3 * u + q] == tri[3 * t + k]) return true;
  }
  return false;
}

// Closest point on triangle t to x, with the Voronoi region it lies in
// (barycentric tests on the edge projections).
TriMesh::Closest TriMesh::closest(int t, const Vec3d& x) const {
  const Vec3d a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
  const Vec3d ab = sub(b, a), ac = sub(c, a), ap = sub(x, a);
  auto done = [&](const Vec3d& p, Region r, int k) {
    const Vec3d d = sub(x, p);
    return Closest{p, dot(d, d), r, k};
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return done(a, Region::Corner, 0);
  const Vec3d bp = sub(x, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return done(b, Region::Corner, 1);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return done(add(a, mul(ab, d1 / (d1 - d3))), Region::Edge, 0);
  const Vec3d cp = sub(x, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return done(c, Region::Corner, 2);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return done(add(a, mul(ac, d2 / (d2 - d6))), Region::Edge, 2);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return done(add(b, mul(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))), Region::Edge, 1);
  const double den = 1.0 / (va + vb + vc);
  return done(add(a, add(mul(ab, vb * den), mul(ac, vc * den))), Region::Face, 0);
}

// Cells about the mean edge length (at most 64 a side), each listing the
// triangles whose bounding boxes overlap it.
void TriMesh::bin() {
  const std::size_t n = ntri();
  bbox_lo = {1e300, 1e300, 1e300};
  bbox_hi = {-1e300, -1e300, -1e300};
  double edge_sum = 0;
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3d p = corner(t, k), d = sub(corner(t, (k + 1) % 3), p);
      edge_sum += std::sqrt(dot(d, d));
      for (int q = 0; q < 3; ++q) bbox_lo[q] = std::min(bbox_lo[q], p[q]), bbox_hi[q] = std::max(bbox_hi[q], p[q]);
    }
  cell_ = std::max(edge_sum / (6.0 * n), 1e-300);  // half the mean edge
  double span = 0;
  for (int q = 0; q < 3; ++q) span = std::max(span, bbox_hi[q] - bbox_lo[q]);
  cell_ = std::max(cell_, span / 128);  // at most 128 a side
  for (int q = 0; q < 3; ++q) nb_[q] = std::clamp(static_cast<int>((bbox_hi[q] - bbox_lo[q]) / cell_) + 1, 1, 128);
  auto cell_of = [&](double v, int q) {
    return std::clamp(static_cast<int>((v - bbox_lo[q]) / cell_), 0, nb_[q] - 1);
  };
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(nb_[0]) * nb_[1] * nb_[2]);
  for (std::size_t t = 0; t < n; ++t) {
    int lo[3], hi[3];
    for (int q = 0; q < 3; ++q) {
      double a = 1e300, b = -1e300;
      for (int k = 0; k < 3; ++k) a = std::min(a, corner(t, k)[q]), b = std::max(b, corner(t, k)[q]);
      lo[q] = cell_of(a, q), hi[q] = cell_of(b, q);
    }
    // Only the cells the triangle comes near (centre within the half diagonal):
    // a long thin triangle's box would cover many cells it never enters.
    const double half2 = 0.75 * cell_ * cell_ * (1 + 1e-9);
    for (int i = lo[0]; i <= hi[0]; ++i)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int k = lo[2]; k <= hi[2]; ++k) {
          const Vec3d centre{bbox_lo[0] + (i + 0.5) * cell_, bbox_lo[1] + (j + 0.5) * cell_, bbox_lo[2] + (k + 0.5) * cell_};
          if (closest(static_cast<int>(t), centre).dist2 <= half2)
            cells[(static_cast<std::size_t>(i) * nb_[1] + j) * nb_[2] + k].push_back(static_cast<int>(t));
        }
  }
  cell_first_.assign(1, 0);
  cell_tri_.clear();
  for (auto& c : cells) {
    cell_tri_.insert(cell_tri_.end(), c.begin(), c.end());
    cell_first_.push_back(static_cast<int>(cell_tri_.size()));
  }
}

void TriMesh::near_closest(const Vec3d& x, double r, std::vector<Near>& out, Scratch& sc) const {
  out.clear();
  int lo[3], hi[3];
  if (!box_reaches(x, r)) return;
  for (int q = 0; q < 3; ++q) {
    lo[q] = std::clamp(static_cast<int>((x[q] - r - bbox_lo[q]) / cell_), 0, nb_[q] - 1);
    hi[q] = std::clamp(static_cast<int>((x[q] + r - bbox_lo[q]) / cell_), 0, nb_[q] - 1);
  }
  std::vector<std::uint32_t>& seen = sc.seen;
  if (seen.size() != ntri()) seen.assign(ntri(), 0), sc.stamp = 0;
  if (++sc.stamp == 0) std::fill(seen.begin(), seen.end(), sc.stamp++);  // wrapped: start over
  for (int i = lo[0]; i <= hi[0]; ++i)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int k = lo[2]; k <= hi[2]; ++k) {
        const std::size_t c = (static_cast<std::size_t>(i) * nb_[1] + j) * nb_[2] + k;
        for (int q = cell_first_[c]; q < cell_first_[c + 1]; ++q) {
          const int t = cell_tri_[q];
          if (seen[t] == sc.stamp) continue;
          seen[t] = sc.stamp;
          Closest cl;
          if (closest_within(t, x, r, cl)) out.push_back({t, cl});
        }
      }
  std::sort(out.begin(), out.end(), [](const Near& a, const Near& b) { return a.tri < b.tri; });
}

void TriMesh::near(const Vec3d& x, double r, std::vector<int>& out) const {
  std::vector<Near> found;
  Scratch sc;
  near_closest(x, r, found, sc);
  out.clear();
  for (const Near& f : found) out.push_back(f.tri);
}

void TriMesh::near_brute(const Vec3d& x, double r, std::vector<int>& out) const {
  out.clear();
  for (std::size_t t = 0; t < ntri(); ++t)
    if (closest(static_cast<int>(t), x).dist2 < r * r) out.push_back(static_cast<int>(t));
}

Vec3d TriMesh::to_world(const Vec3d& xb) const { return add(mat_apply(R, xb), T); }
Vec3d TriMesh::dir_to_world(const Vec3d& db) const { return mat_apply(R, db); }
Vec3d TriMesh::to_body(const Vec3d& xw) const {
  const Vec3d d = sub(xw, T);  // R^T d
  return {R[0] * d[0] + R[3] * d[1] + R[6] * d[2], R[1] * d[0] + R[4] * d[1] + R[7] * d[2],
          R[2] * d[0] + R[5] * d[1] + R[8] * d[2]};
}

void TriMesh::advance_to(long step, double dt) {
  if (pose_step < 0) pose_step = step;
  std::erase_if(motions, [](const Motion& m) { return m.ended(); });
  for (; pose_step < step; ++pose_step)
    for (const Motion& m : motions) {
      if (!m.rotate) {
        T = add(T, mul(m.v, dt));
        continue;
      }
      double Q[9], QR[9];  // x -> Q (x - o) + o
      rotation(m.axis, m.omega * dt, Q);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) QR[3 * i + j] = Q[3 * i] * R[j] + Q[3 * i + 1] * R[3 + j] + Q[3 * i + 2] * R[6 + j];
      std::copy(QR, QR + 9, R);
      T = add(mat_apply(Q, sub(T, m.origin)), m.origin);
    }
}

Vec3d TriMesh::velocity(const Vec3d& pw) const {
  Vec3d v{0, 0, 0};
  for (const Motion& m : motions)
    if (!m.ended()) v = add(v, m.rotate ? mul(cross(m.axis, sub(pw, m.origin)), m.omega) : m.v);
  return v;
}

Vec3d TriMesh::velocity(const Vec3d& pw, int t) const {
  Vec3d v = velocity(pw);
  const double speed = std::sqrt(dot(belt, belt));
  if (speed == 0) return v;
  const Vec3d n = dir_to_world({normal[3 * t], normal[3 * t + 1], normal[3 * t + 2]});
  const Vec3d along = sub(belt, mul(n, dot(belt, n)));  // in the triangle's plane
  const double len = std::sqrt(dot(along, along));
  return len > 1e-12 * speed ? add(v, mul(along, speed / len)) : v;  // a belt normal to the face: none
}

void TriMesh::clear_load() {
  force = torque = {0, 0, 0};
  tri_force.assign(3 * ntri(), 0.0);
}

double TriMesh::area(int t) const {
  const Vec3d a = corner(t, 0), u = sub(corner(t, 1), a), v = sub(corner(t, 2), a), c = cross(u, v);
  return 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

void TriMesh::add_force_torque(const Vec3d& f, const Vec3d& t) {
  force = add(force, f);
  torque = add(torque, t);
}

void TriMesh::add_triangle_load(int t, const Vec3d& f) {
  if (tri_force.size() != 3 * ntri()) tri_force.assign(3 * ntri(), 0.0);
  for (int k = 0; k < 3; ++k) tri_force[3 * static_cast<std::size_t>(t) + k] += f[k];
}

}  // namespace sable
