// fix ID group ave/time Nevery Nrepeat Nfreq value1 value2 ... keyword args ...
//   value = c_ID, c_ID[I], f_ID, f_ID[I], v_name (global scalars; global vectors with mode vector)
//   keywords: mode scalar|vector, ave one|running|window M, start S, off M, file F,
//             overwrite, title1/title2/title3 STRING, hdf5 F (sable addition)
// LIGGGHTS 3.8 semantics and file format (fix_ave_time.cpp): values sampled on
// Nrepeat steps Nevery apart ending on each multiple of Nfreq, averaged, then
// combined across Nfreq outputs per `ave`. Outputs f_ID (first value) and
// f_ID[i] (value i; row i in vector mode). `hdf5 F` writes datasets `step` and
// `time` (N; the time axis of core/io/h5_series.h: attributes units, timestep)
// and `values` (N x nvalues, or N x nrows x nvalues), attribute `columns`.
// Global arrays (c_ID[I] in vector mode) are not available: sable's computes and
// fixes have none.
#include "fixes/fix_ave_time.h"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <type_traits>

#include "core/engine/error.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/io/thermo.h"
#include "core/input/variable.h"
#include "core/io/yade_script.h"

namespace sable {
namespace ave {

void Schedule::parse(const Args& a, std::size_t i) {
  nevery = a.integer(i, "Nevery (steps between samples)");
  nrepeat = a.integer(i + 1, "Nrepeat (samples per average)");
  nfreq = a.integer(i + 2, "Nfreq (steps between averages)");
  if (nevery <= 0) a.fail(i, "Nevery > 0");
  if (nrepeat <= 0) a.fail(i + 1, "Nrepeat > 0");
  if (nfreq <= 0) a.fail(i + 2, "Nfreq > 0");
  if (nfreq % nevery) a.fail(i + 2, "Nfreq a multiple of Nevery (" + std::to_string(nevery) + ")");
  if ((nrepeat - 1) * nevery >= nfreq)
    a.fail(i + 1, "Nrepeat with (Nrepeat-1)*Nevery < Nfreq (samples of one average must not overlap the next)");
}

long Schedule::first_after(long step) const {  // LIGGGHTS' nextvalid()
  long n = (step / nfreq) * nfreq + nfreq;
  while (n < start) n += nfreq;
  if (n - nfreq == step && nrepeat == 1)
    n = step;
  else
    n -= (nrepeat - 1) * nevery;
  if (n < step) n += nfreq;
  return n;
}

TextFile::~TextFile() {
  if (fd_ >= 0) ::close(fd_);
}

void TextFile::open(const Options& o, const Args& a) {
  path_ = o.file;
  overwrite = o.overwrite;
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND, 0644);
  if (fd_ < 0) a.fail(o.file_at, "a writable file (" + std::string(std::strerror(errno)) + ")");
}

std::unique_ptr<H5Series> open_h5(const Options& o, const std::vector<Value>& values, const char* key, const Fix& fix) {
  auto h5 = std::make_unique<H5Series>(o.h5file);
  std::vector<std::string> words;
  for (auto& v : values) words.push_back(v.word);
  h5->attribute(key, words);
  h5->attribute("fix", {fix.id, fix.style, fix.args.joined(1)});
  return h5;
}

void TextFile::write_all(int fd, const std::string& s) {
  for (std::size_t done = 0; done < s.size();) {
    const ssize_t w = ::write(fd, s.data() + done, s.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) fail("writing '" + path_ + "' failed: " + std::strerror(errno));
    done += static_cast<std::size_t>(w);
  }
}

void TextFile::header(const std::string& text) {
  header_ = text;
  write_all(fd_, text);
}

void TextFile::block(const std::string& text) {
  if (!overwrite) return write_all(fd_, text);
  const std::string tmp = path_ + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) fail("cannot write '" + tmp + "': " + std::strerror(errno));
  write_all(fd, header_ + text);
  ::close(fd);
  std::filesystem::rename(tmp, path_);
  ::close(fd_);  // the old descriptor points at the replaced file
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND);
}


