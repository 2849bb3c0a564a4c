// dump custom/vtk: the files are parsed back and checked for structure (point and
// cell counts, every array holding one tuple per point) and values.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/input/style_registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_dump_custom_vtk {

using sable::test::Deck;
namespace fs = std::filesystem;

namespace {

// Per-atom test compute: 10 * id.
class ComputeVtkTestPeratom : public sable::Compute {
 public:
  ComputeVtkTestPeratom(sable::Simulation& s, const sable::Args& a) : Compute(s, a) { peratom_flag = true; }
  void compute_peratom() override {
    peratom.resize(sim.atoms.n);
    for (std::size_t i = 0; i < sim.atoms.n; ++i) peratom[i] = 10.0 * sim.atoms.id[i];
  }
};

// A fresh directory per test (parallel ctest runs never share files), removed
// when the test passes and kept for a look when it fails.
struct TestDir {
  std::string path;
  TestDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path = (fs::temp_directory_path() / ("sable_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                                         std::to_string(getpid())))
               .string();
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TestDir() {
    if (!::testing::Test::HasFailure()) fs::remove_all(path);
  }
};

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void three_grains(Deck& d) {
  d(R"(units si
atom_style granular
atom_modify map array sort 0 0
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.9 units box
create_atoms 1 single 0.2 0.3 0.4 units box
create_atoms 1 single 0.7 0.1 0.2 units box
compute pa all test/vtk_peratom
variable twice atom 2*vx)");
  sable::Atoms& a = d->atoms;
  const double v[3][3] = {{1.5, -2, 0.25}, {0.1, 0, 0}, {0, 0, -0.5}};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) a.v[3 * i + k] = v[i][k];
  a.set_radius_density(0, 0.05, 2500);
}

struct Array {
  int ncomp = 1;
  std::vector<double> values;
};

// Legacy POLYDATA: returns the point count, fills arrays (Points included); any
// structural error is a test failure.
std::size_t parse_legacy(const std::string& text, std::map<std::string, Array>& arrays) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("# vtk DataFile Version ", 0), 0u);
  std::getline(in, line);  // title
  std::getline(in, line);
  EXPECT_EQ(line, "ASCII");
  std::getline(in, line);
  EXPECT_EQ(line, "DATASET POLYDATA");
  std::string word, type;
  std::size_t n = 0, ncells = 0, size = 0, nfields = 0;
  in >> word >> n >> type;
  EXPECT_EQ(word, "POINTS");
  Array& pts = arrays["Points"];
  pts.ncomp = 3;
  pts.values.resize(3 * n);
  for (auto& x : pts.values) in >> x;
  in >> word >> ncells >> size;
  EXPECT_EQ(word, "VERTICES");
  EXPECT_EQ(ncells, n);
  EXPECT_EQ(size, 2 * n);
  for (std::size_t c = 0; c < ncells; ++c) {
    std::size_t one, idx;
    in >> one >> idx;
    EXPECT_EQ(one, 1u);
    EXPECT_EQ(idx, c);
  }
  EXPECT_FALSE(in.fail());
  if (in >> word) {
    EXPECT_EQ(word, "POINT_DATA");
    std::size_t np;
    in >> np >> word >> type >> nfields;
    EXPECT_EQ(np, n);
    EXPECT_EQ(word, "FIELD");
    for (std::size_t f = 0; f < nfields; ++f) {
      std::string name;
      std::size_t ntuples;
      Array arr;
      in >> name >> arr.ncomp >> ntuples >> type;
      EXPECT_EQ(ntuples, n) << name;
      EXPECT_TRUE(type == "int" || type == "double") << name << " " << type;
      arr.values.resize(arr.ncomp * ntuples);
      for (auto& x : arr.values) in >> x;
      arrays[name] = arr;
    }
    EXPECT_FALSE(in.fail());
  }
  EXPECT_FALSE(in >> word) << "trailing '" << word << "'";
  return n;
}

