#include "fixes/fix_wall_gran_mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "contact_models/materials.h"
#include "contact_models/pair_gran.h"
#include "contact_models/registry.h"
#include "core/engine/global_property.h"
#include "core/io/restart.h"
#include "core/engine/simulation.h"
#include "core/engine/threads.h"
#include "fixes/fix_mesh_surface.h"

namespace sable {

static Vec3d sub3(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

FixWallGranMesh::FixWallGranMesh(Simulation& s, const Args& a) : Fix(s, a) {
  hooks = atom_tasks = POST_FORCE;
  vector_size = 3;
  const ModelSelection sel = parse_model_selection(a, 4);
  kernel_ = make_kernel(sel, a, s);
  ModelSettings settings;
  kernel_->settings(settings);
  std::size_t i = sel.next;
  if (i >= a.size() || a[i] != "mesh") a.fail(i, "'mesh n_meshes K meshes ID1 ... IDK'");
  if (a.word(i + 1, "'n_meshes'") != "n_meshes") a.fail(i + 1, "'n_meshes'");
  const long k = a.integer(i + 2, "the number of meshes");
  if (k < 1) a.fail(i + 2, "at least one mesh");
  if (a.word(i + 3, "'meshes'") != "meshes") a.fail(i + 3, "'meshes'");
  for (long m = 0; m < k; ++m) {
    const std::string& id = a.word(i + 4 + m, "the ID of a fix mesh/surface");
    if (!dynamic_cast<FixMeshSurface*>(s.find_fix(id))) a.fail(i + 4 + m, "the ID of a fix mesh/surface defined before");
    mesh_ids_.push_back(id);
  }
  i += 4 + k;
  while (i < a.size()) {
    if (a[i] == "store_force" || a[i] == "store_force_contact") {
      if (a.yes_no(i + 1, "yes or no")) a.fail(i + 1, "'no' (use f_" + id + "[1..3] or the mesh's f_ID)");
      i += 2;
    } else if (!settings.try_parse(a, i)) {
      a.fail(i, "a model keyword: " + settings.names());
    }
  }
  hist_size_ = static_cast<int>(kernel_->history_slots().size());
  find_meshes();
}

void FixWallGranMesh::find_meshes() {
  meshes_.clear();
  for (const std::string& m : mesh_ids_) {
    auto* f = dynamic_cast<FixMeshSurface*>(sim.find_fix(m));
    if (!f) args.fail_line("fix mesh/surface " + m + " no longer exists");
    meshes_.push_back(f);
  }
  prev_.resize(meshes_.size());  // kept across runs
  for (HistoryStore& h : prev_)
    if (h.size() != hist_size_) h.configure(hist_size_);
  near_.resize(meshes_.size());
  glue_.resize(meshes_.size());  // filled at init (records() before a run: no glue yet)
  // The first wall/gran mesh fix of a mesh clears its load each step; the others add to it.
  owner_.assign(meshes_.size(), false);
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    owner_[m] = true;
    for (auto& f : sim.fixes) {
      if (f.get() == this) break;
      if (auto* w = dynamic_cast<FixWallGranMesh*>(f.get()))
        for (const std::string& id : w->mesh_ids_) owner_[m] = owner_[m] && id != mesh_ids_[m];
    }
  }
}

void FixWallGranMesh::init() {
  find_meshes();
  // Image shifts, code 9 a + 3 b + c with a, b, c in {0: none, 1: -L, 2: +L} per axis.
  for (int q = 0; q < 27; ++q) {
    const int c[3] = {q / 9, q / 3 % 3, q % 3};
    for (int d = 0; d < 3; ++d) shifts_[q][d] = c[d] == 0 ? 0.0 : (c[d] == 1 ? -1.0 : 1.0) * sim.domain.length(d);
  }
  near_.assign(meshes_.size(), NearList{});  // the deck may have moved grains since the last run
  xref_builds_ = -1;
  glue_.assign(meshes_.size(), Glue{});
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    meshes_[m]->update_pose();
    find_glue(static_cast<int>(m));
  }
  kernel_->connect(Materials::of(sim), args);
  find_k_finnie();
  freeze_bit_ = frozen_groupbits(sim);
  setup_pass_ = true;
}

