// dump ID group custom/vtk N file col ...: one VTK file per snapshot that
// ParaView opens, chosen by extension as in LIGGGHTS: .vtu (XML unstructured
// grid), .vtp (XML poly data), .pvtu/.pvtp (parallel wrapper + one piece),
// anything else legacy ASCII .vtk POLYDATA. Points are always written; vx vy vz
// (f, omega, tq alike) become one 3-component array "v" when all three are
// given; duplicates are dropped. As LIGGGHTS does, the box goes to a separate
// *boundingBox* file (rectilinear grid). ASCII only.
#include <cstdio>
#include <filesystem>

#include "core/io/dump_columns.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

enum class VtkFormat { Legacy, Vtu, Vtp, Pvtu, Pvtp };

bool ends_with(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

// Content goes to path.tmp, then is renamed: readers never see a half-written file.
void write_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) fail("dump custom/vtk: cannot open '" + tmp + "' for writing");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) fail("dump custom/vtk: writing '" + tmp + "' failed");
  std::filesystem::rename(tmp, path);
}

std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '&') r += "&amp;";
    else if (c == '<') r += "&lt;";
    else if (c == '>') r += "&gt;";
    else if (c == '"') r += "&quot;";
    else r += c;
  }
  return r;
}

class DumpCustomVTK : public Dump {
 public:
  DumpCustomVTK(Simulation& s, const Args& a) : Dump(s, a) {
    if (ends_with(file, ".vtu")) format_ = VtkFormat::Vtu;
    else if (ends_with(file, ".vtp")) format_ = VtkFormat::Vtp;
    else if (ends_with(file, ".pvtu")) format_ = VtkFormat::Pvtu;
    else if (ends_with(file, ".pvtp")) format_ = VtkFormat::Pvtp;
    std::vector<AtomColumn> cols;
    for (std::size_t i = 6; i < a.size(); ++i) {
      AtomColumn c = parse_atom_column(s, a, i);
      if (c.kind == AtomColumn::X) continue;  // positions are the points
      bool dup = false;
      for (auto& o : cols) dup = dup || o.name == c.name;
      if (!dup) cols.push_back(std::move(c));
    }
    // Vector quantities whose three components are all listed become one 3-tuple array.
    static const std::pair<AtomColumn::Kind, const char*> vectors[] = {
        {AtomColumn::V, "v"}, {AtomColumn::F, "f"}, {AtomColumn::OMEGA, "omega"}, {AtomColumn::TORQUE, "tq"}};
    for (auto& c : cols) {
      const char* vname = nullptr;
      for (auto& [k, nm] : vectors)
        if (c.kind == k) vname = nm;
      int have = 0;
      for (auto& o : cols) have += vname && o.kind == c.kind;
      if (have == 3) {
        bool done = false;
        for (auto& arr : arrays_) done = done || arr.name == vname;
        if (done) continue;
        Array arr{vname, {}};
        for (int k = 0; k < 3; ++k) arr.comps.push_back(AtomColumn{c.kind, k, vname, ""});
        arrays_.push_back(std::move(arr));
      } else {
        // LIGGGHTS names an atom-style variable's array without its v_ prefix.
        arrays_.push_back(Array{c.kind == AtomColumn::VARIABLE ? c.ref : c.name, {c}});
      }
    }
  }

  bool modify_param(const Args& a, std::size_t& i) override {
    if (Dump::modify_param(a, i) || filter_.parse(sim, a, i)) return true;
    const std::string& k = a[i];
    if (k == "binary") {
      if (a.yes_no(i + 1, "no")) a.fail(i + 1, "'no' (sable writes ASCII VTK only)");
    } else if (k == "compressor") {
      if (a.word(i + 1, "none") != "none") a.fail(i + 1, "'none' (sable writes ASCII VTK only)");
    } else {
      return false;
    }
    i += 2;
    return true;
  }

