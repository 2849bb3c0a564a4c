// dump ID group custom N file col ...: the LIGGGHTS/LAMMPS text dump, byte for
// byte (ITEM: lines, %g values, a trailing space after every value, as LIGGGHTS 3.8 writes).
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <numeric>

#include "core/io/dump_columns.h"
#include "core/io/dump_file.h"
#include "core/input/style_registry.h"
#include "core/io/yade_script.h"

namespace sable {
namespace {

// One printf conversion for one value, checked when the deck gives it so a bad
// format fails at its line instead of crashing snprintf mid-run.
struct ValueFormat {
  std::string spec;    // with an `l` length modifier for integer conversions
  bool integer = false;
};

bool parse_value_format(const std::string& s, ValueFormat& out) {
  std::string r;
  int conversions = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    r += s[i];
    if (s[i] != '%') continue;
    if (i + 1 < s.size() && s[i + 1] == '%') {  // literal %
      r += s[++i];
      continue;
    }
    std::size_t j = i + 1;
    while (j < s.size() && std::strchr("-+ #0123456789.", s[j])) r += s[j++];
    while (j < s.size() && std::strchr("hlLqjzt", s[j])) ++j;  // drop length modifiers; we choose our own
    if (j >= s.size()) return false;
    const char c = s[j];
    if (std::strchr("diouxX", c)) {
      out.integer = true;
      r += 'l';
    } else if (!std::strchr("eEfFgGaA", c)) {
      return false;  // %s, %n, %p ... cannot print a number safely
    }
    r += c;
    i = j;
    ++conversions;
  }
  out.spec = r;
  return conversions == 1;
}

class DumpCustom : public Dump {
 public:
  DumpCustom(Simulation& s, const Args& a) : Dump(s, a) {
    a.need(7, "at least one per-atom attribute after the file name");
    for (std::size_t i = 6; i < a.size(); ++i) {
      cols_.push_back(parse_atom_column(s, a, i));
      header_ += a[i] + " ";
    }
    fmt_.resize(cols_.size());
  }

  void export_yade(YadeScript& s) const override;
  bool modify_param(const Args& a, std::size_t& i) override {
    const std::string& k = a[i];
    if (k == "sort" && i + 1 < a.size() && a[i + 1] != "id" && a[i + 1] != "off") {
      // sort N / -N: by the Nth column, ascending / descending
      const long n = a.integer(i + 1, "id, off, N or -N (a column number)");
      if (n == 0 || std::labs(n) > static_cast<long>(cols_.size()))
        a.fail(i + 1, "a column number in 1.." + std::to_string(cols_.size()) + " (or its negative)");
      sort_col_ = static_cast<int>(n);
      sort_by_id = false;
      i += 2;
      return true;
    }
    if (k == "sort") sort_col_ = 0;
    if (Dump::modify_param(a, i) || filter_.parse(sim, a, i)) return true;
    if (k == "format") {
      parse_format(a, i);
      return true;
    }
    if (k == "append") {
      append_file_ = a.yes_no(i + 1, "yes or no");
    } else if (k == "flush" || k == "buffer") {
      a.yes_no(i + 1, "yes or no");  // every snapshot is written and flushed in one write() anyway
    } else {
      return false;
    }
    i += 2;
    return true;
  }