// k of Finnie's wear model per (grain type, mesh type), when a mesh has `wear finnie`.
void FixWallGranMesh::find_k_finnie() {
  k_finnie_.clear();
  for (FixMeshSurface* m : meshes_) {
    if (m->mesh().wear.empty()) continue;
    const GlobalProperty* k = GlobalProperty::find(sim, "k_finnie");
    const std::size_t nt = static_cast<std::size_t>(sim.atoms.ntypes);
    if (!k || k->kind != GlobalProperty::Kind::Matrix || k->rows() != nt || static_cast<std::size_t>(k->ncols) != nt)
      m->args.fail_line("wear finnie needs 'fix ID all property/global k_finnie peratomtypepair " + std::to_string(nt) +
                        " ...' (" + std::to_string(nt * nt) + " values), as LIGGGHTS 3.8");
    k_finnie_ = k->values;
    return;
  }
}

namespace {

// Finnie's erosion rate for one grain-wall contact (LIGGGHTS 3.8, doc/finnie-wear.pdf
// Eq. 4.23): 2 k |v| f(gamma) |F| while the grain approaches the contact point (v.c > 0),
// v the grain's centre velocity relative to the wall, c from its centre to the contact,
// F the contact force, gamma the impact angle to the surface, f(gamma) = cos^2/3 for
// tan gamma > 1/3, else sin 2 gamma - 3 sin^2 gamma. LIGGGHTS 3.8 writes 1/3 as 0.33333
// in the first branch: with it, five impacts agree to 4e-8, with 1/3 to 9e-6
// (MeshWall.FinnieWearMatchesLiggghts).
double finnie_rate(const double v[3], const double c[3], const double f[3], double k) {
  const double vc = v[0] * c[0] + v[1] * c[1] + v[2] * c[2];
  if (!(vc > 0)) return 0.0;
  const double c2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2], s = vc / c2;
  const double t[3] = {v[0] - s * c[0], v[1] - s * c[1], v[2] - s * c[2]};  // v's part in the surface
  const double vn2 = vc * s, vt2 = t[0] * t[0] + t[1] * t[1] + t[2] * t[2], v2 = vn2 + vt2;
  // cos^2 gamma = vt^2 / v^2, sin 2 gamma = 2 vn vt / v^2, sin^2 gamma = vn^2 / v^2.
  const double fg = 9 * vn2 > vt2 ? 0.33333 * vt2 / v2 : (2 * std::sqrt(vn2 * vt2) - 3 * vn2) / v2;
  return 2 * k * std::sqrt(v2) * fg * std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
}

double dist2(const Vec3d& a, const Vec3d& b) {
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

bool has_vertex(const TriMesh& m, int t, int v) {
  return m.tri[3 * t] == v || m.tri[3 * t + 1] == v || m.tri[3 * t + 2] == v;
}

}  // namespace

// Edge (t, k) of the touch `a` is shared with the touch `b`: the same edge in
// the same image, or its periodic twin seen from the image one glue shift on.
bool FixWallGranMesh::shares_edge(int m, const Touchish& a, const Touchish& b) const {
  const TriMesh& mesh = meshes_[m]->mesh();
  const int e = 3 * a.tri + a.k;
  if (a.img == b.img && mesh.nbr[e] == b.tri) return true;
  const Glue& g = glue_[m];
  if (g.tri.empty() || g.tri[e] != b.tri) return false;
  return dist2(Vec3d{shifts_[b.img][0] - shifts_[a.img][0], shifts_[b.img][1] - shifts_[a.img][1],
                     shifts_[b.img][2] - shifts_[a.img][2]},
               g.shift[e]) <= 1e-20 * (1 + dist2(g.shift[e], {0, 0, 0}));
}

// One surface: triangles sharing an inactive edge (also through a periodic
// boundary) or an inactive corner (same image).
bool FixWallGranMesh::same_surface(int m, const Touchish& a, const Touchish& b) const {
  const TriMesh& mesh = meshes_[m]->mesh();
  if (a.img == b.img) return mesh.same_surface(a.tri, b.tri);
  const Glue& g = glue_[m];
  for (int k = 0; k < 3; ++k)
    if (!g.tri.empty() && g.tri[3 * a.tri + k] == b.tri && !g.active[3 * a.tri + k] &&
        shares_edge(m, Touchish{a.tri, k, a.img}, Touchish{b.tri, 0, b.img}))
      return true;
  return false;
}

