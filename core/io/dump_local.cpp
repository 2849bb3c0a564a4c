// dump ID group local N file value ...: LAMMPS' `dump local` text format
//   ITEM: TIMESTEP / ITEM: NUMBER OF ENTRIES / ITEM: BOX BOUNDS / ITEM: ENTRIES
// with one line per row of the computes' local data (a value is c_ID[k], column
// k of a local compute such as wall/gran/local or pair/gran/local, or `index`,
// the row number from 1; LAMMPS' f_ID[k] is not offered: no sable fix has
// local data). Every value's compute must give the same number of
// rows (LAMMPS' rule). As in LAMMPS the group is not used: the computes' own
// groups pick the contacts. Values print as %g, index as %d, each followed by
// a space (LAMMPS' default formats; `dump_modify ID format float %.17g` or
// `format N FMT` for more digits). A step with no rows writes its header with
// 0 entries.
// A file name ending in .h5 or .hdf5 chooses HDF5 (sable's, for long
// recordings: one file, full precision; LIGGGHTS would write text under that
// name), through core/io/h5_series.h (blocks, readable after a kill):
//   entries [rows, values] (every snapshot's rows one after the other, the
//     values in the deck's order, index as 1, 2, ...; root attribute columns);
//   first, count [snapshots] (each snapshot's first row in entries and its rows);
//   time, step [snapshots] (the time axis: attributes units, timestep).
// No '*' (one file holds every snapshot) and no dump_modify format.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <cstring>
#include <memory>

#include "core/engine/compute.h"
#include "core/io/dump.h"
#include "core/io/dump_file.h"
#include "core/io/h5_series.h"
#include "core/engine/error.h"
#include "core/engine/simulation.h"
#include "core/input/number_format.h"
#include "core/input/style_registry.h"
#include "core/io/yade_script.h"

namespace sable {
namespace {

class DumpLocal : public Dump {
 public:
  DumpLocal(Simulation& s, const Args& a) : Dump(s, a) {
    a.need(7, "at least one value after the file name (c_ID[k] of a local compute, or index)");
    bool any_compute = false;
    for (std::size_t i = 6; i < a.size(); ++i) {
      cols_.push_back(parse(a, i));
      any_compute = any_compute || cols_.back().compute;
      header_ += (i > 6 ? " " : "") + a[i];
    }
    if (!any_compute) a.fail(6, "at least one c_ID[k] (index alone names no contacts)");
    const std::string ext = file.substr(std::min(file.size(), file.find_last_of('.')));
    if (ext == ".h5" || ext == ".hdf5") open_h5(a);
  }

  void init() override {
    for (Column& c : cols_) resolve(args, c);
  }
  void export_yade(YadeScript& s) const override;

  // dump_modify ... format float FMT | format N FMT | format none (LAMMPS' forms for
  // c_ID[k] values: one e/f/g conversion, e.g. %.17g for full precision).
  bool modify_param(const Args& a, std::size_t& i) override {
    if (a[i] == "sort") a.fail(i, "a dump_modify keyword dump local supports (format); LAMMPS cannot sort it by id either");
    if (a[i] != "format") return Dump::modify_param(a, i);
    if (h5_) a.fail(i, "a dump_modify keyword of an HDF5 dump local (it keeps full precision: no format)");
    const std::string& w = a.word(i + 1, "float, a column number or none");
    if (w == "none") {
      for (Column& c : cols_) c.format.clear();
      i += 2;
      return true;
    }
    const std::string& f = a.word(i + 2, "a printf format with one %e, %f or %g conversion");
    if (!number_format_problem(f, false).empty()) a.fail(i + 2, "a printf format with one %e, %f or %g conversion and no other %");
    long n = 0;
    if (w == "float") {
      for (Column& c : cols_) c.format = f;
    } else if (parse_long(w, n) && n >= 1 && n <= static_cast<long>(cols_.size()) && cols_[n - 1].compute) {
      cols_[n - 1].format = f;
    } else {
      a.fail(i + 1, "float, none or the number (1.." + std::to_string(cols_.size()) + ") of a c_ID[k] value");
    }
    i += 3;
    return true;
  }

