#include "fixes/fix_property_global.h"

#include <cmath>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

FixPropertyGlobal::FixPropertyGlobal(Simulation& s, const Args& a) : Fix(s, a) {
  line = &args;
  name = a.word(4, "a property name (e.g. youngsModulus)");
  style_word = a.word(5, "a style: scalar, vector, peratomtype, matrix or peratomtypepair");
  const std::string& st = style_word;
  std::size_t first = 6;
  if (st == "scalar") {
    kind = Kind::Scalar;
  } else if (st == "vector" || st == "atomtype" || st == "peratomtype") {
    kind = Kind::Vector;
  } else if (st == "matrix" || st == "atomtypepair" || st == "peratomtypepair") {
    kind = Kind::Matrix;
    symmetric = st != "matrix";
    const long nc = a.integer(6, symmetric ? "the number of atom types N (then N*N values)" : "the number of columns");
    if (nc < 1) a.fail(6, "a number of columns >= 1");
    ncols = static_cast<int>(nc);
    first = 7;
  } else {
    a.fail(5, "a style: scalar, vector, atomtype/peratomtype, matrix or atomtypepair/peratomtypepair");
  }
  for (std::size_t i = first; i < a.size(); ++i) values.push_back(a.num(i, "a value of " + name));

  const std::size_t nv = values.size();
  if (nv == 0) a.fail(a.size(), "at least one value for " + name);
  if (kind == Kind::Scalar && nv != 1) a.fail(first + 1, "exactly one value for scalar " + name);
  if (kind == Kind::Matrix) {
    const std::size_t n = ncols;
    if (symmetric && nv != n * n) {
      // Name the word where the count goes wrong: N itself when values are missing, else the first surplus value.
      a.fail(nv < n * n ? 6 : first + n * n,
             "N*N = " + std::to_string(n * n) + " values after N = " + std::to_string(n) + " atom types, got " +
                 std::to_string(nv));
    }
    if (!symmetric && nv % n != 0)
      a.fail(a.size(), "a multiple of " + std::to_string(n) + " values (whole rows), got " + std::to_string(nv));
    if (symmetric)
      for (std::size_t r = 0; r < n; ++r)
        for (std::size_t c = r + 1; c < n; ++c)
          if (values[r * n + c] != values[c * n + r])
            a.fail(first + c * n + r, "a symmetric per-type-pair matrix (value " + std::to_string(c + 1) + "," +
                                          std::to_string(r + 1) + " must equal value " + std::to_string(r + 1) +
                                          "," + std::to_string(c + 1) + " = " + a[first + r * n + c] + ")");
  }
  // LIGGGHTS refuses two property/global fixes with the same variable name (a new fix with the same ID replaces).
  for (auto& f : s.fixes)
    if (auto* p = dynamic_cast<FixPropertyGlobal*>(f.get()); p && p->id != id && p->name == name)
      a.fail(4, "a property name not defined yet (fix " + p->id + " already defines " + name + ")");
  if (kind == Kind::Scalar) scalar_flag = 1;
  else vector_size = static_cast<int>(nv);
}

double FixPropertyGlobal::compute_vector(int i) {
  if (i < 1 || i > static_cast<int>(values.size()))
    args.fail_line("f_" + id + "[" + std::to_string(i) + "]: index out of range 1.." + std::to_string(values.size()));
  return values[i - 1];
}

SABLE_FIX("property/global", FixPropertyGlobal);

}  // namespace sable