// The touched triangles of one grain (all its images) reduced to its
// contacts: an edge or corner contact goes when a triangle sharing that edge
// or corner is nearer (the point is also that triangle's, which counts it);
// triangles of one surface, and contacts at one point (a convex edge seen
// from both sides, or from two images), join, and the nearest of each group
// is the contact (ties: lower index). Per contact: its index in `ts`.
template <class T>
static void reduce_touches(const FixWallGranMesh& f, int m, const TriMesh& mesh, std::vector<T>& ts, double r,
                           std::vector<int>& out) {
  out.clear();
  const std::size_t n = ts.size();
  if (n == 1) {  // one triangle within reach (most grains): nothing to drop or join
    out.push_back(0);
    return;
  }
  const double eps = 1e-12 * r * r, same2 = 1e-16 * r * r;  // far above round-off, far below any overlap
  for (std::size_t a = 0; a < n; ++a) {
    const TriMesh::Closest& c = ts[a].c;
    if (c.region == TriMesh::Region::Face) continue;
    const int t = ts[a].tri;
    for (std::size_t b = 0; b < n && ts[a].alive; ++b) {
      if (b == a || !(ts[b].c.dist2 < c.dist2 - eps)) continue;
      const bool shares = c.region == TriMesh::Region::Edge
                              ? f.shares_edge(m, {t, c.k, ts[a].img}, {ts[b].tri, 0, ts[b].img})
                              : ts[a].img == ts[b].img && has_vertex(mesh, ts[b].tri, mesh.tri[3 * t + c.k]);
      if (shares) ts[a].alive = false;
    }
  }
  std::vector<int> root(n);
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      if (ts[a].alive && ts[b].alive &&
          (f.same_surface(m, {ts[a].tri, 0, ts[a].img}, {ts[b].tri, 0, ts[b].img}) ||
           dist2(ts[a].preal, ts[b].preal) <= same2))
        root[find(static_cast<int>(b))] = find(static_cast<int>(a));
  for (std::size_t a = 0; a < n; ++a) {
    if (!ts[a].alive || find(static_cast<int>(a)) != static_cast<int>(a)) continue;
    int best = static_cast<int>(a);
    for (std::size_t b = 0; b < n; ++b) {
      if (!ts[b].alive || find(static_cast<int>(b)) != static_cast<int>(a)) continue;
      const auto& cb = ts[b].c;
      const auto& cr = ts[best].c;
      if (cb.dist2 < cr.dist2 || (cb.dist2 == cr.dist2 && ts[b].tri < ts[best].tri)) best = static_cast<int>(b);
    }
    out.push_back(best);
  }
}

// Boundary edges of a mesh that meet again through a periodic boundary (the
// same two vertices one or more box lengths apart) are glued: one edge, active
// or not by the angle of its triangles, as any inner edge. Found with the
// mesh's pose now (meshes that turn away from the axes lose the glue's meaning).
void FixWallGranMesh::find_glue(int m) {
  const TriMesh& mesh = meshes_[m]->mesh();
  const Domain& dom = sim.domain;
  Glue& g = glue_[m];
  g = Glue{};
  if (!dom.wraps(0) && !dom.wraps(1) && !dom.wraps(2)) return;
  std::vector<int> open;
  for (std::size_t e = 0; e < mesh.nbr.size(); ++e)
    if (mesh.nbr[e] < 0) open.push_back(static_cast<int>(e));
  if (open.empty() || open.size() > 20000) return;  // (quadratic search: large open meshes go without)
  g.tri.assign(mesh.nbr.size(), -1);
  g.active.assign(mesh.nbr.size(), 1);
  g.shift.assign(mesh.nbr.size(), {0, 0, 0});
  auto ends = [&](int e, Vec3d& a, Vec3d& b) {
    a = mesh.to_world(mesh.corner(e / 3, e % 3));
    b = mesh.to_world(mesh.corner(e / 3, (e % 3 + 1) % 3));
  };
  const double tol = 1e-9 * std::max({dom.length(0), dom.length(1), dom.length(2)});
  for (int e : open)
    for (int q : open) {
      if (q / 3 == e / 3) continue;
      Vec3d a, b, c, d;
      ends(e, a, b);
      ends(q, c, d);
      if (dist2(sub3(c, a), sub3(d, b)) > tol * tol) std::swap(c, d);  // the twin may run either way
      const Vec3d s = sub3(c, a);
      if (dist2(s, sub3(d, b)) > tol * tol || dist2(s, {0, 0, 0}) < tol * tol) continue;
      bool whole = true;  // each component: 0 or a whole number of periodic box lengths
      for (int k = 0; k < 3 && whole; ++k) {
        if (std::fabs(s[k]) < tol) continue;
        const double n = std::round(s[k] / dom.length(k));
        whole = dom.wraps(k) && n != 0 && std::fabs(s[k] - n * dom.length(k)) < tol;
      }
      if (!whole) continue;
      const int t = e / 3, u = q / 3;
      const double cosang = mesh.normal[3 * t] * mesh.normal[3 * u] + mesh.normal[3 * t + 1] * mesh.normal[3 * u + 1] +
                            mesh.normal[3 * t + 2] * mesh.normal[3 * u + 2];
      g.tri[e] = u;
      g.shift[e] = s;  // world frame (the glue is found with the pose now)
      g.active[e] = std::fabs(cosang) < mesh.cos_curvature;
    }
}