bool Options::parse(const Args& a, std::size_t& i, Schedule& sched, const char* start_what) {
  const std::string& k = a[i];
  if (k == "mode") {
    vector_mode = a.choice(i + 1, {"scalar", "vector"}) == 1;
    i += 2;
  } else if (k == "ave") {
    const std::string& m = a.word(i + 1, "one, running or window M");
    if (m == "one") {
      ave = One;
    } else if (m == "running") {
      ave = Running;
    } else if (m == "window") {
      ave = Window;
      nwindow = a.integer(i + 2, "the window length M (outputs)");
      if (nwindow <= 0) a.fail(i + 2, "a window of M > 0 outputs");
      ++i;
    } else {
      a.fail(i + 1, "one, running or window M");
    }
    i += 2;
  } else if (k == "start") {
    sched.start = a.integer(i + 1, start_what);
    i += 2;
  } else if (k == "file") {
    file = a.word(i + 1, "a file name");
    file_at = i + 1;
    i += 2;
  } else if (k == "hdf5") {
    h5file = a.word(i + 1, "an HDF5 file name");
    i += 2;
  } else if (k == "overwrite") {
    overwrite = true;
    ++i;
  } else if (k == "title1" || k == "title2" || k == "title3") {
    const int t = k[5] - '1';
    title[t] = a.word(i + 1, "a title string");
    titled[t] = true;
    i += 2;
  } else {
    return false;
  }
  return true;
}

void Options::check(const Args& a) const {
  if (overwrite && ave != Running) a.fail_line("'overwrite' needs 'ave running' (as in LIGGGHTS)");
}

void Value::resolve(Simulation& sim, const Args& a, const Fix* self, const char* doing) {
  c = kind == 'c' ? sim.find_compute(id) : nullptr;
  Fix* f = kind == 'f' ? sim.find_fix(id) : nullptr;
  g = c ? static_cast<GlobalOutput*>(c) : f;
  if (kind == 'c' && !c) a.fail(at, "an existing compute ID ('" + id + "' is not defined)");
  if (kind == 'f' && !f) a.fail(at, "an existing fix ID ('" + id + "' is not defined)");
  if (kind == 'f' && f == self) a.fail(at, std::string("another fix (a fix cannot ") + doing + " itself)");
  if (kind == 'v' && !sim.variables->exists(id)) a.fail(at, "a defined variable ('" + id + "' is not)");
}

}  // namespace ave