std::string attr(const std::string& tag, const std::string& name) {
  const std::size_t p = tag.find(" " + name + "=\"");
  if (p == std::string::npos) return "";
  const std::size_t b = p + name.size() + 3;
  return tag.substr(b, tag.find('"', b) - b);
}

// XML (.vtu/.vtp): every DataArray with its component count and values, keyed by Name;
// piece attributes (NumberOfPoints, NumberOfCells / NumberOfVerts) in `piece`.
void parse_xml(const std::string& text, std::map<std::string, Array>& arrays, std::string& piece) {
  ASSERT_EQ(text.rfind("<?xml version=\"1.0\"?>\n<VTKFile ", 0), 0u);
  const std::size_t pp = text.find("<Piece ");
  ASSERT_NE(pp, std::string::npos);
  piece = text.substr(pp, text.find('>', pp) - pp);
  for (std::size_t p = 0; (p = text.find("<DataArray ", p)) != std::string::npos;) {
    const std::size_t close = text.find('>', p);
    const std::string tag = text.substr(p, close - p);
    const std::size_t end = text.find("</DataArray>", close);
    ASSERT_NE(end, std::string::npos);
    Array arr;
    if (!attr(tag, "NumberOfComponents").empty()) arr.ncomp = std::stoi(attr(tag, "NumberOfComponents"));
    std::istringstream vs(text.substr(close + 1, end - close - 1));
    for (double x; vs >> x;) arr.values.push_back(x);
    EXPECT_TRUE(vs.eof()) << "non-numeric data in " << tag;
    arrays[attr(tag, "Name")] = arr;
    p = end;
  }
  // Tags balance (a cheap well-formedness check).
  auto count = [&](const std::string& s) {
    std::size_t c = 0;
    for (std::size_t p = 0; (p = text.find(s, p)) != std::string::npos; ++p) ++c;
    return c;
  };
  for (std::string t : {"VTKFile", "Piece", "PointData", "Points", "DataArray"})
    EXPECT_EQ(count("<" + t + " ") + count("<" + t + ">"), count("</" + t + ">")) << t;
}

}  // namespace

SABLE_COMPUTE("test/vtk_peratom", ComputeVtkTestPeratom);

TEST(DumpCustomVtk, LegacyFilePerSnapshotWithVectorsGrouped) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  d("dump v all custom/vtk 2 " + dir + "/snap*.vtk id type radius vx vy vz fx fy fz omegax omegay omegaz mass x y z "
    "c_pa v_twice vx\n"
    "dump_modify v sort id\n"
    "run 3");
  std::vector<std::string> names;
  for (auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"snap0.vtk", "snap2.vtk", "snapboundingBox_0.vtk",
                                             "snapboundingBox_2.vtk"}));  // LIGGGHTS' names, no .tmp left
  std::map<std::string, Array> arr;
  EXPECT_EQ(parse_legacy(slurp(dir + "/snap0.vtk"), arr), 3u);
  // x y z are the points; vx vy vz -> v (3 components); duplicates dropped; v_twice -> "twice".
  const std::map<std::string, int> want = {{"Points", 3}, {"id", 1}, {"type", 1}, {"radius", 1}, {"v", 3},
                                           {"f", 3},      {"omega", 3}, {"mass", 1}, {"c_pa", 1}, {"twice", 1}};
  ASSERT_EQ(arr.size(), want.size());
  for (auto& [name, nc] : want) {
    ASSERT_TRUE(arr.count(name)) << name;
    EXPECT_EQ(arr[name].ncomp, nc) << name;
    EXPECT_EQ(arr[name].values.size(), 3u * nc) << name;
  }
  // Values, in id order; printed with 12 significant digits.
  EXPECT_EQ(arr["id"].values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(arr["c_pa"].values, (std::vector<double>{10, 20, 30}));
  EXPECT_EQ(arr["v"].values, (std::vector<double>{1.5, -2, 0.25, 0.1, 0, 0, 0, 0, -0.5}));
  EXPECT_EQ(arr["twice"].values, (std::vector<double>{3, 0.2, 0}));
  EXPECT_EQ(arr["Points"].values, (std::vector<double>{0.5, 0.5, 0.9, 0.2, 0.3, 0.4, 0.7, 0.1, 0.2}));
  EXPECT_EQ(arr["radius"].values[0], 0.05);
  // The bounding box is a 2x2x2 rectilinear grid of the box bounds.
  const std::string bb = slurp(dir + "/snapboundingBox_2.vtk");
  EXPECT_NE(bb.find("DATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2\nX_COORDINATES 2 double\n0 1\n"), std::string::npos) << bb;
}

