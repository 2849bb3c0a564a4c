// Reading sable's outputs (HDF5 series, dumps, text tables) and writing CSV / HDF5.
#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "core/io/h5_series.h"
#include "reference_runs/analysis/analysis.h"

namespace sable::analysis {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> w;
  std::string cur;
  for (char ch : line) {
    if (ch == ' ' || ch == '\t' || ch == ',' || ch == '\r') {
      if (!cur.empty()) w.push_back(cur);
      cur.clear();
    } else {
      cur += ch;
    }
  }
  if (!cur.empty()) w.push_back(cur);
  return w;
}

bool number(const std::string& s, double& v) {
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end && *end == '\0' && !s.empty();
}

std::string joined(const std::vector<std::string>& w) {
  std::string s;
  for (auto& x : w) s += (s.empty() ? "" : " ") + x;
  return s.empty() ? "(none)" : s;
}

// 0-based index of a 1-based number or a name.
std::size_t resolve(const std::string& path, const std::string& spec, const std::vector<std::string>& names,
                    std::size_t ncols) {
  const std::string where = "file '" + path + "'";
  if (spec.empty()) {
    if (ncols == 1) return 0;
    throw Error(where + " has " + std::to_string(ncols) + " columns (" + joined(names) + "): say which with --column");
  }
  if (std::all_of(spec.begin(), spec.end(), ::isdigit)) {
    const std::size_t k = std::stoul(spec);
    if (k < 1 || k > ncols)
      throw Error(where + ": column " + spec + " out of range (it has " + std::to_string(ncols) + " columns: " +
                  joined(names) + "; numbers count from 1)");
    return k - 1;
  }
  const auto it = std::find(names.begin(), names.end(), spec);
  if (it == names.end()) throw Error(where + ": no column named '" + spec + "' (columns: " + joined(names) + ")");
  return static_cast<std::size_t>(it - names.begin());
}

bool is_hdf5(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char sig[8] = {};
  in.read(sig, 8);
  return in.gcount() == 8 && std::string(sig, 8) == std::string("\x89HDF\r\n\x1a\n", 8);
}

std::vector<std::string> h5_strings(hid_t obj, const char* name) {
  std::vector<std::string> out;
  if (H5Aexists(obj, name) <= 0) return out;
  const hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  const hid_t space = H5Aget_space(a);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  std::vector<char*> p(static_cast<std::size_t>(std::max<hssize_t>(n, 0)), nullptr);
  if (n > 0 && H5Aread(a, type, p.data()) >= 0)
    for (char* s : p) {
      out.emplace_back(s ? s : "");
      H5free_memory(s);
    }
  H5Tclose(type);
  H5Sclose(space);
  H5Aclose(a);
  return out;
}

std::vector<std::string> h5_members(hid_t f) {
  std::vector<std::string> out;
  H5G_info_t info;
  if (H5Gget_info(f, &info) < 0) return out;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char buf[256] = {};
    if (H5Lget_name_by_idx(f, ".", H5_INDEX_NAME, H5_ITER_INC, i, buf, sizeof buf, H5P_DEFAULT) >= 0) out.push_back(buf);
  }
  return out;
}

// Opens an HDF5 file to read, also one a run is still writing (SWMR); negative when it cannot.
hid_t h5_open(const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) f = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);  // a run still writing
  return f;
}

// Dataset `name` of the open file f as doubles (row-major), its shape in dims. Errors close f first;
// a missing dataset's error lists the file's datasets, `hint` saying how to choose another.
Vec h5_doubles(hid_t f, const std::string& path, const std::string& name, std::vector<std::size_t>& dims,
               const std::string& hint) {
  if (H5Lexists(f, name.c_str(), H5P_DEFAULT) <= 0) {
    const std::string m = joined(h5_members(f));
    H5Fclose(f);
    throw Error("file '" + path + "': no dataset '" + name + "' (it has: " + m + hint + ")");
  }
  const hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(d);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> h(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space, h.data(), nullptr);
  std::size_t total = 1;
  dims.assign(h.begin(), h.end());
  for (std::size_t n : dims) total *= n;
  Vec all(total);
  const bool ok = total == 0 || H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()) >= 0;
  H5Sclose(space);
  H5Dclose(d);
  if (!ok) {
    H5Fclose(f);
    throw Error("file '" + path + "': cannot read dataset '" + name + "' as numbers");
  }
  return all;
}

Column read_hdf5(const std::string& path, const std::string& spec, std::string dataset) {
  const hid_t f = h5_open(path);
  if (f < 0) throw Error("file '" + path + "': cannot open as HDF5");
  if (dataset.empty()) dataset = "values";  // fix ave/time
  std::vector<std::size_t> dims;
  const Vec all = h5_doubles(f, path, dataset, dims, "; choose with --dataset");
  std::vector<std::string> names = h5_strings(f, "columns");
  if (names.empty()) names = h5_strings(f, "values");
  H5Fclose(f);
  const std::size_t total = all.size();
  const std::size_t ncols = dims.size() <= 1 ? 1 : dims.back();  // [rows] or [rows][cols] or [rows][nrows][cols]
  if (names.size() != ncols) names.clear();
  const std::size_t k = resolve(path + "' dataset '" + dataset, spec, names, ncols);
  Column c;
  for (std::size_t i = k; i < total; i += ncols) c.values.push_back(all[i]);
  c.label = path + ":" + dataset + ", column " + (names.empty() ? std::to_string(k + 1) : names[k]);
  return c;
}

