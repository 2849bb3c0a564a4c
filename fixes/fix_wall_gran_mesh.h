#pragma once
// fix ID group wall/gran model M [tangential T] [rolling_friction R]
//     mesh n_meshes K meshes ID1 ... IDK [keyword on|off ...]
// LIGGGHTS 3.8 mesh walls: every grain of the group touching a triangle of a
// fix mesh/surface (its face, an active edge or an active corner) gets one
// wall contact per touched surface, through the same compiled kernel as
// `pair_style gran` and the primitive walls, with the mesh's material type
// and the mesh's surface velocity (fix move/mesh) at the contact point.
//   - Per contact, the closest point of the triangle to the grain centre.
//     A contact on an edge or corner is dropped when a triangle sharing that
//     edge or corner is nearer (the point belongs to it too); triangles of one
//     surface (shared inactive edge or corner, see fix mesh/surface curvature)
//     and contacts at one point count once: the nearest triangle.
//   - History (tangential, rolling) per (grain id, mesh, triangle), kept
//     through sorting and rebuilds; when a grain's contact passes to another
//     triangle of the same surface its history goes with it (not across an
//     active edge: LIGGGHTS 3.8, checked by input_scripts/compare/mesh_fold.in).
//   - The reaction (minus the force on the grain) acts on the mesh at the
//     contact point: f_MESH[1..3], torque f_MESH[4..6] about its reference point.
//   - Periodic boxes: a grain sees the mesh through the boundary (nearest images).
//   - Each thread finds and evaluates the contacts of its own atoms (a
//     POST_FORCE atom task: the pipelined fast path); the mesh's force and torque and
//     the kept history are then summed / merged in a fixed order (grain id,
//     triangle): bits independent of threads and of the atoms' order in memory.
// Output f_ID[1..3]: total force of the grains on all the fix's meshes.
#include <memory>
#include <vector>

#include "contact_models/kernel.h"
#include "core/engine/block_sum.h"
#include "core/engine/contact_source.h"
#include "core/engine/fix.h"
#include "core/engine/threads.h"
#include "core/engine/history_store.h"
#include "core/geometry/mesh.h"

namespace sable {

class FixMeshSurface;

class FixWallGranMesh : public Fix, public ContactSource {
 public:
  FixWallGranMesh(Simulation& sim, const Args& args);
  void export_yade(YadeScript& s) const override;  // fixes/fix_wall_gran_yade.cpp
  void init() override;
  void begin(FixHook) override;
  void range(FixHook, const AtomRange& r) override;
  void end(FixHook) override;
  double compute_vector(int i) override;
  // Restart: the contacts' history (per mesh: grain ids, triangles, rows).
  bool write_state(std::string& out) const override;
  void read_state(const std::string& in) override;

  ContactKernel& kernel() { return *kernel_; }
  // A triangle seen from image `img` of a grain (k: an edge index where it matters).
  struct Touchish {
    int tri, k, img;
  };
  bool shares_edge(int m, const Touchish& a, const Touchish& b) const;
  bool same_surface(int m, const Touchish& a, const Touchish& b) const;
  bool joined(int m, int t, int u) const;  // same surface, through any periodic image
  // ContactSource. Record r's triangle is element(r.shift) (of the fix's mesh number mesh(r.shift)).
  Kind contact_kind() const override { return Kind::Mesh; }
  std::string law_name() const override { return kernel_->name(); }
  const std::vector<HistorySlot>& history_slots() const override { return kernel_->history_slots(); }
  void records(std::uint32_t groupbit, ContactRecords& out) override;
  const double* wall_point(int k) const override { return &rec_.point[3 * k]; }
  const double* wall_velocity(int k) const override { return &rec_.vwall[3 * k]; }
  int element(int k) const override { return rec_.tri[k]; }
  void ids_renumbered(const std::vector<long>& o, const std::vector<long>& n) override {
    for (HistoryStore& h : prev_) h.renumber(o, n);
  }
  std::vector<HistoryStore*> histories_by_grain() override {
    std::vector<HistoryStore*> out;
    for (HistoryStore& h : prev_) out.push_back(&h);
    return out;
  }
  void history_moved() override {
    for (HistoryStore& h : prev_) h.sort();
  }
  int mesh(int k) const { return rec_.mesh[k]; }

  // One grain-triangle contact of a step.
  struct Hit {
    long tag;
    int atom, tri;
    double deltan, en[3], vwall[3];
    Vec3d point, pmesh;  // closest point seen from the grain (its image) / on the mesh itself
  };