TEST(DumpCustomVtk, XmlUnstructuredGridAndPolyData) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  d("dump u all custom/vtk 1 " + dir + "/u.vtu id vx fx fy fz\n"
    "dump p all custom/vtk 1 " + dir + "/p.vtp id type omegax omegay omegaz\n"
    "run 2");
  for (const char* f : {"u.vtu", "p.vtp"}) {
    const bool ug = f[0] == 'u';
    std::map<std::string, Array> arr;
    std::string piece;
    parse_xml(slurp(dir + "/" + f), arr, piece);
    EXPECT_EQ(attr(piece, "NumberOfPoints"), "3") << f;
    EXPECT_EQ(attr(piece, ug ? "NumberOfCells" : "NumberOfVerts"), "3") << f;
    EXPECT_EQ(arr["Points"].ncomp, 3);
    EXPECT_EQ(arr["Points"].values.size(), 9u);
    EXPECT_EQ(arr["connectivity"].values, (std::vector<double>{0, 1, 2}));
    EXPECT_EQ(arr["offsets"].values, (std::vector<double>{1, 2, 3}));
    if (ug) {
      EXPECT_EQ(arr["types"].values, (std::vector<double>{1, 1, 1}));  // VTK_VERTEX
      EXPECT_EQ(arr["vx"].ncomp, 1);  // a lone component stays a scalar array
      EXPECT_EQ(arr["vx"].values.size(), 3u);
      EXPECT_EQ(arr["f"].ncomp, 3);
      EXPECT_EQ(arr["f"].values.size(), 9u);
      EXPECT_EQ(arr.size(), 7u);  // id vx f Points connectivity offsets types
    } else {
      EXPECT_EQ(arr["omega"].ncomp, 3);
      EXPECT_EQ(arr["omega"].values.size(), 9u);
      EXPECT_EQ(arr.size(), 6u);  // id type omega Points connectivity offsets
    }
    EXPECT_EQ(arr["id"].values.size(), 3u);
  }
  // Single-file mode rewrites the file (atomically) and writes LIGGGHTS' box file beside it.
  EXPECT_TRUE(fs::exists(dir + "/u_boundingBox.vtr"));
  EXPECT_TRUE(fs::exists(dir + "/p_boundingBox.vtr"));
  std::map<std::string, Array> bb;
  std::string piece;
  parse_xml(slurp(dir + "/u_boundingBox.vtr"), bb, piece);
  EXPECT_EQ(bb["z"].values, (std::vector<double>{0, 1}));
  for (auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().extension(), ".tmp");
}

TEST(DumpCustomVtk, ParallelWrapperPointsAtItsPiece) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  d("dump w all custom/vtk 1 " + dir + "/w*.pvtu id vx vy vz\nrun 0");
  const std::string wrapper = slurp(dir + "/w0.pvtu");
  EXPECT_NE(wrapper.find("<PUnstructuredGrid GhostLevel=\"0\">"), std::string::npos) << wrapper;
  EXPECT_NE(wrapper.find("<PDataArray type=\"Float64\" Name=\"v\" NumberOfComponents=\"3\"/>"), std::string::npos);
  EXPECT_NE(wrapper.find("<Piece Source=\"w0_0.vtu\"/>"), std::string::npos) << wrapper;
  std::map<std::string, Array> arr;
  std::string piece;
  parse_xml(slurp(dir + "/w0_0.vtu"), arr, piece);
  EXPECT_EQ(attr(piece, "NumberOfPoints"), "3");
  EXPECT_EQ(arr["v"].values.size(), 9u);
}