Column read_dump(const std::string& path, const std::string& spec, std::istream& in) {
  Column c;
  std::string line;
  std::vector<std::string> names;
  std::size_t k = 0, lineno = 0, natoms = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.rfind("ITEM: NUMBER OF ATOMS", 0) == 0) {
      std::getline(in, line);
      ++lineno;
      natoms = std::stoul(line);
    } else if (line.rfind("ITEM: ATOMS", 0) == 0) {
      names = split(line.substr(11));
      k = resolve(path, spec, names, names.size());
      for (std::size_t a = 0; a < natoms && std::getline(in, line); ++a) {
        ++lineno;
        const auto w = split(line);
        double v;
        if (w.size() != names.size() || !number(w[k], v))
          throw Error("file '" + path + "' line " + std::to_string(lineno) + ": bad atom line for column '" + names[k] + "'");
        c.values.push_back(v);
      }
    }
  }
  if (names.empty()) throw Error("file '" + path + "': a dump without an ITEM: ATOMS section");
  c.label = path + ", column " + names[k];
  return c;
}

Column read_text(const std::string& path, const std::string& spec, std::istream& in) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::size_t> linenos;
  std::vector<std::string> header, comment;
  std::string line;
  std::size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (line[first] == '#') {
      comment = split(line.substr(first + 1));
      if (!comment.empty() && comment[0].back() == ':') comment.clear();  // '# key: value' metadata
      continue;
    }
    auto w = split(line);
    double v;
    if (rows.empty() && header.empty() && !number(w[0], v)) {  // a CSV header line
      header = w;
      continue;
    }
    if (rows.empty() && header.empty()) header = comment;
    rows.push_back(std::move(w));
    linenos.push_back(lineno);
  }
  if (rows.empty()) throw Error("file '" + path + "': no data lines");
  // fix ave/time vector mode interleaves 'step nrows' lines with the rows: keep the usual width.
  std::map<std::size_t, std::size_t> widths;
  for (auto& r : rows) ++widths[r.size()];
  std::size_t width = 0, most = 0;
  for (auto [w, n] : widths)
    if (n > most) {
      most = n;
      width = w;
    }
  if (header.size() != width) header.clear();
  const std::size_t k = resolve(path, spec, header, width);
  Column c;
  std::size_t skipped = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].size() != width) {
      ++skipped;
      continue;
    }
    double v;
    if (!number(rows[i][k], v))
      throw Error("file '" + path + "' line " + std::to_string(linenos[i]) + ": '" + rows[i][k] + "' in column " +
                  std::to_string(k + 1) + " is not a number");
    c.values.push_back(v);
  }
  if (skipped)
    std::cerr << "note: " << path << ": skipped " << skipped << " lines whose width is not " << width
              << " (block headers)\n";
  c.label = path + ", column " + (header.empty() ? std::to_string(k + 1) : header[k]);
  return c;
}

}  // namespace

bool is_hdf5_file(const std::string& path) { return is_hdf5(path); }

bool h5_has_dataset(const std::string& path, const std::string& name) {
  if (!is_hdf5(path)) return false;
  const hid_t f = h5_open(path);
  if (f < 0) return false;
  const bool has = H5Lexists(f, name.c_str(), H5P_DEFAULT) > 0;
  H5Fclose(f);
  return has;
}

Vec read_h5_array(const std::string& path, const std::string& name, std::vector<std::size_t>& dims) {
  const hid_t f = h5_open(path);
  if (f < 0) throw Error("file '" + path + "': cannot open as HDF5");
  Vec all = h5_doubles(f, path, name, dims, "");
  H5Fclose(f);
  return all;
}

Column read_column(const std::string& path, const std::string& spec, const std::string& dataset) {
  std::ifstream in(path);
  if (!in) throw Error("file '" + path + "': cannot open");
  if (is_hdf5(path)) return read_hdf5(path, spec, dataset);
  std::string first;
  while (std::getline(in, first) && first.find_first_not_of(" \t\r") == std::string::npos) {
  }
  in.clear();
  in.seekg(0);
  if (first.rfind("ITEM:", 0) == 0) return read_dump(path, spec, in);
  return read_text(path, spec, in);
}

void write_table(const std::string& path, const Table& t) {
  for (auto& c : t.cols)
    if (c.size() != t.cols.front().size()) throw Error("write_table: columns of different lengths");
  const bool h5 = path.size() > 3 && (path.ends_with(".h5") || path.ends_with(".hdf5"));
  if (h5) {
    H5Series f(path);
    for (auto& [k, v] : t.meta) f.attribute(k, {v});
    f.attribute("columns", t.names);
    for (std::size_t i = 0; i < t.names.size(); ++i) f.constant(t.names[i], t.cols[i]);
    return;
  }
  std::ofstream out(path);
  if (!out) throw Error("file '" + path + "': cannot write");
  for (auto& [k, v] : t.meta) out << "# " << k << ": " << v << "\n";
  for (std::size_t i = 0; i < t.names.size(); ++i) out << (i ? "," : "") << t.names[i];
  out << "\n";
  const std::size_t n = t.cols.empty() ? 0 : t.cols.front().size();
  char buf[32];
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t i = 0; i < t.cols.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%.17g", t.cols[i][r]);
      out << (i ? "," : "") << buf;
    }
    out << "\n";
  }
  if (!out) throw Error("file '" + path + "': write failed (disk full?)");
}

}  // namespace sable::analysis