// The mesh's bounding box in the world now (its body box's corners moved).
static void world_box(const TriMesh& mesh, Vec3d& wlo, Vec3d& whi) {
  wlo = {1e300, 1e300, 1e300};
  whi = {-1e300, -1e300, -1e300};
  for (int c = 0; c < 8; ++c) {
    const Vec3d p = mesh.to_world({c & 1 ? mesh.bbox_hi[0] : mesh.bbox_lo[0], c & 2 ? mesh.bbox_hi[1] : mesh.bbox_lo[1],
                                   c & 4 ? mesh.bbox_hi[2] : mesh.bbox_lo[2]});
    for (int d = 0; d < 3; ++d) wlo[d] = std::min(wlo[d], p[d]), whi[d] = std::max(whi[d], p[d]);
  }
}

int FixWallGranMesh::images(const double* x, double reach, const Vec3d& wlo, const Vec3d& whi, int* img) const {
  const Domain& dom = sim.domain;
  int code[3][3], ns[3];
  for (int d = 0; d < 3; ++d) {
    ns[d] = 0;
    const double L = dom.wraps(d) ? dom.length(d) : 0.0;
    for (int q = 0; q < (L > 0 ? 3 : 1); ++q) {
      const double s = (q == 0 ? 0.0 : q == 1 ? -L : L);
      if (x[d] + s + reach > wlo[d] && x[d] + s - reach < whi[d]) code[d][ns[d]++] = q;
    }
    if (ns[d] == 0) return 0;
  }
  int n = 0;  // in increasing code
  for (int a = 0; a < ns[0]; ++a)
    for (int b = 0; b < ns[1]; ++b)
      for (int c = 0; c < ns[2]; ++c) img[n++] = code[0][a] * 9 + code[1][b] * 3 + code[2][c];
  return n;
}