 private:
  std::unique_ptr<ContactKernel> kernel_;
  std::vector<std::string> mesh_ids_;
  std::vector<FixMeshSurface*> meshes_;
  std::vector<bool> owner_;  // this fix clears the mesh's force (first wall fix using it)
  int hist_size_ = 0;
  bool setup_pass_ = true;
  std::uint32_t freeze_bit_ = 0;
  double force_[3] = {0, 0, 0};
  // Last step's contacts per mesh and their history, by (grain id, triangle).
  std::vector<HistoryStore> prev_;
  std::vector<double> k_finnie_;  // ntypes x ntypes (wear finnie), else empty
  void find_k_finnie();
  // Records of the last records() call (all meshes, in order).
  struct Rec {
    std::vector<double> vwall, point;
    std::vector<int> tri, mesh;
  } rec_;

  void find_meshes();
  // Periodic glue per mesh: boundary edge e = 3 t + k meets triangle tri[e]'s
  // edge `shift[e]` (body frame) away through a periodic boundary.
  struct Glue {
    std::vector<int> tri;
    std::vector<Vec3d> shift;
    std::vector<std::uint8_t> active;
  };
  std::vector<Glue> glue_;
  Vec3d shifts_[27] = {};  // grain image shifts by code (init)
  void find_glue(int m);
  // A triangle within reach of one image of a grain: its closest point (body
  // frame of the mesh, as seen from that image) and that point in the grain's own frame.
  struct Touch {
    int tri, img;
    TriMesh::Closest c;
    Vec3d preal;
    bool alive = true;
  };
  // One thread's search scratch and, per mesh, its contacts of a pass.
  struct alignas(64) Part {
    std::vector<Touch> touched;
    std::vector<TriMesh::Near> cand;
    TriMesh::Scratch seen;
    struct PerMesh {
      std::vector<Hit> hits;
      // hits in atom order (a grain's by triangle); keys their (grain id,
      // triangle) in key order, order[q] the hit of keys[q], rows[k] the key
      // place (history row) of hit k, hist the rows in key order.
      std::vector<HistoryStore::Key> keys;
      std::vector<double> hist, force, cols, wear;  // wear: per contact, this step's (wear finnie)
      std::vector<int> atoms, rows, order;
    };
    std::vector<PerMesh> mesh;
  };
  ThreadParts<Part> parts_;
  void contact_wear(int m, Part::PerMesh& pm);
  Part serial_;  // refresh_near and records
  bool pass_update_ = true;
  // The image codes of a grain at x whose image comes within reach of the mesh's
  // world box [wlo, whi] (itself and, on periodic axes, one box length either way).
  int images(const double* x, double reach, const Vec3d& wlo, const Vec3d& whi, int* img) const;
  // Grains that can reach mesh m until the next refresh, and their candidate
  // triangles (see refresh_near): per step only these are tested.
  struct Cand {
    int tri, img;
  };
  struct NearList {
    std::vector<int> atoms;   // by atom index
    std::vector<int> first;   // atoms[c]'s candidates: cand[first[c], first[c + 1]), by image then triangle
    std::vector<Cand> cand;
    long builds = -1;
    std::size_t n = 0;
    double R[9];
    Vec3d T;
  };
  std::vector<NearList> near_;
  // The grains' positions at the last neighbour build (taken at the first refresh
  // after it): candidates are searched from there (see refresh_near).
  std::vector<double> xref_;
  long xref_builds_ = -1;
  void refresh_near(int m);
  // The candidates of near_[m].atoms[c] within distance r of grain i now, into p.touched.
  void touches(int m, std::size_t c, std::size_t i, double r, const Vec3d& wlo, const Vec3d& whi, Part& p);
  // Contacts with mesh m of the grains of near_[m].atoms[c0, c1) in groupbit & also,
  // in atom order, each grain's by triangle.
  void collect(int m, std::uint32_t also, std::size_t c0, std::size_t c1, Part& p, std::vector<Hit>& out);
  // History rows for the hits from prev_[m] (same triangle, else the same surface),
  // in key order: keys, order (the hit of each key) and rows (each hit's key place).
  std::vector<double> history_for(int m, const std::vector<Hit>& hits, std::vector<HistoryStore::Key>& keys,
                                  std::vector<int>& order, std::vector<int>& rows) const;
  WallBatch batch(int m, const std::vector<Hit>& hits, std::vector<double>& cols, std::vector<int>& atoms,
                  const std::vector<int>& rows, double* hist);
  // Core's sums of the reaction on each mesh (this pass): f_ID, and force and
  // torque about the reference point of the grains in the mesh fix's group.
  std::vector<AtomSum<9>> sums_;
  std::vector<Vec3d> ref_world_;  // each mesh's reference point this pass
  void sum_loads(int m, const AtomRange& r, const Part::PerMesh& pm);
};

}  // namespace sable
