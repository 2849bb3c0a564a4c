// dump ID group custom/vtk N file col ...: one VTK file per snapshot that
// ParaView opens, chosen by extension as in LIGGGHTS: .vtu (XML unstructured
// grid), .vtp (XML poly data), .pvtu/.pvtp (parallel wrapper + one piece),
// anything else legacy .vtk POLYDATA. Points are always written; vx vy vz
// (f, omega, tq alike) become one 3-component array "v" when all three are
// given; duplicates are dropped. As LIGGGHTS does, the box goes to a separate
// *boundingBox* file (rectilinear grid, always ASCII: six numbers).
// dump_modify ID binary yes|no (LIGGGHTS' keyword and default, no): with yes
// the XML files (.vtu/.vtp and the pieces of .pvtu/.pvtp) keep their arrays as
// raw bytes appended after the XML (VTK's format="appended", <AppendedData
// encoding="raw">, each block after its UInt64 byte count, header_type
// UInt64, the machine's byte order), and a legacy .vtk is BINARY (big-endian,
// as that format requires). Values are the same doubles and ints, full
// precision (ASCII prints 12 significant digits).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/io/dump_columns.h"
#include "core/io/text_file.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

enum class VtkFormat { Legacy, Vtu, Vtp, Pvtu, Pvtp };

bool ends_with(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

void write_atomic(const std::string& path, const std::string& text) {
  write_file_atomic(path, text, "dump custom/vtk");
}

void put(std::string& s, double v, bool integer) {
  char buf[40];
  const int len = integer ? std::snprintf(buf, sizeof buf, "%ld", static_cast<long>(v))
                          : std::snprintf(buf, sizeof buf, "%.12g", v);
  s.append(buf, len);
}
// Values, one tuple per line.
void tuples(std::string& s, const std::vector<double>& v, std::size_t nc, bool integer, const char* indent) {
  for (std::size_t j = 0; j < v.size(); j += nc) {
    s += indent;
    for (std::size_t k = 0; k < nc; ++k) {
      if (k) s += ' ';
      put(s, v[j + k], integer);
    }
    s += '\n';
  }
}

// One value as 4 bytes (int32) or 8 (double), in big-endian or the machine's order.
void put_binary(std::string& out, double v, bool integer, bool big_endian) {
  unsigned char b[8];
  std::size_t len = 8;
  if (integer) {
    const auto i = static_cast<std::int32_t>(v);
    std::memcpy(b, &i, len = 4);
  } else {
    std::memcpy(b, &v, 8);
  }
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + len);
  out.append(reinterpret_cast<const char*>(b), len);
}

// The arrays of one XML file: inline ASCII, or binary blocks kept in `appended`
// and written after the XML, each preceded by its byte count (UInt64).
struct XmlArrays {
  bool binary = false;
  std::string appended;