// Grains of the group that can touch mesh m before the next refresh, with
// their candidate triangles: those within r + skin of the grain's position at
// the last neighbour build. Until the next build a grain moves (and grows) at
// most skin/2 from there (the rebuild rule), and until the next refresh the
// mesh moves at most skin/2 from its pose now (refreshed, candidates searched
// again from the same grain positions, once a point of it has moved more:
// rigid motion, a corner of its box moves most). So a triangle that comes
// within r of a grain before the next refresh is among its candidates.
// LIGGGHTS instead counts a moving mesh's node displacement in its rebuild
// check and rebuilds every list; here only the mesh's lists are refreshed.
void FixWallGranMesh::refresh_near(int mi) {
  const TriMesh& mesh = meshes_[mi]->mesh();
  const Atoms& at = sim.atoms;
  NearList& nl = near_[mi];
  const double half_skin = 0.5 * sim.neighbor.skin;
  double moved2 = 0;
  for (int c = 0; c < 8 && nl.builds >= 0; ++c) {
    const Vec3d p{c & 1 ? mesh.bbox_hi[0] : mesh.bbox_lo[0], c & 2 ? mesh.bbox_hi[1] : mesh.bbox_lo[1],
                  c & 4 ? mesh.bbox_hi[2] : mesh.bbox_lo[2]};
    const Vec3d now = mesh.to_world(p);
    Vec3d then = nl.T;
    for (int d = 0; d < 3; ++d) then[d] += nl.R[3 * d] * p[0] + nl.R[3 * d + 1] * p[1] + nl.R[3 * d + 2] * p[2];
    const Vec3d dd = sub3(now, then);
    moved2 = std::max(moved2, dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
  }
  if (nl.builds == sim.neighbor.builds && nl.n == at.n && moved2 <= half_skin * half_skin) return;
  // The positions the rebuild rule measures from: the first refresh after a build
  // comes in that step's force pass, before any grain moves again.
  if (xref_builds_ != sim.neighbor.builds || xref_.size() != 3 * at.n) {
    xref_.assign(at.x.begin(), at.x.begin() + 3 * static_cast<std::ptrdiff_t>(at.n));
    xref_builds_ = sim.neighbor.builds;
  }
  nl.builds = sim.neighbor.builds;
  nl.n = at.n;
  std::copy(mesh.R, mesh.R + 9, nl.R);
  nl.T = mesh.T;
  nl.atoms.clear();
  nl.first.clear();
  nl.cand.clear();
  Vec3d wlo, whi;
  world_box(mesh, wlo, whi);
  int img[27];
  for (std::size_t i = 0; i < at.n; ++i) {
    if (!(at.mask[i] & groupbit)) continue;
    const double* x = &xref_[3 * i];
    const double reach = at.radius[i] + 2 * half_skin;
    const std::size_t before = nl.cand.size();
    const int ni = images(x, reach, wlo, whi, img);
    for (int q = 0; q < ni; ++q) {
      const Vec3d& sh = shifts_[img[q]];
      mesh.near_closest(mesh.to_body({x[0] + sh[0], x[1] + sh[1], x[2] + sh[2]}), reach, serial_.cand, serial_.seen);
      for (const TriMesh::Near& nc : serial_.cand) nl.cand.push_back({nc.tri, img[q]});
    }
    if (nl.cand.size() == before) continue;
    nl.atoms.push_back(static_cast<int>(i));
    nl.first.push_back(static_cast<int>(before));
  }
  nl.first.push_back(static_cast<int>(nl.cand.size()));
}

// The triangles within r of grain i's images now, among its candidates: the
// same tests, in the same order, as a search of the mesh's bin grid would make.
void FixWallGranMesh::touches(int mi, std::size_t c, std::size_t i, double r, const Vec3d& wlo, const Vec3d& whi,
                              Part& p) {
  std::vector<Touch>& touched = p.touched;
  touched.clear();
  const TriMesh& mesh = meshes_[mi]->mesh();
  const NearList& nl = near_[mi];
  const double* x = &sim.atoms.x[3 * i];
  int img[27];
  const int ni = images(x, r, wlo, whi, img);
  int k = nl.first[c];
  const int end = nl.first[c + 1];
  for (int q = 0; q < ni; ++q) {
    while (k < end && nl.cand[k].img < img[q]) ++k;
    if (k == end) break;
    if (nl.cand[k].img != img[q]) continue;
    const Vec3d& sh = shifts_[img[q]];
    const Vec3d xb = mesh.to_body({x[0] + sh[0], x[1] + sh[1], x[2] + sh[2]});
    if (!mesh.box_reaches(xb, r)) continue;
    for (; k < end && nl.cand[k].img == img[q]; ++k) {
      TriMesh::Closest cl;
      if (!mesh.closest_within(nl.cand[k].tri, xb, r, cl) || cl.dist2 == 0.0) continue;  // a centre on the surface has no normal
      touched.push_back({nl.cand[k].tri, img[q], cl, sub3(mesh.to_world(cl.p), sh)});
    }
  }
}

void FixWallGranMesh::collect(int mi, std::uint32_t also, std::size_t c0, std::size_t c1, Part& p,
                              std::vector<Hit>& out) {
  out.clear();
  const TriMesh& mesh = meshes_[mi]->mesh();
  const Atoms& at = sim.atoms;
  Vec3d wlo, whi;
  world_box(mesh, wlo, whi);
  std::vector<Touch>& touched = p.touched;
  std::vector<int> contacts;
  for (std::size_t c = c0; c < c1; ++c) {
    const std::size_t i = static_cast<std::size_t>(near_[mi].atoms[c]);
    if (!(at.mask[i] & also)) continue;
    const double r = at.radius[i], *x = &at.x[3 * i];
    touches(mi, c, i, r, wlo, whi, p);
    if (touched.empty()) continue;
    reduce_touches(*this, mi, mesh, touched, r, contacts);
    const std::size_t first = out.size();
    for (const int rep : contacts) {
      const Touch& tc = touched[rep];
      const Vec3d& sh = shifts_[tc.img];
      const Vec3d xb = mesh.to_body({x[0] + sh[0], x[1] + sh[1], x[2] + sh[2]});
      const double dist = std::sqrt(tc.c.dist2);
      const Vec3d nb{(xb[0] - tc.c.p[0]) / dist, (xb[1] - tc.c.p[1]) / dist, (xb[2] - tc.c.p[2]) / dist};
      Hit h;
      h.tag = at.id[i];
      h.atom = static_cast<int>(i);
      h.tri = tc.tri;
      h.deltan = r - dist;
      const Vec3d en = mesh.dir_to_world(nb);
      h.pmesh = mesh.to_world(tc.c.p);
      const Vec3d vw = mesh.velocity(h.pmesh, tc.tri);
      for (int d = 0; d < 3; ++d) {
        h.en[d] = en[d];
        h.vwall[d] = vw[d];
        h.point[d] = x[d] - en[d] * dist;
      }
      out.push_back(h);
    }
    std::sort(out.begin() + static_cast<long>(first), out.end(), [](const Hit& p, const Hit& q) { return p.tri < q.tri; });
  }
}

// Triangles t and u are one surface: a shared inactive edge or corner, or an
// inactive edge glued through a periodic boundary.
bool FixWallGranMesh::joined(int m, int t, int u) const {
  if (meshes_[m]->mesh().same_surface(t, u)) return true;
  const Glue& g = glue_[m];
  for (int k = 0; k < 3 && !g.tri.empty(); ++k)
    if (g.tri[3 * t + k] == u && !g.active[3 * t + k]) return true;
  return false;
}

// Last step's history of each hit: the same (grain, triangle), else a contact
// of that grain on a triangle of the same surface (curvature) that has ended
// (the grain passed onto this triangle), else zeros: as LIGGGHTS 3.8, history
// does not pass an active edge.
std::vector<double> FixWallGranMesh::history_for(int m, const std::vector<Hit>& hits, std::vector<HistoryStore::Key>& keys,
                                                 std::vector<int>& order, std::vector<int>& rows) const {
  const std::size_t n = hits.size();
  order.resize(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int p, int q) {
    return hits[p].tag != hits[q].tag ? hits[p].tag < hits[q].tag : hits[p].tri < hits[q].tri;
  });
  keys.resize(n);
  rows.resize(n);
  for (std::size_t q = 0; q < n; ++q) {
    const Hit& h = hits[order[q]];
    keys[q] = {h.tag, HistoryStore::kWall, h.tri};
    rows[order[q]] = static_cast<int>(q);
  }
  std::vector<double> out(static_cast<std::size_t>(hist_size_) * n);
  prev_[m].look_up(keys.data(), keys.size(), out.data(), [&](int before, int now) { return joined(m, before, now); });
  return out;
}

