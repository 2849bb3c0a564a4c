// dump ID group mesh/vtk N file [output face] [ID-KEYWORDS ...] [MESHID ...]
// dump ID group mesh/gran/VTK N file [ID-KEYWORDS ...] [MESHID ...]
// The current triangles of the listed fix mesh/surface (all when none is
// listed) as legacy ASCII VTK POLYDATA, one file per snapshot ('*' in the name
// becomes the step; without '*' each snapshot overwrites the file), with cell
// data: the mesh's index in the list and its material type, and per LIGGGHTS'
// dump identifiers: `id` (the triangle's index in its mesh), `stress`
// (normal_stress_average |f.n|/A and shear_stress_average |f - (f.n)n|/A of the
// grains' force f on the triangle in the last force pass, LIGGGHTS 3.8's names and
// values), `stresscomponents` (f/A), `vel` (the wall velocity at its centroid),
// `area`, `wear` (the mesh's Finnie wear, fix mesh/surface ... wear finnie; 0
// without). LIGGGHTS 3.8 writes the same fields for both styles. LIGGGHTS'
// `output face` is what is written; other outputs and identifiers (owner, aedges,
// acorners, nneighs) are refused. The group is ignored.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/io/dump.h"
#include "core/io/dump_meshes.h"
#include "core/engine/error.h"
#include "core/geometry/mesh.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

class DumpMeshVtk : public Dump {
 public:
  DumpMeshVtk(Simulation& s, const Args& a) : Dump(s, a) {
    std::size_t i = 6;
    for (; i < a.size() && meshes_.ids.empty(); ++i) {
      const std::string& w = a[i];
      if (w == "output") {
        if (a.word(i + 1, "face (the output sable writes)") != "face")
          a.fail(i + 1, "face (sable writes cell data; interpolate and original are not supported)");
        ++i;
      } else if (bool* field = identifier(w)) {
        *field = true;
      } else if (w == "owner" || w == "aedges" || w == "acorners" || w == "nneighs") {
        a.fail(i, "a dump identifier sable writes: id, stress, stresscomponents, vel, area, wear ('" + w + "' is not supported)");
      } else {
        meshes_.name(s, a, i, "a dump identifier (id, stress, stresscomponents, vel, area, wear) or the ID of a fix mesh/surface");
      }
    }
    for (; i < a.size(); ++i) meshes_.name(s, a, i);
  }
  void init() override { meshes_.find(sim, args, style); }

 protected:
  void write_snapshot(long step, const std::string& path, bool) override {
    FILE* f = std::fopen(path.c_str(), "wb");  // one snapshot per file: VTK holds one
    if (!f) fail("dump " + style + ": cannot open '" + path + "' for writing");
    std::size_t ntri = 0;
    for (auto& [fix, m] : meshes_.meshes) {
      m->update_pose();
      ntri += m->mesh().ntri();
    }
    std::fprintf(f, "# vtk DataFile Version 2.0\nsable meshes, step %ld\nASCII\nDATASET POLYDATA\nPOINTS %zu double\n", step,
                 3 * ntri);
    for (auto& [fix, m] : meshes_.meshes) {
      const TriMesh& mesh = m->mesh();
      for (std::size_t t = 0; t < mesh.ntri(); ++t)
        for (int k = 0; k < 3; ++k) {
          const Vec3d p = mesh.to_world(mesh.corner(static_cast<int>(t), k));
          std::fprintf(f, "%.15g %.15g %.15g\n", p[0], p[1], p[2]);
        }
    }
    std::fprintf(f, "POLYGONS %zu %zu\n", ntri, 4 * ntri);
    for (std::size_t t = 0; t < ntri; ++t) std::fprintf(f, "3 %zu %zu %zu\n", 3 * t, 3 * t + 1, 3 * t + 2);
    std::fprintf(f, "CELL_DATA %zu\nSCALARS mesh int 1\nLOOKUP_TABLE default\n", ntri);
    for (std::size_t m = 0; m < meshes_.meshes.size(); ++m)
      for (std::size_t t = 0; t < meshes_.meshes[m].second->mesh().ntri(); ++t) std::fprintf(f, "%zu\n", m);
    std::fprintf(f, "SCALARS type int 1\nLOOKUP_TABLE default\n");
    for (auto& [fix, m] : meshes_.meshes)
      for (std::size_t t = 0; t < m->mesh().ntri(); ++t) std::fprintf(f, "%d\n", m->wall_type());
    write_fields(f);
    if (std::fclose(f) != 0) fail("dump " + style + ": writing '" + path + "' failed");
  }