 protected:
  void write_snapshot(long step, const std::string& path, bool append) override {
    // A new run starting where the last one ended would repeat that snapshot; LAMMPS writes it once.
    if (!multifile && append && step == last_step_) return;
    last_step_ = step;
    std::vector<std::size_t> sel = selected_atoms();
    filter_.apply(sim, sel);
    const std::size_t nc = cols_.size();
    std::vector<std::vector<double>> vals(nc);
    for (std::size_t c = 0; c < nc; ++c) gather_atom_column(sim, cols_[c], sel, vals[c]);
    std::vector<double> ids;  // several ranks: every grain's id, for the order by id
    if (sim.comm.distributed && !to_rank_zero(sel, vals, ids)) return;
    const std::size_t n = vals.empty() ? 0 : vals[0].size();
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    if (sort_by_id && !ids.empty())
      std::stable_sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return ids[p] < ids[q]; });
    if (sort_col_) {
      const auto& key = vals[std::labs(sort_col_) - 1];
      std::stable_sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) {
        return sort_col_ > 0 ? key[p] < key[q] : key[p] > key[q];
      });
    }

    // The whole snapshot goes out in one write(): earlier snapshots are never touched again; a kill
    // -9 can still cut the one in flight (the kernel may stop a write between pages).
    std::string out;
    out.reserve(200 + n * nc * 14);
    char buf[256];
    append_snapshot_head(out, sim.domain, step, "NUMBER OF ATOMS", n);
    out += "ITEM: ATOMS " + header_ + "\n";
    for (std::size_t r : order) {
      for (std::size_t c = 0; c < nc; ++c) {
        const double v = vals[c][r];
        const ValueFormat& f = fmt_[c];
        int len;
        if (f.spec.empty())
          len = cols_[c].integer() ? std::snprintf(buf, sizeof buf, "%ld ", static_cast<long>(v))
                                   : std::snprintf(buf, sizeof buf, "%g ", v);
        else
          len = f.integer ? std::snprintf(buf, sizeof buf, f.spec.c_str(), static_cast<long>(v))
                          : std::snprintf(buf, sizeof buf, f.spec.c_str(), v);
        out.append(buf, std::min<std::size_t>(std::max(len, 0), sizeof buf - 1));
        if (!f.spec.empty()) out += ' ';
      }
      out += '\n';
    }

    file_.write(out, path, !multifile && (append || append_file_), multifile, id);
  }

 private:
  // format "STR" (LIGGGHTS: one conversion per column), or the LAMMPS forms
  // format line "STR" | int FMT | float FMT | N FMT | none.
  void parse_format(const Args& a, std::size_t& i) {
    const std::string& w = a.word(i + 1, "a format string, or line/int/float/N FMT, or none");
    auto one = [&](std::size_t at) {
      ValueFormat f;
      if (!parse_value_format(a.word(at, "a printf format"), f))
        a.fail(at, "a printf format with exactly one numeric conversion (%d, %g, %e, %f, ...)");
      return f;
    };
    long col;
    if (w == "none") {
      std::fill(fmt_.begin(), fmt_.end(), ValueFormat{});
      i += 2;
    } else if (w == "int" || w == "float") {
      const ValueFormat f = one(i + 2);
      for (std::size_t c = 0; c < cols_.size(); ++c)
        if (cols_[c].integer() == (w == "int")) fmt_[c] = f;
      i += 3;
    } else if (parse_long(w, col)) {
      if (col < 1 || col > static_cast<long>(cols_.size()))
        a.fail(i + 1, "a column number in 1.." + std::to_string(cols_.size()));
      fmt_[col - 1] = one(i + 2);
      i += 3;
    } else {
      const std::size_t at = w == "line" ? i + 2 : i + 1;
      Args words(split(a.word(at, "a format string")), a.where());
      if (words.size() < cols_.size())
        a.fail(at, "a format string with one conversion per column (" + std::to_string(cols_.size()) + " columns)");
      for (std::size_t c = 0; c < cols_.size(); ++c) {
        ValueFormat f;
        if (!parse_value_format(words[c], f))
          a.fail(at, "one printf conversion per column ('" + words[c] + "' is not one numeric conversion)");
        fmt_[c] = f;
      }
      i = at + 1;
    }
  }
  static std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> w;
    std::size_t p = 0;
    while ((p = s.find_first_not_of(" \t", p)) != std::string::npos) {
      const std::size_t e = s.find_first_of(" \t", p);
      w.push_back(s.substr(p, e - p));
      p = e;
    }
    return w;
  }

  // Several ranks: every rank's rows (and ids) to rank 0, in rank order; false on the
  // other ranks, which write nothing.
  bool to_rank_zero(const std::vector<std::size_t>& sel, std::vector<std::vector<double>>& vals,
                    std::vector<double>& ids) const {
    const std::size_t nc = vals.size(), w = nc + 1;
    std::vector<double> mine, all;
    mine.reserve(sel.size() * w);
    for (std::size_t r = 0; r < sel.size(); ++r) {
      mine.push_back(static_cast<double>(sim.atoms.id[sel[r]]));
      for (std::size_t c = 0; c < nc; ++c) mine.push_back(vals[c][r]);
    }
    sim.comm.gather(mine, all);
    if (sim.comm.rank() != 0) return false;
    const std::size_t rows = all.size() / w;
    ids.resize(rows);
    for (auto& v : vals) v.resize(rows);
    for (std::size_t r = 0; r < rows; ++r) {
      ids[r] = all[r * w];
      for (std::size_t c = 0; c < nc; ++c) vals[c][r] = all[r * w + 1 + c];
    }
    return true;
  }

  std::vector<AtomColumn> cols_;
  std::vector<ValueFormat> fmt_;  // empty spec: LIGGGHTS default (%d / %g)
  std::string header_;            // "id type x ... " with LIGGGHTS' trailing space
  DumpFilter filter_;
  int sort_col_ = 0;              // dump_modify sort N (>0 ascending, <0 descending)
  bool append_file_ = false;      // dump_modify append yes: keep an existing file
  DumpFile file_;
  long last_step_ = -1;
};

}  // namespace