WallBatch FixWallGranMesh::batch(int m, const std::vector<Hit>& hits, std::vector<double>& cols,
                                 std::vector<int>& atoms, const std::vector<int>& rows, double* hist) {
  const std::size_t n = hits.size();
  cols.assign(7 * n, 0.0);  // deltan, en, vwall
  atoms.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    atoms[k] = hits[k].atom;
    cols[k] = hits[k].deltan;
    for (int d = 0; d < 3; ++d) {
      cols[n + 3 * k + d] = hits[k].en[d];
      cols[4 * n + 3 * k + d] = hits[k].vwall[d];
    }
  }
  Atoms& at = sim.atoms;
  WallBatch b;
  b.a = atom_view(at, at.n, freeze_bit_);
  b.n = n;
  b.atom = atoms.data();
  b.deltan = cols.data();
  b.en = cols.data() + n;
  b.vwall = cols.data() + 4 * n;
  if (hist_size_ > 0) {
    b.hist = hist;
    b.hist_index = rows.data();
    b.hist_stride = hist_size_;
  }
  b.wall_type = meshes_[m]->wall_type();
  b.ctx.dt = sim.dt;
  return b;
}

void FixWallGranMesh::begin(FixHook) {
  sums_.resize(meshes_.size());
  ref_world_.resize(meshes_.size());
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    meshes_[m]->update_pose();
    TriMesh& mesh = meshes_[m]->mesh();
    if (owner_[m]) mesh.clear_load();
    refresh_near(static_cast<int>(m));
    ref_world_[m] = mesh.to_world(mesh.ref_body);
    sums_[m].begin(sim.atoms.n);
  }
  pass_update_ = !setup_pass_;  // LIGGGHTS: no history update in the setup force pass
  setup_pass_ = false;
  parts_.start([&](Part& p) {
    p.mesh.resize(meshes_.size());
    for (auto& pm : p.mesh) pm.hits.clear(), pm.keys.clear();
  });
}