namespace {

// The title lines of the text file (title1..3 or LIGGGHTS' defaults), `words` the values as given.
std::string time_header(const ave::Options& o, const std::string& id, const std::vector<std::string>& words) {
  std::string h = o.title_or(0, "# Time-averaged data for fix " + id) + "\n";
  if (o.titled[1]) {
    h += o.title[1] + "\n";
  } else if (!o.vector_mode) {
    h += "# TimeStep";
    for (const auto& w : words) h += " " + w;
    h += "\n";
  } else {
    h += "# TimeStep Number-of-rows\n";
  }
  if (o.vector_mode) {
    if (o.titled[2]) {
      h += o.title[2] + "\n";
    } else {
      h += "# Row";
      for (const auto& w : words) h += " " + w;
      h += "\n";
    }
  }
  return h;
}

class FixAveTime : public Fix {
 public:
  FixAveTime(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = END_OF_STEP;
    sched_.parse(a, 4);
    std::size_t i = 7;
    for (; i < a.size(); ++i) {
      Value v;
      if (!parse_reference(a[i], v.kind, v.id, v.index)) break;
      v.word = a[i];
      v.at = i;
      values_.push_back(v);
    }
    if (values_.empty()) a.fail(7, "at least one value: c_ID, c_ID[I], f_ID, f_ID[I] or v_name");
    std::vector<long> off;
    while (i < a.size()) {
      if (opt_.parse(a, i, sched_, "the first step to average from")) continue;
      if (a[i] == "off") {
        off.push_back(a.integer(i + 1, "the number of a value not to average (1..N)"));
        if (off.back() < 1 || off.back() > static_cast<long>(values_.size()))
          a.fail(i + 1, "a value number between 1 and " + std::to_string(values_.size()));
        i += 2;
      } else {
        a.fail(i,
               "a value (c_ID, f_ID, v_name) or an ave/time keyword: mode, ave, start, off, file, overwrite, "
               "title1, title2, title3, hdf5");
      }
    }
    opt_.check(a);
    for (auto& v : values_) v.off = std::find(off.begin(), off.end(), &v - values_.data() + 1) != off.end();
    check_values();
    scalar_flag = !opt_.vector_mode;
    vector_size = opt_.vector_mode ? nrows_ : static_cast<int>(values_.size());
    const std::size_t width = (opt_.vector_mode ? nrows_ : 1) * values_.size();
    sample_.assign(width, 0.0);
    total_.assign(width, 0.0);
    if (opt_.ave == Window) window_.assign(opt_.nwindow * width, 0.0);

    const bool writer = sim.comm.rank() == 0;  // several ranks: rank 0 writes, every rank averages
    if (!opt_.file.empty() && writer) {
      text_.open(opt_, a);
      std::vector<std::string> words;
      for (auto& v : values_) words.push_back(v.word);
      text_.header(time_header(opt_, id, words));
    }
    if (!opt_.h5file.empty() && writer) {
      h5_ = ave::open_h5(opt_, values_, "columns", *this);
      std::vector<std::size_t> shape{values_.size()};
      if (opt_.vector_mode) shape.insert(shape.begin(), nrows_);
      h5_values_ = h5_->series("values", shape, false);
      h5_->time_axis(sim.units);
      h5_->start();
    }
    sched_.begin(s.step);
  }

  void init() override {
    for (auto& v : values_) resolve(v);
    sched_.resume(sim.step);
  }
  void setup() override { end_of_step(); }  // LIGGGHTS: samples at setup when due (step 0 with Nrepeat 1)

  // --export-yade: a _AveTime recorder (the script's head), written after the engines.
  void export_yade(YadeScript& s) const override {
    s.add_recorder(*this, [this](YadeScript& s) { export_yade_recorder(s); });
  }
  void end_of_step() override {
    if (sim.step != sched_.nvalid) return;
    const std::size_t nv = values_.size(), rows = opt_.vector_mode ? nrows_ : 1;
    if (sched_.irepeat == 0) std::fill(sample_.begin(), sample_.end(), 0.0);
    for (std::size_t j = 0; j < nv; ++j)
      for (std::size_t r = 0; r < rows; ++r) {
        const double x = value(values_[j], static_cast<int>(r));
        double& s = sample_[r * nv + j];
        s = values_[j].off ? x : s + x;
      }
    if (!sched_.sampled(sim.step)) return;
    for (std::size_t k = 0; k < sample_.size(); ++k)
      if (!values_[k % nv].off) sample_[k] /= static_cast<double>(sched_.nrepeat);
    // Combine with earlier outputs, as LIGGGHTS (same operations, same rounding).
    const std::size_t w = sample_.size();
    if (opt_.ave == One) {
      total_ = sample_;
      norm_ = 1;
    } else if (opt_.ave == Running) {
      for (std::size_t k = 0; k < w; ++k) total_[k] += sample_[k];
      ++norm_;
    } else {
      double* slot = &window_[iwindow_ * w];
      for (std::size_t k = 0; k < w; ++k) {
        total_[k] += sample_[k];
        if (window_full_) total_[k] -= slot[k];
        slot[k] = sample_[k];
      }
      if (++iwindow_ == opt_.nwindow) iwindow_ = 0, window_full_ = true;
      norm_ = window_full_ ? opt_.nwindow : iwindow_;
    }
    for (std::size_t k = 0; k < w; ++k)
      if (values_[k % nv].off) total_[k] = norm_ * sample_[k];
    write_outputs();
  }