 protected:
  void write_snapshot(long step, const std::string& path, bool append) override {
    if (!multifile && append && step == last_step_) return;  // a run starting where the last ended
    last_step_ = step;
    const std::size_t n = gather();
    if (h5_) return write_h5(step, n);
    std::string out;
    out.reserve(256 + n * cols_.size() * 14);
    char buf[256];
    append_snapshot_head(out, sim.domain, step, "NUMBER OF ENTRIES", n);
    out += "ITEM: ENTRIES " + header_ + "\n";
    for (std::size_t r = 0; r < n; ++r) {
      for (const Column& c : cols_) {
        if (!c.compute) {
          out += std::to_string(r + 1) + ' ';
          continue;
        }
        const double v = c.compute->local[r * c.compute->local_cols + c.col];
        const int len = std::snprintf(buf, sizeof buf, c.format.empty() ? "%g" : c.format.c_str(), v);
        out.append(buf, std::min<std::size_t>(static_cast<std::size_t>(std::max(len, 0)), sizeof buf - 1));
        out += ' ';
      }
      out += '\n';
    }
    file_.write(out, path, !multifile && append, multifile, id);
  }

 private:
  struct Column {
    std::string id;              // compute ID; empty for index
    int col = 0;                 // 0-based column
    std::size_t at = 0;          // word in the dump command
    Compute* compute = nullptr;  // resolved at init
    std::string format;          // dump_modify format; empty: %g
  };

  Column parse(const Args& a, std::size_t i) {
    Column c;
    c.at = i;
    const std::string& w = a[i];
    if (w == "index") return c;
    const std::size_t open = w.find('[');
    if (w.rfind("c_", 0) != 0 || open == std::string::npos || w.back() != ']' || open < 3)
      a.fail(i, "c_ID[k] (a column of a local compute) or index");
    c.id = w.substr(2, open - 2);
    long k = 0;
    if (!parse_long(w.substr(open + 1, w.size() - open - 2), k) || k < 1) a.fail(i, "c_ID[k] with k a column number >= 1");
    c.col = static_cast<int>(k - 1);
    resolve(a, c);
    return c;
  }

  void resolve(const Args& a, Column& c) const {
    if (c.id.empty()) return;
    c.compute = sim.find_compute(c.id);
    if (!c.compute) a.fail(c.at, "a defined compute (no compute '" + c.id + "')");
    if (!c.compute->local_flag)
      a.fail(c.at, "a compute with local (per-contact) data (" + c.compute->style + " has none)");
    if (c.col >= c.compute->local_cols)
      a.fail(c.at, "a column in 1.." + std::to_string(c.compute->local_cols) + " of compute " + c.id);
  }

  // Evaluates the computes; returns the common row count.
  std::size_t gather() {
    std::size_t n = 0;
    bool first = true;
    for (Column& c : cols_) {
      if (!c.compute) continue;
      resolve(args, c);  // uncompute / redefinition between runs
      c.compute->local_now();
      const std::size_t rows = c.compute->local_rows();
      if (!first && rows != n)
        args.fail(c.at, "values with the same number of rows (" + std::to_string(rows) + " here, " + std::to_string(n) +
                            " before it) at step " + std::to_string(sim.step));
      n = rows;
      first = false;
    }
    return n;
  }

  void open_h5(const Args& a) {
    if (multifile) a.fail(5, "an HDF5 file name without '*' (one file holds every snapshot)");
    h5_ = std::make_unique<H5Series>(file);
    std::vector<std::string> names;
    for (std::size_t i = 6; i < a.size(); ++i) names.push_back(a[i]);
    h5_->attribute("columns", names);
    h5_->attribute("dump", {a.joined()});
    entries_ = h5_->series("entries", {cols_.size()}, false);
    first_row_ = h5_->series("first", {}, true);
    count_ = h5_->series("count", {}, true);
    h5_->time_axis(sim.units);
    h5_->start();
  }