// The contacts of the near grains among atoms [lo, hi): found, given their
// history and evaluated on this thread (the grains are this thread's alone).
void FixWallGranMesh::range(FixHook, const AtomRange& r) {
  const std::size_t lo = r.lo, hi = r.hi;
  Part& p = parts_[r.thread];
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const std::vector<int>& near = near_[m].atoms;
    const auto c0 = std::lower_bound(near.begin(), near.end(), static_cast<int>(lo)) - near.begin();
    const auto c1 = std::lower_bound(near.begin(), near.end(), static_cast<int>(hi)) - near.begin();
    Part::PerMesh& pm = p.mesh[m];
    const int mi = static_cast<int>(m);
    collect(mi, ~0u, static_cast<std::size_t>(c0), static_cast<std::size_t>(c1), p, pm.hits);
    pm.hist = history_for(mi, pm.hits, pm.keys, pm.order, pm.rows);
    WallBatch b = batch(mi, pm.hits, pm.cols, pm.atoms, pm.rows, pm.hist.data());
    pm.force.assign(3 * pm.hits.size(), 0.0);
    b.force = pm.force.data();
    b.ctx.update = pass_update_;
    if (!pm.hits.empty()) kernel_->wall_forces(b);
    contact_wear(mi, pm);
    sum_loads(mi, r, pm);
  }
}

// The reaction of this range's contacts on mesh m into core's AtomSum, in atom
// order: every contact's (f_ID), and of the grains in the mesh fix's group
// (LIGGGHTS' stress module) the force and the torque about the reference point.
void FixWallGranMesh::sum_loads(int m, const AtomRange& r, const Part::PerMesh& pm) {
  AtomSum<9>& sum = sums_[m];
  sum.range(r);
  const std::uint32_t mesh_bits = meshes_[m]->groupbit;
  for (std::size_t k = 0; k < pm.hits.size(); ++k) {
    const Hit& h = pm.hits[k];
    const Vec3d on_mesh{0.0 - pm.force[3 * k], 0.0 - pm.force[3 * k + 1], 0.0 - pm.force[3 * k + 2]};
    double v[9] = {on_mesh[0], on_mesh[1], on_mesh[2], 0, 0, 0, 0, 0, 0};
    if (sim.atoms.mask[h.atom] & mesh_bits) {
      const Vec3d a = sub3(h.pmesh, ref_world_[m]);  // lever arm
      const double t[3] = {a[1] * on_mesh[2] - a[2] * on_mesh[1], a[2] * on_mesh[0] - a[0] * on_mesh[2],
                           a[0] * on_mesh[1] - a[1] * on_mesh[0]};
      for (int d = 0; d < 3; ++d) v[3 + d] = on_mesh[d], v[6 + d] = t[d];
    }
    sum.add(r, static_cast<std::size_t>(h.atom), v);
  }
}

// Each mesh's force and torque from core's AtomSum; the per-triangle loads and
// wear (a scatter onto triangles) and the history kept for the next pass from
// the threads' contacts in (grain id, triangle) order.
void FixWallGranMesh::end(FixHook) {
  double total[3] = {0, 0, 0};
  const std::size_t hs = static_cast<std::size_t>(hist_size_);
  HistoryStore::Order order;  // (part, contact in key order)
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    auto pm_of = [&](int t) -> const Part::PerMesh& { return parts_[t].mesh[m]; };
    double v[9];
    sums_[m].total(v);
    TriMesh& mesh = meshes_[m]->mesh();
    mesh.add_force_torque({v[3], v[4], v[5]}, {v[6], v[7], v[8]});
    for (int d = 0; d < 3; ++d) total[d] += v[d];
    HistoryStore::merged_order(
        parts_.size(), [&](int t) { return pm_of(t).keys.data(); },
        [&](int t) { return pm_of(t).hits.size(); }, order);
    const std::uint32_t mesh_bits = meshes_[m]->groupbit;  // LIGGGHTS' stress module: grains of the mesh fix's group
    for (const auto& [t, q] : order) {
      const Part::PerMesh& pm = pm_of(t);
      const int k = pm.order[q];
      const Hit& h = pm.hits[k];
      if (!(sim.atoms.mask[h.atom] & mesh_bits)) continue;
      mesh.add_triangle_load(h.tri, {0.0 - pm.force[3 * k], 0.0 - pm.force[3 * k + 1], 0.0 - pm.force[3 * k + 2]});
      if (!pm.wear.empty() && pass_update_) mesh.wear[h.tri] += pm.wear[k];
    }
    prev_[m].keep(
        order, [&](int t, int q) { return pm_of(t).keys[q]; }, [&](int t, int q) { return pm_of(t).hist.data() + q * hs; });
  }
  std::copy(total, total + 3, force_);
}