  double compute_scalar() override { return norm_ ? total_[0] / norm_ : 0.0; }
  double compute_vector(int i) override {
    if (i < 1 || i > vector_size)
      args.fail_line("f_" + id + "[" + std::to_string(i) + "]: index out of range 1.." + std::to_string(vector_size));
    // Vector mode: row i of the first value (LIGGGHTS forgets to divide by norm there; we do not).
    const std::size_t k = opt_.vector_mode ? static_cast<std::size_t>(i - 1) * values_.size() : i - 1;
    return norm_ ? total_[k] / norm_ : 0.0;
  }

 private:
  void export_yade_recorder(YadeScript& s) const;
  using Value = ave::Value;  // kinds c, f, v
  using enum ave::Ave;
  ave::Schedule sched_;
  std::vector<Value> values_;
  ave::Options opt_;  // mode, ave, file, ... as given
  long iwindow_ = 0;
  bool window_full_ = false;
  int nrows_ = 1;
  long norm_ = 0;
  std::vector<double> sample_, total_, window_;  // [row * nvalues + value]
  ave::TextFile text_;
  std::unique_ptr<ave::H5Series> h5_;
  int h5_values_ = -1;

  // Errors at the value's own word, with what was expected there.
  void check_values() {
    int len = -1;
    for (auto& v : values_) {
      resolve(v);
      int n = 0;
      if (v.kind == 'v') {
        if (opt_.vector_mode) args.fail(v.at, "c_ID or f_ID (variables cannot be used with mode vector)");
        if (sim.variables->is_atom_style(v.id))
          args.fail(v.at, "an equal-style variable (v_" + v.id + " is atom-style)");
        continue;
      }
      const bool scalar = v.g->scalar_flag != 0;
      const int size = v.g->vector_size;
      const std::string what = global_output_name(v.kind, v.id);
      if (!opt_.vector_mode) {
        if (v.index == 0 && !scalar)
          args.fail(v.at, "a global scalar (" + what + " has none" + (size ? "; use " + v.word + "[I]" : "") + ")");
        if (v.index > 0 && v.index > size)
          args.fail(v.at, "an index within the global vector of " + what + " (1.." + std::to_string(size) + ")");
        continue;
      }
      if (v.index > 0) args.fail(v.at, "a global vector without [I] (sable computes and fixes have no global arrays)");
      if (size <= 0) args.fail(v.at, "a global vector (" + what + " has none)");
      n = size;
      if (len >= 0 && n != len)
        args.fail(v.at, "a vector of the same length as the others (" + std::to_string(len) + ", not " +
                            std::to_string(n) + ")");
      len = n;
    }
    if (opt_.vector_mode) nrows_ = len;
  }

  void resolve(Value& v) { v.resolve(sim, args, this, "average"); }

  double value(const Value& v, int row) {
    if (v.g) return v.g->global(opt_.vector_mode ? row + 1 : v.index);
    double x;
    if (!sim.variables->numeric(v.id, x)) args.fail(v.at, "an equal-style variable");
    return x;
  }

  void write_outputs() {
    const std::size_t nv = values_.size(), w = total_.size();
    std::vector<double> out(w);
    for (std::size_t k = 0; k < w; ++k) out[k] = total_[k] / norm_;
    if (text_.is_open()) {
      char buf[64];
      std::string s;
      if (!opt_.vector_mode) {
        std::snprintf(buf, sizeof buf, "%ld", sim.step);
        s = buf;
        for (double x : out) std::snprintf(buf, sizeof buf, " %g", x), s += buf;
        s += "\n";
      } else {
        std::snprintf(buf, sizeof buf, "%ld %d\n", sim.step, nrows_);
        s = buf;
        for (int r = 0; r < nrows_; ++r) {
          s += std::to_string(r + 1);
          for (std::size_t j = 0; j < nv; ++j) std::snprintf(buf, sizeof buf, " %g", out[r * nv + j]), s += buf;
          s += "\n";
        }
      }
      text_.block(s);
    }
    if (h5_) {
      h5_->append(h5_values_, out.data());
      h5_->end_record(sim.step, sim.time, sim.dt);  // last: the record is complete
    }
  }
};

}  // namespace