// --export-yade: a _DumpCustom recorder (the script's head) writing this dump's
// text on YADE's bodies: the same schedule, header, box, %g / %d values with a
// trailing space (or the dump_modify format), rows in id order (sable: memory
// order unless dump_modify sort id). Forces add m g to YADE's contact forces
// (sable's f holds fix gravity's).
void DumpCustom::export_yade(YadeScript& s) const {
  const Args& a = args;  // dump ID group custom N file cols... (a[0]: the command)
  if (s.boundary.find_first_of("sm") != std::string::npos)
    s.refuse(a, "a dump with shrink-wrapped boundaries (boundary " + s.boundary +
                    ") writes a box YADE does not have; not translated");
  static const std::map<std::string, std::string> kCol{
      {"id", "i"}, {"type", "_type[i]"}, {"mass", "_m[i]"}, {"radius", "_b(i).shape.radius"},
      {"diameter", "2 * _b(i).shape.radius"}, {"x", "_pos(i, 0)"}, {"y", "_pos(i, 1)"}, {"z", "_pos(i, 2)"},
      {"vx", "_b(i).state.vel[0]"}, {"vy", "_b(i).state.vel[1]"}, {"vz", "_b(i).state.vel[2]"},
      {"omegax", "_b(i).state.angVel[0]"}, {"omegay", "_b(i).state.angVel[1]"}, {"omegaz", "_b(i).state.angVel[2]"}};
  std::vector<std::string> cols, fmts;
  for (std::size_t k = 6; k < a.size(); ++k) {
    const std::string& w = a[k];
    const bool force = w == "fx" || w == "fy" || w == "fz";
    if (!force && !kCol.count(w))
      a.fail(k, "a dump column export-yade translates: id, type, mass, radius, diameter, x, y, z, vx, vy, vz, fx, fy, "
                "fz, omegax, omegay, omegaz");
    const int c = force ? w[1] - 'x' : 0;
    cols.push_back(force ? "O.forces.f(_bid(i), sync=True)[" + std::to_string(c) + "] + _m[i] * " +
                               yade_num(s.gravity()[c])
                         : kCol.at(w));
    fmts.push_back(w == "id" || w == "type" ? "%d " : "%g ");
  }
  for (const Args& m : s.dump_mods[id]) {
    for (std::size_t k = 2; k < m.size();) {
      if (m[k] == "sort" && m.word(k + 1, "id") == "id") {
        k += 2;
      } else if (m[k] == "format") {
        const std::size_t at = m.word(k + 1, "a format string") == "line" ? k + 2 : k + 1;
        std::istringstream words(m.word(at, "a format string"));
        for (std::size_t c = 0; c < fmts.size(); ++c) {
          std::string w;
          words >> w;
          fmts[c] = yade_python_format(w) + " ";
        }
        k = at + 1;
      } else {
        m.fail(k, "a dump_modify keyword export-yade translates: format \"...\" (or format line \"...\"), sort id");
      }
    }
  }
  const std::vector<std::size_t> members = [&] {
    std::vector<std::size_t> v;
    for (std::size_t i = 0; i < sim.atoms.n; ++i)
      if (sim.atoms.mask[i] & groupbit) v.push_back(i);
    return v;
  }();
  const std::string box = s.dump_box();
  s.py << "# " << a.where().file << ":" << a.where().line << ": dump " << id << " custom\n"
       << "_recorders.append(_DumpCustom(" << yade_quoted(id) << ", " << yade_quoted(file) << ", " << every << ", [";
  std::vector<long> ids;
  for (std::size_t i : members) ids.push_back(sim.atoms.id[i]);
  std::sort(ids.begin(), ids.end());
  for (long i : ids) s.py << i << ", ";
  s.py << "], " << yade_quoted(box) << ", " << yade_quoted("ITEM: ATOMS " + header_ + "\n") << ", [";
  for (std::size_t c = 0; c < cols.size(); ++c)
    s.py << "(" << yade_quoted(fmts[c]) << ", lambda i: " << cols[c] << "), ";
  s.py << "]))\n";
}

SABLE_DUMP("custom", DumpCustom);

}  // namespace sable
