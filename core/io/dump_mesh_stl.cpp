// dump ID group mesh/stl N file [MESHID ...]
// The current triangles (moved by move/mesh) of the listed fix mesh/surface
// (all of them when none is listed) as ASCII STL, one solid per mesh per
// snapshot (ParaView and any CAD tool open it). With '*' in the name, one file
// per snapshot; else snapshots are appended, as LIGGGHTS does. The group is ignored.
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

#include "core/io/dump.h"
#include "core/io/dump_meshes.h"
#include "core/engine/error.h"
#include "core/geometry/mesh.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

class DumpMeshStl : public Dump {
 public:
  DumpMeshStl(Simulation& s, const Args& a) : Dump(s, a) {
    for (std::size_t i = 6; i < a.size(); ++i) meshes_.name(s, a, i);
  }
  void init() override { meshes_.find(sim, args, style); }

 protected:
  void write_snapshot(long step, const std::string& path, bool append) override {
    FILE* f = std::fopen(path.c_str(), append ? "ab" : "wb");
    if (!f) fail("dump mesh/stl: cannot open '" + path + "' for writing");
    for (auto& [id, m] : meshes_.meshes) {
      m->update_pose();
      const TriMesh& mesh = m->mesh();
      std::fprintf(f, "solid %s_step_%ld\n", id.c_str(), step);
      for (std::size_t t = 0; t < mesh.ntri(); ++t) {
        const Vec3d n = mesh.dir_to_world({mesh.normal[3 * t], mesh.normal[3 * t + 1], mesh.normal[3 * t + 2]});
        std::fprintf(f, "  facet normal %.10g %.10g %.10g\n    outer loop\n", n[0], n[1], n[2]);
        for (int k = 0; k < 3; ++k) {
          const Vec3d p = mesh.to_world(mesh.corner(static_cast<int>(t), k));
          std::fprintf(f, "      vertex %.15g %.15g %.15g\n", p[0], p[1], p[2]);
        }
        std::fprintf(f, "    endloop\n  endfacet\n");
      }
      std::fprintf(f, "endsolid %s_step_%ld\n", id.c_str(), step);
    }
    if (std::fclose(f) != 0) fail("dump mesh/stl: writing '" + path + "' failed");
  }

 private:
  DumpedMeshes meshes_;
};

SABLE_DUMP("mesh/stl", DumpMeshStl);

}  // namespace sable
