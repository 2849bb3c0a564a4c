#pragma once
// The YADE script that sable --export-yade writes (tools/export_yade.h). The
// writer knows no style names: each style adds its own translation through
// its export_yade(YadeScript&) (core/engine/fix.h, pair.h, dump.h, compute.h) next to
// the style, or refuses at its deck line. Kept here: the Python helpers
// (head()), the deck-order bookkeeping (variables, thermo, dumps), the
// translation of equal-style expressions, and the scene's lists (materials,
// walls, meshes, grains, clumps, engines, recorders) the styles fill in.
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/input/args.h"
#include "core/geometry/mesh.h"
#include "core/io/yade_clumps.h"

namespace sable {

class Simulation;
class Fix;
class Compute;

// A number as the script writes it (%.17g: the double round-trips).
std::string yade_num(double v);
// A Python string literal.
std::string yade_quoted(const std::string& s);
// A C format of one column as Python's % operator takes it (%ld -> %d).
std::string yade_python_format(const std::string& spec);

class YadeScript {
 public:
  explicit YadeScript(Simulation& sim) : sim(sim) {}
  Simulation& sim;
  std::ostringstream py;  // the script after head(), in deck order

  std::string script() const { return head() + py.str() + "print('Loop time: done')\n"; }
  // A refusal naming the deck line of `where`: "export-yade: " + why.
  [[noreturn]] void refuse(const Args& where, const std::string& why) const { where.fail_line("export-yade: " + why); }

  // ---- the deck-order bookkeeping (tools/export_yade.cpp fills it in)
  std::map<std::string, std::string> formulas;  // equal-style variables, as defined
  std::set<std::string> snaps;                  // variable NAME equal $(cpu): _snap[NAME], the script's clock then
  std::vector<std::string> thermo_cols{"step"};
  long thermo_every = 0;
  std::string boundary;                         // the boundary command's styles, as written
  std::set<std::string> dumps_done;             // dumps already recorders (at an earlier run)
  std::map<std::string, std::vector<Args>> dump_mods;  // dump_modify lines per dump ID
  const Args* first_run = nullptr;              // the scene's run: errors of what the scene holds name it

  // ---- expressions: a LAMMPS equal-style formula as Python evaluated in YADE
  std::string translate(const std::string& expr, const Args& at, int depth = 0) const;
  std::string ids_of(std::uint32_t bits) const;  // the atom ids of a group, a Python list
  std::string dump_box() const;                  // a text dump's ITEM: BOX BOUNDS lines

  // ---- the contact law (the pair style's export_yade)
  std::string model;         // hertz or linear/kneib
  bool limit_force = false;  // limitForce on in the deck (YADE's Mindlin law clips anyway)

  // ---- what fixes add, in deck order
  void integrate(std::uint32_t groupbit);  // the group's grains move on their own (nve/sphere, move)
  void rotate() { rotation_ = true; }      // grains turn (else YADE's blockedDOFs lock XYZ)
  void freeze(const Fix& f);               // fixed grains; f_ID[1-3] their force
  void block(std::size_t i, const std::string& dofs) { blocked_[i] += dofs; }
  void add_gravity(const double g[3]);
  const double* gravity() const { return gravity_; }
  void add_force(const std::string& python) { forces_.push_back(python); }  // each step, before the integrator
  void add_move(const std::string& python) { moves_.push_back(python); }    // once, after the grains are made
  void set_forces(const Fix& f, const std::string& python);  // aveforce/setforce: f_ID[1-3] from _fixf
  // A force component of addforce / aveforce / setforce: number, NULL ("None") or v_name (Python).
  std::string force_component(const Args& a, std::size_t i) const;
  void add_wall(const Fix& f, long type, int axis, double pos);  // a primitive plane
  struct MeshWall {
    const Fix* fix;
    const TriMesh* mesh;
    long type;
    int material = -1;
    std::string motion;  // a YADE kinematic engine on the facets (IDS: their ids), from fix move/mesh
    // One step of that motion, p -> origin + R(axis, angle) (p - origin) + shift:
    // YADE's forces after step n were found where the mesh was after step n - 1
    // (its integrator moves the facets after the force pass), so the mesh torque
    // takes its lever arms there.
    Vec3d shift{0, 0, 0}, origin{0, 0, 0}, axis{0, 0, 1};
    double angle = 0;
  };
  void add_mesh(const Fix& f, const TriMesh& m, long type);  // a fix mesh/surface, facets if a wall uses it
  MeshWall* mesh(const std::string& id);  // nullptr: no such mesh fix translated
  bool wall_uses_mesh(const std::string& id) const;
  void wall_mesh(const std::string& id) { mesh_order_.push_back(id); }  // a wall/gran mesh uses it
  void add_clumps(const Fix& f, const std::vector<yade::Clump>& bodies);  // rigid bodies
  // A recorder written after the engines (fix ave/time: every wall, mesh and body is known then).
  void add_recorder(const Fix& f, std::function<void(YadeScript&)> write);
  bool is_recorder(const std::string& fix_id) const;
  // The index of fix_id's primitive wall in the script's _walls, its axis and position; -1 if none.
  int wall_index(const std::string& fix_id) const;
  int wall_axis(int w) const { return walls_[w].axis; }
  double wall_pos(int w) const { return walls_[w].pos; }