  std::string file_tag(const std::string& type) const {
    // header_type (the byte counts' type) needs version 1.0; ASCII files keep 0.1.
    return "<VTKFile type=\"" + type + "\" version=\"" + (binary ? "1.0" : "0.1") + "\" byte_order=\"" +
           (std::endian::native == std::endian::big ? "BigEndian" : "LittleEndian") + "\"" +
           (binary ? " header_type=\"UInt64\"" : "") + ">\n";
  }
  // A <DataArray> element: its values inline, or an offset into the appended blocks.
  std::string array(const std::string& name, bool integer, std::size_t nc, const std::vector<double>& v) {
    std::string s = std::string("        <DataArray type=\"") + (integer ? "Int32" : "Float64") + "\" Name=\"" +
                    xml_escape(name) + "\"" + (nc > 1 ? " NumberOfComponents=\"" + std::to_string(nc) + "\"" : "");
    if (binary) {
      s += " format=\"appended\" offset=\"" + std::to_string(appended.size()) + "\"/>\n";
      const std::uint64_t bytes = v.size() * (integer ? 4 : 8);
      unsigned char b[8];
      std::memcpy(b, &bytes, 8);
      appended.append(reinterpret_cast<const char*>(b), 8);
      for (double x : v) put_binary(appended, x, integer, std::endian::native == std::endian::big);
      return s;
    }
    s += " format=\"ascii\">\n";
    tuples(s, v, nc, integer, "          ");
    return s + "        </DataArray>\n";
  }
  // The XML closed by </VTKFile>, with the appended blocks before that tag.
  std::string finish(std::string xml) const {
    if (!binary) return xml + "</VTKFile>\n";
    return xml + "  <AppendedData encoding=\"raw\">\n_" + appended + "\n  </AppendedData>\n</VTKFile>\n";
  }
};

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
      binary_ = a.yes_no(i + 1, "yes (binary VTK) or no (ASCII)");
    } else if (k == "compressor") {
      if (a.word(i + 1, "none") != "none") a.fail(i + 1, "'none' (sable writes VTK uncompressed)");
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

  static std::vector<double> points(std::size_t n, const std::vector<double> (&xyz)[3]) {
    std::vector<double> p(3 * n);
    for (std::size_t j = 0; j < n; ++j)
      for (int k = 0; k < 3; ++k) p[3 * j + k] = xyz[k][j];
    return p;
  }

  std::string legacy(long step, std::size_t n, const std::vector<double> (&xyz)[3],
                     const std::vector<std::vector<double>>& data) const {
    // Version 3.0 (VERTICES as "1 i" cells): readable by every ParaView, old and new.
    std::string s = "# vtk DataFile Version 3.0\nGenerated by sable, step " + std::to_string(step) + "\n" +
                    (binary_ ? "BINARY" : "ASCII") + "\nDATASET POLYDATA\nPOINTS " + std::to_string(n) + " double\n";
    legacy_values(s, points(n, xyz), 3, false);
    s += "VERTICES " + std::to_string(n) + " " + std::to_string(2 * n) + "\n";
    std::vector<double> cells(2 * n, 1.0);
    for (std::size_t j = 0; j < n; ++j) cells[2 * j + 1] = static_cast<double>(j);
    legacy_values(s, cells, 2, true);
    if (n == 0 || arrays_.empty()) return s;
    s += "POINT_DATA " + std::to_string(n) + "\nFIELD FieldData " + std::to_string(arrays_.size()) + "\n";
    for (std::size_t a = 0; a < arrays_.size(); ++a) {
      const Array& arr = arrays_[a];
      s += arr.name + " " + std::to_string(arr.comps.size()) + " " + std::to_string(n) +
           (arr.integer() ? " int\n" : " double\n");
      legacy_values(s, data[a], arr.comps.size(), arr.integer());
    }
    return s;
  }

  // A legacy block's values: one tuple per line, or big-endian bytes and a newline.
  void legacy_values(std::string& s, const std::vector<double>& v, std::size_t nc, bool integer) const {
    if (!binary_) return tuples(s, v, nc, integer, "");
    for (double x : v) put_binary(s, x, integer, true);
    if (!v.empty()) s += '\n';
  }

  std::string xml(std::size_t n, const std::vector<double> (&xyz)[3], const std::vector<std::vector<double>>& data,
                  bool unstructured) const {
    const std::string N = std::to_string(n);
    const std::string type = unstructured ? "UnstructuredGrid" : "PolyData";
    XmlArrays out{binary_, {}};
    std::string s = "<?xml version=\"1.0\"?>\n" + out.file_tag(type) + "  <" + type + ">\n";
    s += unstructured ? "    <Piece NumberOfPoints=\"" + N + "\" NumberOfCells=\"" + N + "\">\n"
                      : "    <Piece NumberOfPoints=\"" + N + "\" NumberOfVerts=\"" + N +
                            "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
    s += "      <PointData>\n";
    for (std::size_t a = 0; a < arrays_.size(); ++a)
      s += out.array(arrays_[a].name, arrays_[a].integer(), arrays_[a].comps.size(), data[a]);
    s += "      </PointData>\n      <Points>\n" + out.array("Points", false, 3, points(n, xyz)) + "      </Points>\n";
    // One vertex cell per point.
    std::vector<double> conn(n), offs(n), types(n, 1.0);  // 1 = VTK_VERTEX
    for (std::size_t j = 0; j < n; ++j) {
      conn[j] = static_cast<double>(j);
      offs[j] = static_cast<double>(j + 1);
    }
    s += unstructured ? "      <Cells>\n" : "      <Verts>\n";
    s += out.array("connectivity", true, 1, conn);
    s += out.array("offsets", true, 1, offs);
    if (unstructured) s += out.array("types", true, 1, types);
    s += unstructured ? "      </Cells>\n" : "      </Verts>\n";
    return out.finish(s + "    </Piece>\n  </" + type + ">\n");
  }

  std::string pxml(const std::string& piece, bool unstructured) const {
    const std::string type = unstructured ? "PUnstructuredGrid" : "PPolyData";
    std::string s = "<?xml version=\"1.0\"?>\n" + XmlArrays{binary_, {}}.file_tag(type) + "  <" + type +
                    " GhostLevel=\"0\">\n    <PPointData>\n";
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
    XmlArrays out;  // ASCII: six numbers
    s = "<?xml version=\"1.0\"?>\n" + out.file_tag("RectilinearGrid") +
        "  <RectilinearGrid WholeExtent=\"0 1 0 1 0 1\">\n    <Piece Extent=\"0 1 0 1 0 1\">\n      <Coordinates>\n";
    for (int k = 0; k < 3; ++k) s += out.array(std::string(1, char('x' + k)), false, 1, {d.lo[k], d.hi[k]});
    return out.finish(s + "      </Coordinates>\n    </Piece>\n  </RectilinearGrid>\n");
  }

  static void write_plain(const std::string& path, const std::string& text) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) fail("dump custom/vtk: cannot open '" + path + "' for writing");
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (std::fclose(f) != 0 || !ok) fail("dump custom/vtk: writing '" + path + "' failed");
  }

  VtkFormat format_ = VtkFormat::Legacy;
  bool binary_ = false;  // dump_modify binary yes
  std::vector<Array> arrays_;
  DumpFilter filter_;
};

}  // namespace

SABLE_DUMP("custom/vtk", DumpCustomVTK);

}  // namespace sable