TEST(DumpCustomVtk, ThreshSelectsAtoms) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  d("dump t all custom/vtk 1 " + dir + "/t.vtk id radius\ndump_modify t thresh radius < 0.1\nrun 0");
  std::map<std::string, Array> arr;
  EXPECT_EQ(parse_legacy(slurp(dir + "/t.vtk"), arr), 1u);  // only atom 1 has r = 0.05 < 0.1 (others 0.5)
  EXPECT_EQ(arr["id"].values, (std::vector<double>{1}));
  // Empty selection: still a valid file.
  d("dump_modify t thresh radius > 10\nrun 0");
  arr.clear();
  EXPECT_EQ(parse_legacy(slurp(dir + "/t.vtk"), arr), 0u);
}

TEST(DumpCustomVtk, VtkLibraryReadsEveryFormat) {
  // ParaView reads with VTK's readers: let them read each format. The test
  // command installs Debian's python3-vtk9 (.ci/install_deps.sh); without it this fails.
  std::string py;
  for (const char* c : {"/usr/bin/python3", "python3"})
    if (std::system((std::string(c) + " -c 'import vtk' > /dev/null 2>&1").c_str()) == 0) {
      py = c;
      break;
    }
  ASSERT_FALSE(py.empty()) << "no python3 with the vtk module: apt-get install python3-vtk9 (.ci/install_deps.sh does)";
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  for (const char* f : {"a.vtk", "b.vtu", "c.vtp", "d.pvtu", "e.pvtp"})
    d(std::string("dump ") + f[0] + " all custom/vtk 1 " + dir + "/" + f + " id vx vy vz radius c_pa");
  d("run 0");
  std::ofstream(dir + "/read.py") << R"(import sys, vtk
for p in sys.argv[1:]:
    r = vtk.vtkGenericDataObjectReader() if p.endswith('.vtk') else vtk.vtkXMLGenericDataObjectReader()
    r.SetFileName(p)
    r.Update()
    o = r.GetOutput()
    pd = o.GetPointData()
    a = ' '.join('%s:%d:%d' % (pd.GetArrayName(i), pd.GetArray(i).GetNumberOfComponents(),
                               pd.GetArray(i).GetNumberOfTuples()) for i in range(pd.GetNumberOfArrays()))
    print(p.split('/')[-1], o.GetClassName(), o.GetNumberOfPoints(), o.GetNumberOfCells(), a)
)";
  std::string cmd = py + " " + dir + "/read.py";
  for (const char* f : {"a.vtk", "b.vtu", "c.vtp", "d.pvtu", "e.pvtp", "a_boundingBox.vtk", "b_boundingBox.vtr"})
    cmd += " " + dir + "/" + f;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  EXPECT_EQ(pclose(p), 0) << out;
  const std::string arrays = " 3 3 id:1:3 v:3:3 radius:1:3 c_pa:1:3\n";
  EXPECT_EQ(out, "a.vtk vtkPolyData" + arrays + "b.vtu vtkUnstructuredGrid" + arrays + "c.vtp vtkPolyData" + arrays +
                     "d.pvtu vtkUnstructuredGrid" + arrays + "e.pvtp vtkPolyData" + arrays +
                     "a_boundingBox.vtk vtkRectilinearGrid 8 1 \nb_boundingBox.vtr vtkRectilinearGrid 8 1 \n");
}

}  // namespace test_dump_custom_vtk
