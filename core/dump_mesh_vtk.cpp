// dump ID group mesh/vtk N file [MESHID ...]
// The current triangles of the listed fix mesh/surface (all when none is
// listed) as legacy ASCII VTK POLYDATA, one file per snapshot ('*' in the name
// becomes the step; without '*' each snapshot overwrites the file), with cell
// data: the mesh's index in the list and its material type. ParaView opens it.
// The group is ignored.
#include <algorithm>
#include <cstdio>

#include "core/dump.h"
#include "core/error.h"
#include "core/mesh.h"
#include "core/simulation.h"
#include "core/style_registry.h"

namespace sable {

class DumpMeshVtk : public Dump {
 public:
  DumpMeshVtk(Simulation& s, const Args& a) : Dump(s, a) {
    for (std::size_t i = 6; i < a.size(); ++i) {
      if (!dynamic_cast<MeshHolder*>(s.find_fix(a[i]))) a.fail(i, "the ID of a fix mesh/surface");
      ids_.push_back(a[i]);
    }
  }
  void init() override {
    meshes_.clear();
    for (auto& f : sim.fixes)
      if (auto* m = dynamic_cast<MeshHolder*>(f.get()))
        if (ids_.empty() || std::find(ids_.begin(), ids_.end(), f->id) != ids_.end()) meshes_.push_back(m);
    if (meshes_.empty()) args.fail_line("dump mesh/vtk: no fix mesh/surface to write");
  }

 protected:
  void write_snapshot(long step, const std::string& path, bool) override {
    FILE* f = std::fopen(path.c_str(), "wb");  // one snapshot per file: VTK holds one
    if (!f) fail("dump mesh/vtk: cannot open '" + path + "' for writing");
    std::size_t ntri = 0;
    for (MeshHolder* m : meshes_) {
      m->update_pose();
      ntri += m->mesh().ntri();
    }
    std::fprintf(f, "# vtk DataFile Version 2.0\nsable meshes, step %ld\nASCII\nDATASET POLYDATA\nPOINTS %zu double\n", step,
                 3 * ntri);
    for (MeshHolder* m : meshes_) {
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
    for (std::size_t m = 0; m < meshes_.size(); ++m)
      for (std::size_t t = 0; t < meshes_[m]->mesh().ntri(); ++t) std::fprintf(f, "%zu\n", m);
    std::fprintf(f, "SCALARS type int 1\nLOOKUP_TABLE default\n");
    for (MeshHolder* m : meshes_)
      for (std::size_t t = 0; t < m->mesh().ntri(); ++t) std::fprintf(f, "%d\n", m->wall_type());
    if (std::fclose(f) != 0) fail("dump mesh/vtk: writing '" + path + "' failed");
  }

 private:
  std::vector<std::string> ids_;
  std::vector<MeshHolder*> meshes_;
};

SABLE_DUMP("mesh/vtk", DumpMeshVtk);

}  // namespace sable
