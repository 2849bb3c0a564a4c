// compute ID group property/atom attr1 attr2 ...
// Per-atom copies of atom attributes (LIGGGHTS 3.8 / LAMMPS): with one
// attribute a per-atom vector (c_ID), with several a per-atom array (c_ID[k]),
// zero for atoms outside the group. The attributes are the dump custom words
// that LIGGGHTS' property/atom also knows (id type mass x y z xs.. xu.. ix..
// vx.. fx.. omegax.. tqx.. radius diameter). This is how a LIGGGHTS deck feeds
// atom attributes to compute reduce (which there takes only x..fz, c_, f_, v_):
// compute pz all property/atom z + compute zmax all reduce max c_pz.
#include <algorithm>
#include <set>

#include "core/io/dump_columns.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

class ComputePropertyAtom : public Compute {
 public:
  ComputePropertyAtom(Simulation& s, const Args& a) : Compute(s, a) {
    if (a.size() < 5) a.fail(4, "at least one atom attribute: " + words());
    for (std::size_t i = 4; i < a.size(); ++i) {
      if (!known(a[i])) a.fail(i, unsupported(a[i]));
      cols_.push_back(parse_atom_column(s, a, i));
    }
    peratom_flag = true;
    peratom_cols = cols_.size() == 1 ? 0 : static_cast<int>(cols_.size());
  }

  void compute_peratom() override {
    const Atoms& at = sim.atoms;
    std::vector<std::size_t> sel;
    for (std::size_t i = 0; i < at.n; ++i)
      if (at.mask[i] & groupbit) sel.push_back(i);
    const std::size_t nc = cols_.size();
    peratom.assign(at.n * nc, 0.0);
    std::vector<double> v;
    for (std::size_t c = 0; c < nc; ++c) {
      gather_atom_column(sim, cols_[c], sel, v);
      for (std::size_t j = 0; j < sel.size(); ++j) peratom[sel[j] * nc + c] = v[j];
    }
  }

 private:
  std::vector<AtomColumn> cols_;

  static constexpr const char* kWords[] = {
      "id", "type", "mass", "x", "y", "z", "xs", "ys", "zs", "xu", "yu", "zu", "ix", "iy", "iz",
      "vx", "vy", "vz", "fx", "fy", "fz", "omegax", "omegay", "omegaz", "tqx", "tqy", "tqz", "radius", "diameter"};
  static std::string words() {
    std::string s;
    for (const char* w : kWords) s += (s.empty() ? "" : ", ") + std::string(w);
    return s;
  }
  static bool known(const std::string& w) {
    return std::find(std::begin(kWords), std::end(kWords), w) != std::end(kWords);
  }
  // LIGGGHTS attributes that sable's spheres do not carry, named as such.
  static std::string unsupported(const std::string& w) {
    static const std::set<std::string> absent = {"mol",     "q",       "mux",     "muy",    "muz",    "mu",
                                                 "angmomx", "angmomy", "angmomz", "shapex", "shapey", "shapez",
                                                 "quatw",   "quati",   "quatj",   "quatk"};
    if (absent.count(w) || w.starts_with("end") || w.starts_with("corner") || w.starts_with("i_") ||
        w.starts_with("d_"))
      return "an attribute of sable's spheres ('" + w + "' is a LIGGGHTS attribute of other atom styles): " + words();
    return "an atom attribute: " + words();
  }
};

}  // namespace

SABLE_COMPUTE("property/atom", ComputePropertyAtom);

}  // namespace sable