  // ---- the scene, written once at the first run (tools/export_yade.cpp calls these in order)
  void begin_fixes();
  void check_integrated() const;
  void materials();
  void walls();
  void mesh_facets();
  void bodies();
  void engines();
  void recorders();
  void periodic_cell();

 private:
  std::string head() const;
  std::string term(const std::string& name, const std::string& index, const Args& at, int depth) const;
  bool constant(const std::string& formula, int depth) const;
  std::string group_function(const std::string& name, const std::string& args, const Args& at) const;
  double type_value(const std::string& prop, int t, const Args& at) const;
  double pair_value(const std::string& prop, int i, int j, const Args& at) const;
  bool yade_periodic(int k) const;  // periodic in the script's YADE cell (periodic_cell)
  void wall_materials(const Args& pair);
  int hertz_surface_material(const Fix& f, long type, double s, const std::string& note, const Args& pair, int& next_id);
  void periodic_fit(const MeshWall& w, std::size_t t) const;
  int group_mask(const Fix& f);
  void grain_masks(const std::vector<std::size_t>& order);
  void clumps();
  void contact_history();

  struct Wall {
    const Fix* fix;
    long type;
    int axis;
    double pos;
    int material = -1;  // YADE material id
    int mask = 1;       // YADE groupMask: 1 touches every grain; a bit of its own for a group's wall
  };
  std::vector<Wall> walls_;
  std::map<std::string, int> wall_of_fix_;  // fix ID -> index in the script's walls list
  bool boxes_ = false;                      // primitive walls written as thin boxes (a periodic cell)
  int grain_type_ = 1;                      // the one grain type a Hertz wall is matched to
  std::map<std::string, MeshWall> meshes_;  // by mesh fix ID
  std::vector<std::string> mesh_order_;     // meshes a wall/gran uses, in order: the script's _meshes
  // Per atom (by index): fixed (frozen), integrated, in a clump, its blockedDOFs.
  std::vector<char> fixed_, integrated_, in_body_;
  std::vector<std::string> blocked_;
  std::vector<std::string> forces_, moves_;  // python lines run each step / at set-up
  std::map<std::string, std::uint32_t> freeze_bits_;  // fix freeze ID -> its group's bit: f_ID[1-3] its grains' force
  std::set<std::string> set_force_fixes_;  // aveforce / setforce fix IDs: f_ID[1..3] from the script's _fixf
  std::vector<yade::Clump> clumps_;        // rigid bodies (fix rigid, rigid/small, multisphere)
  std::map<std::string, std::pair<std::size_t, std::size_t>> clumps_of_;  // fix ID -> first index in clumps_, count
  std::vector<std::pair<const Fix*, std::function<void(YadeScript&)>>> recorders_;
  double gravity_[3] = {0, 0, 0};
  bool rotation_ = false;
};

}  // namespace sable