 protected:
  void write_snapshot(long step, const std::string& path, bool) override {
    std::vector<std::size_t> sel = selected_atoms();
    filter_.apply(sim, sel);
    const std::size_t n = sel.size();
    std::vector<double> xyz[3], tmp;
    for (int k = 0; k < 3; ++k) gather_atom_column(sim, AtomColumn{AtomColumn::X, k, "x", ""}, sel, xyz[k]);
    std::vector<std::vector<double>> data(arrays_.size());  // tuples interleaved
    for (std::size_t a = 0; a < arrays_.size(); ++a) {
      const std::size_t nc = arrays_[a].comps.size();
      data[a].resize(n * nc);
      for (std::size_t k = 0; k < nc; ++k) {
        gather_atom_column(sim, arrays_[a].comps[k], sel, tmp);
        for (std::size_t j = 0; j < n; ++j) data[a][j * nc + k] = tmp[j];
      }
    }

    // The base hands us `path`.tmp in multi-file mode (and renames it); in
    // single-file mode the file is rewritten, so replace it atomically here.
    const std::string final_path = multifile ? path.substr(0, path.size() - 4) : path;
    std::string text;
    if (format_ == VtkFormat::Legacy) {
      text = legacy(step, n, xyz, data);
    } else if (format_ == VtkFormat::Vtu || format_ == VtkFormat::Vtp) {
      text = xml(n, xyz, data, format_ == VtkFormat::Vtu);
    } else {
      const bool ug = format_ == VtkFormat::Pvtu;
      const std::string piece = final_path.substr(0, final_path.size() - 5) + (ug ? "_0.vtu" : "_0.vtp");
      write_atomic(piece, xml(n, xyz, data, ug));
      text = pxml(std::filesystem::path(piece).filename().string(), ug);
    }
    if (multifile) write_plain(path, text);
    else write_atomic(path, text);
    write_atomic(bounding_box_name(step), bounding_box());
  }

 private:
  struct Array {
    std::string name;
    std::vector<AtomColumn> comps;  // 1 or 3
    bool integer() const { return comps[0].integer(); }
  };

  static void put(std::string& s, double v, bool integer) {
    char buf[40];
    const int len = integer ? std::snprintf(buf, sizeof buf, "%ld", static_cast<long>(v))
                            : std::snprintf(buf, sizeof buf, "%.12g", v);
    s.append(buf, len);
  }
  // Values, one tuple per line.
  static void tuples(std::string& s, const std::vector<double>& v, std::size_t nc, bool integer, const char* indent) {
    for (std::size_t j = 0; j < v.size(); j += nc) {
      s += indent;
      for (std::size_t k = 0; k < nc; ++k) {
        if (k) s += ' ';
        put(s, v[j + k], integer);
      }
      s += '\n';
    }
  }
  static std::vector<double> points(std::size_t n, const std::vector<double> (&xyz)[3]) {
    std::vector<double> p(3 * n);
    for (std::size_t j = 0; j < n; ++j)
      for (int k = 0; k < 3; ++k) p[3 * j + k] = xyz[k][j];
    return p;
  }

  std::string legacy(long step, std::size_t n, const std::vector<double> (&xyz)[3],
                     const std::vector<std::vector<double>>& data) const {
    // Version 3.0 (VERTICES as "1 i" cells): readable by every ParaView, old and new.
    std::string s = "# vtk DataFile Version 3.0\nGenerated by sable, step " + std::to_string(step) +
                    "\nASCII\nDATASET POLYDATA\nPOINTS " + std::to_string(n) + " double\n";
    tuples(s, points(n, xyz), 3, false, "");
    s += "VERTICES " + std::to_string(n) + " " + std::to_string(2 * n) + "\n";
    for (std::size_t j = 0; j < n; ++j) s += "1 " + std::to_string(j) + "\n";
    if (n == 0 || arrays_.empty()) return s;
    s += "POINT_DATA " + std::to_string(n) + "\nFIELD FieldData " + std::to_string(arrays_.size()) + "\n";
    for (std::size_t a = 0; a < arrays_.size(); ++a) {
      const Array& arr = arrays_[a];
      s += arr.name + " " + std::to_string(arr.comps.size()) + " " + std::to_string(n) +
           (arr.integer() ? " int\n" : " double\n");
      tuples(s, data[a], arr.comps.size(), arr.integer(), "");
    }
    return s;
  }

  std::string data_array(const std::string& name, bool integer, std::size_t nc, const std::vector<double>& v) const {
    std::string s = std::string("        <DataArray type=\"") + (integer ? "Int32" : "Float64") + "\" Name=\"" +
                    xml_escape(name) + "\"" + (nc > 1 ? " NumberOfComponents=\"" + std::to_string(nc) + "\"" : "") +
                    " format=\"ascii\">\n";
    tuples(s, v, nc, integer, "          ");
    return s + "        </DataArray>\n";
  }

