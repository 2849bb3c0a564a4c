#pragma once
// What dump mesh/stl and mesh/vtk share: the fix mesh/surface they write,
// named by ID at the end of the dump command or, when none is named, all.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/engine/simulation.h"
#include "core/geometry/mesh.h"
#include "core/input/args.h"

namespace sable {

struct DumpedMeshes {
  std::vector<std::string> ids;                             // as named; empty: every mesh
  std::vector<std::pair<std::string, MeshHolder*>> meshes;  // from init: fix ID, its mesh, in the fixes' order

  // Word i as the ID of a fix mesh/surface; else an error there expecting `what`.
  void name(Simulation& s, const Args& a, std::size_t i, const std::string& what = "the ID of a fix mesh/surface") {
    if (!dynamic_cast<MeshHolder*>(s.find_fix(a[i]))) a.fail(i, what);
    ids.push_back(a[i]);
  }
  // At each init (fixes come and go between runs); an error when there is none.
  void find(Simulation& s, const Args& a, const std::string& style) {
    meshes.clear();
    for (auto& f : s.fixes)
      if (auto* m = dynamic_cast<MeshHolder*>(f.get()))
        if (ids.empty() || std::find(ids.begin(), ids.end(), f->id) != ids.end()) meshes.push_back({f->id, m});
    if (meshes.empty()) a.fail_line("dump " + style + ": no fix mesh/surface to write");
  }
};

}  // namespace sable