  void write_h5(long step, std::size_t n) {
    std::vector<double> row(cols_.size());
    for (std::size_t r = 0; r < n; ++r) {
      for (std::size_t k = 0; k < cols_.size(); ++k) {
        const Column& c = cols_[k];
        row[k] = c.compute ? c.compute->local[r * c.compute->local_cols + c.col] : static_cast<double>(r + 1);
      }
      h5_->append(entries_, row.data());
    }
    h5_->append(first_row_, static_cast<std::int64_t>(rows_));
    h5_->append(count_, static_cast<std::int64_t>(n));
    h5_->end_record(step, sim.time, sim.dt);
    rows_ += n;
  }

  std::vector<Column> cols_;
  std::unique_ptr<H5Series> h5_;  // a .h5 file: HDF5 instead of text
  int entries_ = -1, first_row_ = -1, count_ = -1;
  std::size_t rows_ = 0;          // rows in entries so far
  std::string header_;  // the value words joined by spaces (LAMMPS' ENTRIES line)
  DumpFile file_;
  long last_step_ = -1;
};

}  // namespace

// --export-yade: the local rows of one compute wall/gran/slices (id x y z fx fy fz:
// the grain, the contact point on the plane, the force on the wall) as a
// _DumpLocal recorder writing this dump's text. Rows in grain id order (sable:
// its wall pass's order, atom memory order).
void DumpLocal::export_yade(YadeScript& s) const {
  const Args& a = args;  // dump ID group local N file values...
  if (h5_) a.fail(5, "a text file (export-yade translates no HDF5 dump local)");
  std::string comp, rows;
  std::vector<std::pair<std::string, std::string>> cols;  // format, Python of row r (None: index)
  for (std::size_t k = 6; k < a.size(); ++k) {
    if (a[k] == "index") {
      cols.push_back({"%d ", "None"});
      continue;
    }
    const std::size_t open = a[k].find('[');
    const Compute* c =
        a[k].rfind("c_", 0) == 0 && open != std::string::npos ? sim.find_compute(a[k].substr(2, open - 2)) : nullptr;
    if (!c || (rows = c->export_yade_rows(s)).empty())
      a.fail(k, "c_ID[k] of a compute wall/gran/slices (export-yade's dump local takes no other local data)");
    if (!comp.empty() && c->id != comp) a.fail(k, "columns of one compute (export-yade)");
    comp = c->id;
    const int col = std::stoi(a[k].substr(open + 1)) - 1;
    cols.push_back({"%g ", col == 0 ? "lambda r: r[0]"
                                    : "lambda r: r[" + std::to_string(col <= 3 ? 1 : 2) + "][" +
                                          std::to_string((col - 1) % 3) + "]"});
  }
  for (const Args& m : s.dump_mods[id])
    for (std::size_t k = 2; k < m.size();) {
      if (m[k] != "format") m.fail(k, "format (export-yade translates dump local's format only)");
      if (m.word(k + 1, "float, none or a column") == "none") {
        for (auto& c : cols) c.first = c.second == "None" ? "%d " : "%g ";
        k += 2;
      } else if (m[k + 1] == "float") {
        for (auto& c : cols)
          if (c.second != "None") c.first = yade_python_format(m.word(k + 2, "a format")) + " ";
        k += 3;
      } else {
        const long n = m.integer(k + 1, "a column number");
        if (n < 1 || n > static_cast<long>(cols.size())) m.fail(k + 1, "a column number of the dump");
        cols[n - 1].first = yade_python_format(m.word(k + 2, "a format")) + " ";
        k += 3;
      }
    }
  const std::string box = s.dump_box();
  s.py << "# " << a.where().file << ":" << a.where().line << ": dump " << id << " local\n"
       << "_recorders.append(_DumpLocal(" << yade_quoted(id) << ", " << yade_quoted(file) << ", " << every << ", "
       << yade_quoted(box) << ", " << yade_quoted("ITEM: ENTRIES " + header_ + "\n") << ", lambda: " << rows << ", [";
  for (const auto& [f, py] : cols) s.py << "(" << yade_quoted(f) << ", " << py << "), ";
  s.py << "]))\n";
}

SABLE_DUMP("local", DumpLocal);

}  // namespace sable