 private:
  DumpedMeshes meshes_;
  bool id_ = false, stress_ = false, components_ = false, vel_ = false, area_ = false, wear_ = false;

  // A LIGGGHTS dump identifier sable writes: the field it turns on (nullptr for any other word).
  bool* identifier(const std::string& w) {
    const std::pair<const char*, bool*> known[] = {{"id", &id_},   {"stress", &stress_}, {"stresscomponents", &components_},
                                                   {"vel", &vel_}, {"area", &area_},     {"wear", &wear_}};
    for (auto& [name, field] : known)
      if (w == name) return field;
    return nullptr;
  }

  // fn(mesh, triangle) -> the values of one cell, for every triangle of every mesh.
  template <class Fn>
  void cells(FILE* f, const char* head, Fn fn) {
    std::fprintf(f, "%s", head);
    for (auto& [fix, m] : meshes_.meshes)
      for (std::size_t t = 0; t < m->mesh().ntri(); ++t) fn(m->mesh(), static_cast<int>(t));
  }
  static Vec3d load(const TriMesh& m, int t) {
    if (m.tri_force.size() != 3 * m.ntri()) return {0, 0, 0};
    return {m.tri_force[3 * t], m.tri_force[3 * t + 1], m.tri_force[3 * t + 2]};
  }
  void write_fields(FILE* f) {
    if (id_) cells(f, "SCALARS id int 1\nLOOKUP_TABLE default\n", [&](const TriMesh&, int t) { std::fprintf(f, "%d\n", t); });
    if (area_)
      cells(f, "SCALARS area double 1\nLOOKUP_TABLE default\n",
            [&](const TriMesh& m, int t) { std::fprintf(f, "%.15g\n", m.area(t)); });
    if (stress_) {
      auto normal_part = [](const TriMesh& m, int t, const Vec3d& fo) {
        const Vec3d n = m.dir_to_world({m.normal[3 * t], m.normal[3 * t + 1], m.normal[3 * t + 2]});
        return fo[0] * n[0] + fo[1] * n[1] + fo[2] * n[2];
      };
      cells(f, "SCALARS normal_stress_average double 1\nLOOKUP_TABLE default\n", [&](const TriMesh& m, int t) {
        std::fprintf(f, "%.15g\n", std::fabs(normal_part(m, t, load(m, t))) / m.area(t));
      });
      cells(f, "SCALARS shear_stress_average double 1\nLOOKUP_TABLE default\n", [&](const TriMesh& m, int t) {
        const Vec3d fo = load(m, t);
        const double fn = normal_part(m, t, fo), f2 = fo[0] * fo[0] + fo[1] * fo[1] + fo[2] * fo[2];
        std::fprintf(f, "%.15g\n", std::sqrt(std::max(0.0, f2 - fn * fn)) / m.area(t));
      });
    }
    if (wear_)
      cells(f, "SCALARS wear double 1\nLOOKUP_TABLE default\n",
            [&](const TriMesh& m, int t) { std::fprintf(f, "%.15g\n", m.wear.empty() ? 0.0 : m.wear[t]); });
    if (components_)
      cells(f, "VECTORS stress double\n", [&](const TriMesh& m, int t) {
        const Vec3d fo = load(m, t);
        const double a = m.area(t);
        std::fprintf(f, "%.15g %.15g %.15g\n", fo[0] / a, fo[1] / a, fo[2] / a);
      });
    if (vel_)
      cells(f, "VECTORS velocity double\n", [&](const TriMesh& m, int t) {
        Vec3d c{0, 0, 0};
        for (int k = 0; k < 3; ++k) {
          const Vec3d p = m.to_world(m.corner(t, k));
          for (int e = 0; e < 3; ++e) c[e] += p[e] / 3.0;
        }
        const Vec3d v = m.velocity(c, t);
        std::fprintf(f, "%.15g %.15g %.15g\n", v[0], v[1], v[2]);
      });
  }
};

SABLE_DUMP("mesh/vtk", DumpMeshVtk);
SABLE_DUMP("mesh/gran/VTK", DumpMeshVtk);

}  // namespace sable