// fix ave/time (ave one; scalar mode, or vector mode of compute wall/gran/slices)
// as the script's _AveTime: the same schedule (LIGGGHTS' nextvalid), averages and
// text file as here, its values evaluated on YADE's bodies.
void FixAveTime::export_yade_recorder(YadeScript& s) const {
  const Args& a = args;  // fix ID group ave/time Nevery Nrepeat Nfreq values... keywords...
  ave::Schedule sched;
  sched.parse(a, 4);
  std::size_t i = 7;
  std::vector<std::string> cols, words;
  for (char kind; i < a.size(); ++i) {
    std::string ref;
    int index = 0;
    if (!parse_reference(a[i], kind, ref, index)) break;
    words.push_back(a[i]);
  }
  ave::Options o;
  std::vector<long> off;
  while (i < a.size()) {
    const std::string& k = a[i];
    if (k == "ave" && a.word(i + 1, "one") != "one")
      a.fail(i + 1, "ave one (export-yade translates no running or window averages)");
    if (k == "overwrite") a.fail(i, "file F or hdf5 F (export-yade writes no overwrite files)");
    if (k == "off") {
      off.push_back(a.integer(i + 1, "a value number"));
      i += 2;
    } else if (!o.parse(a, i, sched, "the first step to average from")) {
      a.fail(i, "an ave/time keyword export-yade translates: mode, ave one, start, off, file, hdf5, title1, "
                "title2, title3");
    }
  }
  // Vector mode: each value a whole vector; export-yade knows compute wall/gran/slices' (c_ID).
  long nrows = 1;
  for (std::size_t j = 0; j < words.size(); ++j) {
    if (!o.vector_mode) {
      cols.push_back("lambda: " + s.translate(words[j], a));  // after the options: those errors first
      continue;
    }
    const Compute* c = words[j].rfind("c_", 0) == 0 ? sim.find_compute(words[j].substr(2)) : nullptr;
    const std::string row = c ? c->export_yade_term(s, 1, a, "r") : "";  // row r of the vector
    if (row.empty())
      a.fail(7 + j, "c_ID of a compute wall/gran/slices (export-yade's vector-mode ave/time takes no other vector)");
    const long n = c->vector_size;
    if (j > 0 && n != nrows) a.fail(7 + j, "vectors of one length");
    nrows = n;
    cols.push_back("lambda: [" + row + " for r in range(" + std::to_string(n) + ")]");
  }
  const std::string h = time_header(o, id, words);  // as the fix writes it
  std::string offs, names;
  for (std::size_t j = 0; j < cols.size(); ++j) {
    const bool kept = std::find(off.begin(), off.end(), static_cast<long>(j + 1)) != off.end();
    offs += std::string(kept ? "True" : "False") + ", ";
    names += yade_quoted(words[j]) + ", ";
  }
  s.py << "# " << a.where().file << ":" << a.where().line << ": fix " << id << " ave/time\n"
       << "_avt[" << yade_quoted(id) << "] = _AveTime(" << (o.file.empty() ? "None" : yade_quoted(o.file)) << ", "
       << yade_quoted(h) << ", " << sched.nevery << ", " << sched.nrepeat << ", " << sched.nfreq << ", " << sched.start
       << ", [";
  for (const auto& c : cols) s.py << c << ", ";
  s.py << "], [" << offs << "]";
  if (o.vector_mode) s.py << ", rows=" << nrows;
  if (!o.h5file.empty())
    s.py << ", h5=(" << yade_quoted(o.h5file) << ", [" << names << "], [" << yade_quoted(id) << ", "
         << yade_quoted(style) << ", " << yade_quoted(a.joined(1)) << "])";
  s.py << ")\n_recorders.append(_avt[" << yade_quoted(id) << "])\n";
}

SABLE_FIX("ave/time", FixAveTime);

}  // namespace sable