// This step's Finnie wear of each contact of pm on its triangle, per triangle area,
// while the grains' velocities are still the half-step ones the forces saw (the
// pipelined step kicks them after this range).
void FixWallGranMesh::contact_wear(int m, Part::PerMesh& pm) {
  const TriMesh& mesh = meshes_[m]->mesh();
  if (mesh.wear.empty()) {
    pm.wear.clear();
    return;
  }
  const Atoms& a = sim.atoms;
  const std::size_t nt = static_cast<std::size_t>(a.ntypes), wt = static_cast<std::size_t>(meshes_[m]->wall_type() - 1);
  pm.wear.resize(pm.hits.size());
  for (std::size_t k = 0; k < pm.hits.size(); ++k) {
    const Hit& h = pm.hits[k];
    const double* x = &a.x[3 * h.atom];
    const double v[3] = {a.v[3 * h.atom] - h.vwall[0], a.v[3 * h.atom + 1] - h.vwall[1], a.v[3 * h.atom + 2] - h.vwall[2]};
    const double c[3] = {h.point[0] - x[0], h.point[1] - x[1], h.point[2] - x[2]};
    const double kf = k_finnie_[static_cast<std::size_t>(a.type[h.atom] - 1) * nt + wt];
    pm.wear[k] = finnie_rate(v, c, &pm.force[3 * k], kf) * sim.dt / mesh.area(h.tri);
  }
}

void FixWallGranMesh::records(std::uint32_t bits, ContactRecords& out) {
  out.clear();
  out.hist_size = hist_size_;
  rec_ = Rec{};
  std::vector<Hit> hits;
  std::vector<HistoryStore::Key> keys;
  std::vector<double> cols;
  std::vector<int> atoms, rows, order;
  ContactRecords part;
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const int mi = static_cast<int>(m);
    meshes_[m]->update_pose();
    refresh_near(mi);
    collect(mi, bits, 0, near_[m].atoms.size(), serial_, hits);
    std::sort(hits.begin(), hits.end(), [](const Hit& p, const Hit& q) { return p.tag != q.tag ? p.tag < q.tag : p.tri < q.tri; });
    std::vector<double> hist = history_for(mi, hits, keys, order, rows);  // records in key order: rows[k] = k
    WallBatch b = batch(mi, hits, cols, atoms, rows, hist.data());
    b.ctx.update = false;
    const int offset = static_cast<int>(rec_.tri.size());
    for (const Hit& h : hits) {
      rec_.vwall.insert(rec_.vwall.end(), h.vwall, h.vwall + 3);
      rec_.point.insert(rec_.point.end(), h.point.begin(), h.point.end());
      rec_.tri.push_back(h.tri);
      rec_.mesh.push_back(mi);
    }
    if (hits.empty()) continue;
    kernel_->wall_records(b, part);
    for (ContactRecord r : part.rows) {
      r.shift += offset;
      out.rows.push_back(r);
    }
    out.hist.insert(out.hist.end(), part.hist.begin(), part.hist.end());
  }
}

bool FixWallGranMesh::write_state(std::string& out) const {
  restart::Packer p;
  p.put<std::uint64_t>(prev_.size());
  for (const HistoryStore& h : prev_) h.write(p);
  out = p.bytes;
  return true;
}

void FixWallGranMesh::read_state(const std::string& in) {
  restart::Unpacker u(in, "the restart state of fix " + id);
  const auto n = u.get<std::uint64_t>();
  if (n != prev_.size()) args.fail_line("the restart file's fix " + id + " had " + std::to_string(n) + " meshes");
  for (HistoryStore& h : prev_)
    if (!h.read(u)) args.fail_line("the restart file's fix " + id + " has another model");
}

double FixWallGranMesh::compute_vector(int i) {
  if (i < 1 || i > 3) args.fail_line("f_" + id + "[" + std::to_string(i) + "]: index out of range 1..3");
  return sim.comm.total(force_[i - 1]);
}

}  // namespace sable