  std::string xml(std::size_t n, const std::vector<double> (&xyz)[3], const std::vector<std::vector<double>>& data,
                  bool unstructured) const {
    const std::string N = std::to_string(n);
    const char* type = unstructured ? "UnstructuredGrid" : "PolyData";
    std::string s = std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"") + type +
                    "\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <" + type + ">\n";
    s += unstructured ? "    <Piece NumberOfPoints=\"" + N + "\" NumberOfCells=\"" + N + "\">\n"
                      : "    <Piece NumberOfPoints=\"" + N + "\" NumberOfVerts=\"" + N +
                            "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
    s += "      <PointData>\n";
    for (std::size_t a = 0; a < arrays_.size(); ++a)
      s += data_array(arrays_[a].name, arrays_[a].integer(), arrays_[a].comps.size(), data[a]);
    s += "      </PointData>\n      <Points>\n" + data_array("Points", false, 3, points(n, xyz)) + "      </Points>\n";
    // One vertex cell per point.
    std::vector<double> conn(n), offs(n), types(n, 1.0);  // 1 = VTK_VERTEX
    for (std::size_t j = 0; j < n; ++j) {
      conn[j] = static_cast<double>(j);
      offs[j] = static_cast<double>(j + 1);
    }
    s += unstructured ? "      <Cells>\n" : "      <Verts>\n";
    s += data_array("connectivity", true, 1, conn) + data_array("offsets", true, 1, offs);
    if (unstructured) s += data_array("types", true, 1, types);
    s += unstructured ? "      </Cells>\n" : "      </Verts>\n";
    return s + "    </Piece>\n  </" + type + ">\n</VTKFile>\n";
  }

  std::string pxml(const std::string& piece, bool unstructured) const {
    const std::string type = unstructured ? "PUnstructuredGrid" : "PPolyData";
    std::string s = "<?xml version=\"1.0\"?>\n<VTKFile type=\"" + type +
                    "\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <" + type + " GhostLevel=\"0\">\n    <PPointData>\n";
    for (const Array& arr : arrays_)
      s += std::string("      <PDataArray type=\"") + (arr.integer() ? "Int32" : "Float64") + "\" Name=\"" +
           xml_escape(arr.name) + "\"" +
           (arr.comps.size() > 1 ? " NumberOfComponents=\"" + std::to_string(arr.comps.size()) + "\"" : "") + "/>\n";
    s += "    </PPointData>\n    <PPoints>\n      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
         "    </PPoints>\n    <Piece Source=\"" + xml_escape(piece) + "\"/>\n  </" + type + ">\n</VTKFile>\n";
    return s;
  }

  // LIGGGHTS' names: dump*.vtk -> dumpboundingBox_STEP.vtk, out.vtu -> out_boundingBox.vtr.
  std::string bounding_box_name(long step) const {
    const std::string ext = format_ == VtkFormat::Legacy ? ".vtk" : ".vtr";
    const std::size_t star = file.find('*');
    if (star != std::string::npos) return file.substr(0, star) + "boundingBox_" + std::to_string(step) + ext;
    const std::size_t dot = file.find_last_of('.');
    const std::size_t slash = file.find_last_of('/');
    const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    return (has_ext ? file.substr(0, dot) : file) + "_boundingBox" + ext;
  }

  std::string bounding_box() const {
    const Domain& d = sim.domain;
    std::string s;
    if (format_ == VtkFormat::Legacy) {
      s = "# vtk DataFile Version 3.0\nGenerated by sable\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2\n";
      for (int k = 0; k < 3; ++k) {
        s += std::string(1, char('X' + k)) + "_COORDINATES 2 double\n";
        tuples(s, {d.lo[k], d.hi[k]}, 2, false, "");
      }
      return s;
    }
    s = "<?xml version=\"1.0\"?>\n<VTKFile type=\"RectilinearGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        "  <RectilinearGrid WholeExtent=\"0 1 0 1 0 1\">\n    <Piece Extent=\"0 1 0 1 0 1\">\n      <Coordinates>\n";
    for (int k = 0; k < 3; ++k) s += data_array(std::string(1, char('x' + k)), false, 1, {d.lo[k], d.hi[k]});
    return s + "      </Coordinates>\n    </Piece>\n  </RectilinearGrid>\n</VTKFile>\n";
  }

  static void write_plain(const std::string& path, const std::string& text) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) fail("dump custom/vtk: cannot open '" + path + "' for writing");
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (std::fclose(f) != 0 || !ok) fail("dump custom/vtk: writing '" + path + "' failed");
  }

  VtkFormat format_ = VtkFormat::Legacy;
  std::vector<Array> arrays_;
  DumpFilter filter_;
};

}  // namespace

SABLE_DUMP("custom/vtk", DumpCustomVTK);

}  // namespace sable
