// ParaView output, probe histories and plots, read back and checked against the particle state.
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/history.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_table.hpp"
#include "io/output.hpp"
#include "io/paraview_script.hpp"
#include "io/probe_plot.hpp"
#include "io/text_lines.hpp"
#include "lua/lua_fixture.hpp"
#include "materials/linear_elastic.hpp"

namespace fs = std::filesystem;
using namespace seismpm;

namespace {

std::string fresh_dir(const std::string& name) {
  const std::string dir = (fs::temp_directory_path() / ("seismpm_test_" + name)).string();
  fs::remove_all(dir);
  return dir;
}

// (time, file) entries of a .pvd, and a check that it is well-formed.
std::vector<std::pair<double, std::string>> read_pvd(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  REQUIRE(text.find("<VTKFile type=\"Collection\"") != std::string::npos);
  REQUIRE(text.find("</VTKFile>") != std::string::npos);
  std::vector<std::pair<double, std::string>> out;
  const std::regex entry("<DataSet timestep=\"([^\"]+)\"[^>]*file=\"([^\"]+)\"/>");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it)
    out.emplace_back(std::stod((*it)[1]), (*it)[2]);
  return out;
}

vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::string& path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  REQUIRE(reader->GetErrorCode() == 0);
  return reader->GetOutput();
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

ino_t inode_of(const std::string& path) {
  struct stat st {};
  REQUIRE(stat(path.c_str(), &st) == 0);
  return st.st_ino;
}

// `before` without its last row (which may be written again) begins `after`: rows were added, not
// the file rewritten differently.
bool extends(const std::string& before, const std::string& after) {
  const auto cut = before.size() < 2 ? 0 : before.rfind('\n', before.size() - 2) + 1;
  return after.compare(0, cut, before, 0, cut) == 0;
}

// A block in a unit box, falling; and a rigid base under it that stays.
std::unique_ptr<Model<2>> block_on_base(const std::string& base_name) {
  ModelSettings<2> s;
  s.cell = 0.05;
  s.gravity = Vec<2>(0.0, -9.81);
  auto m = std::make_unique<Model<2>>(s);
  const int mat = m->add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  m->fill_box(m->add_body("block", 2), mat, Vec<2>(0.3, 0.5), Vec<2>(0.7, 0.9));
  std::array<std::shared_ptr<const History>, 2> v = {std::make_shared<ConstantHistory>(0.0),
                                                     std::make_shared<ConstantHistory>(0.0)};
  m->fill_box(m->add_rigid_body(base_name, 2, 2000, v), -1, Vec<2>(0.1, 0.05), Vec<2>(0.9, 0.1));
  return m;
}

}  // namespace

TEST_CASE("ParaView files hold the particle state and the pvd lists them with their times", "[io][vtu]") {
  const std::string dir = fresh_dir("vtu");
  test::LuaFixture f;
  const std::string error = f.error_of(R"(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    mat = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
    b = m:body{ name = "block", material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
    m:fix{ side = "bottom" }
    p = m:probe{ name = "top", body = b, at = {0.5, 0.5} }
    m:output{ dir = ")" + dir + R"(", every = 0.05, grid = true, probe_every = 0.01 }
    m:run{ duration = 0.2 }
    uy = b:field("uy"); syy = b:field("syy"); ids = b:field("id")
  )");
  REQUIRE(error == "");
  const auto files = read_pvd(dir + "/particles.pvd");
  REQUIRE(files.size() == 5);  // t = 0, 0.05, 0.1, 0.15, 0.2
  for (std::size_t k = 0; k < files.size(); ++k) {
    CHECK(files[k].first == Approx(0.05 * k).margin(1e-9));
    CHECK(fs::exists(dir + "/" + files[k].second));
  }
  CHECK(read_pvd(dir + "/grid.pvd").size() == 5);
  // The last file against the particle state, array by array.
  auto grid = read_vtu(dir + "/" + files.back().second);
  lua_State* L = f.runtime.state();
  const int n = 200;
  REQUIRE(grid->GetNumberOfPoints() == n);
  REQUIRE(grid->GetNumberOfCells() == n);
  auto* pd = grid->GetPointData();
  for (const char* name : {"id", "body", "material", "mass", "volume", "density", "displacement", "velocity", "stress",
                           "strain", "pressure", "q", "shear_strain", "plastic_strain", "yield"})
    CHECK(pd->GetArray(name) != nullptr);
  CHECK(pd->GetArray("displacement")->GetNumberOfComponents() == 3);
  CHECK(pd->GetArray("stress")->GetNumberOfComponents() == 6);
  CHECK(grid->GetFieldData()->GetArray("TimeValue")->GetTuple1(0) == Approx(0.2));
  double worst = 0.0;
  for (int k = 0; k < n; ++k) {
    // Files are in particle (storage) order; map back through the id array.
    const int id = static_cast<int>(pd->GetArray("id")->GetTuple1(k));
    for (const char* table : {"ids", "uy", "syy"}) lua_getglobal(L, table);
    int index = 0;
    for (int i = 1; i <= n; ++i) {
      lua_rawgeti(L, -3, i);
      if (static_cast<int>(lua_tonumber(L, -1)) == id) index = i;
      lua_pop(L, 1);
    }
    REQUIRE(index > 0);
    lua_rawgeti(L, -2, index);
    const double uy = lua_tonumber(L, -1);
    lua_rawgeti(L, -2, index);
    const double syy = lua_tonumber(L, -1);
    lua_pop(L, 5);
    worst = std::max(worst, std::abs(pd->GetArray("displacement")->GetComponent(k, 1) - uy));
    worst = std::max(worst, std::abs(pd->GetArray("stress")->GetComponent(k, 1) - syy) * 1e-6);
  }
  CHECK(worst == 0.0);  // binary doubles: exact
  // probes.csv: a header with every field of the probe, a row per 0.01 s.
  const auto csv = lines_of(dir + "/probes.csv");
  REQUIRE(csv.size() == 1 + 21);
  CHECK(csv[0].rfind("time (s),phase,phase_time (s),top.id,top.body,top.material,top.mass", 0) == 0);
  CHECK(csv[0].find("top.uy") != std::string::npos);
  CHECK(std::count(csv[0].begin(), csv[0].end(), ',') == 23);  // time, phase, phase time + 21 fields in 2D
  // Before any phase: the phase "run", and its time is the model time.
  CHECK(split_csv_fields(csv[5])[1] == "run");
  CHECK(std::stod(split_csv_fields(csv[5])[2]) == Approx(std::stod(split_csv_fields(csv[5])[0])));
  // No temporary files are left behind.
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().extension() != ".tmp");
}

TEST_CASE("rigid bodies go to their own files", "[io][vtu]") {
  const std::string dir = fresh_dir("rigid");
  ModelSettings<2> s;
  s.cell = 0.1;
  Model<2> m(s);
  const int mat = m.add_material(std::make_shared<LinearElastic>(1000, 1e6, 0.3));
  m.fill_box(m.add_body("soil", 2), mat, Vec<2>(0.2, 0.3), Vec<2>(0.8, 0.8));
  m.fill_box(m.add_body("base", 2, true), mat, Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.2));
  Output<2> out(OutputSettings{dir, 0.1});
  out.write(m, {}, "gravity");
  CHECK(read_vtu(dir + "/particles_000000.vtu")->GetNumberOfPoints() == 120);  // 0.6 x 0.5 m, 4 per 0.1 m cell
  auto rigid = read_vtu(dir + "/rigid_000000.vtu");
  CHECK(rigid->GetNumberOfPoints() == 80);
  CHECK(rigid->GetPointData()->GetArray("body")->GetRange()[0] == 1);
  CHECK(read_pvd(dir + "/rigid.pvd").size() == 1);
  auto* phase = vtkStringArray::SafeDownCast(rigid->GetFieldData()->GetAbstractArray("phase"));
  REQUIRE(phase);
  CHECK(phase->GetValue(0) == "gravity");
}

// The material and body indices the particles carry, named in each file: a layered body's materials
// can be told apart in ParaView.
TEST_CASE("the particle files name the material and body indices", "[io][vtu][regions]") {
  const std::string dir = fresh_dir("names");
  ModelSettings<2> s;
  s.cell = 0.1;
  Model<2> m(s);
  const int sand = m.add_material(std::make_shared<LinearElastic>(1800, 1e6, 0.3), "sand");
  const int clay = m.add_material(std::make_shared<LinearElastic>(2000, 1e6, 0.3));
  m.fill(
      m.add_body("ground", 2), [&](const Vec<2>& x) { return x[1] < 0.5 ? clay : sand; }, Vec<2>(0.0, 0.3),
      Vec<2>(1.0, 0.8), [](const Vec<2>&) { return true; });
  m.fill_box(m.add_body("base", 1, true), -1, Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.2));
  Output<2> out(OutputSettings{dir, 0.1});
  out.write(m, {}, "gravity");
  auto grid = read_vtu(dir + "/particles_000000.vtu");
  auto* materials = vtkStringArray::SafeDownCast(grid->GetFieldData()->GetAbstractArray("material_names"));
  auto* bodies = vtkStringArray::SafeDownCast(grid->GetFieldData()->GetAbstractArray("body_names"));
  REQUIRE(materials);
  REQUIRE(bodies);
  REQUIRE(materials->GetNumberOfValues() == 3);
  CHECK(materials->GetValue(0) == "sand");
  CHECK(materials->GetValue(1) == "linear_elastic");  // no name given: the kind
  CHECK(materials->GetValue(2) == "rigid base");
  REQUIRE(bodies->GetNumberOfValues() == 2);
  CHECK(bodies->GetValue(0) == "ground");
  CHECK(bodies->GetValue(1) == "base");
  // Each particle's index names the material of its layer (cell rows 0.3-0.5 clay, 0.5-0.8 sand).
  auto* material = grid->GetPointData()->GetArray("material");
  int wrong = 0;
  for (vtkIdType k = 0; k < grid->GetNumberOfPoints(); ++k) {
    const std::string name = materials->GetValue(static_cast<vtkIdType>(material->GetTuple1(k)));
    wrong += name != (grid->GetPoint(k)[1] < 0.5 ? "linear_elastic" : "sand");
  }
  CHECK(grid->GetNumberOfPoints() == 200);
  CHECK(wrong == 0);
}

TEST_CASE("a run that fails between two writes leaves valid files", "[io][vtu]") {
  const std::string dir = fresh_dir("failed");
  test::LuaFixture f;
  const std::string error = f.error_of(R"(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1, gravity = {0, 0} }
    mat = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
    b = m:body{ material = mat, shape = mpm.shape.rectangle{ 0.5, 0.4, 0.7, 0.6 } }
    b:set_velocity{ 3.0, 0 }
    m:output{ dir = ")" + dir + R"(", every = 0.02 }
    m:run{ duration = 1 }
  )");
  CHECK_THAT(error, Catch::Contains("left the grid"));  // at t = 0.108 s
  const auto files = read_pvd(dir + "/particles.pvd");
  REQUIRE(files.size() == 6);  // 0, 0.02, ... 0.1: all that was reached
  CHECK(files.back().first == Approx(0.1));
  for (const auto& [t, file] : files) CHECK(read_vtu(dir + "/" + file)->GetNumberOfPoints() == 16);
}

TEST_CASE("an unwritable output directory is an error naming the path", "[io][vtu]") {
  test::LuaFixture f;
  const std::string error = f.error_of(R"(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    m:output{ dir = "/proc/seismpm_cannot_write_here", every = 0.1 }
  )");
  CHECK_THAT(error,
             Catch::Contains("model:output: cannot create the output directory /proc/seismpm_cannot_write_here"));
  CHECK_THROWS_AS(write_file_atomically("/proc/nope/file.txt", "x"), OutputError);
  CHECK_THAT(
      f.error_of("mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }:output{ dir = '/tmp/x', fields = {'speed'} }"),
      Catch::Contains("unknown output field 'speed'"));
}

TEST_CASE("probe plots are PNG images, one per quantity", "[io][plot]") {
  const std::string dir = fresh_dir("plot");
  test::LuaFixture f;
  const std::string error = f.error_of(R"(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
    b = m:body{ material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
    m:fix{ side = "bottom" }
    m:probe{ name = "crest", body = b, at = {0.5, 0.5} }
    m:probe{ name = "toe", body = b, at = {0.9, 0.1} }
    m:output{ dir = ")" + dir + R"(", every = 0.1 }
    m:run{ duration = 0.3 }
    pngs = m:plot{ quantities = {"ux", "uy", "syy"} }
    assert(#pngs == 3)
  )");
  REQUIRE(error == "");
  for (const char* q : {"ux", "uy", "syy"}) {
    const std::string png = dir + "/probe_" + q + ".png";
    std::ifstream in(png, std::ios::binary);
    REQUIRE(in);
    unsigned char head[24] = {};
    in.read(reinterpret_cast<char*>(head), 24);
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    CHECK(std::equal(signature, signature + 8, head));
    const unsigned width = head[16] << 24 | head[17] << 16 | head[18] << 8 | head[19];
    const unsigned height = head[20] << 24 | head[21] << 16 | head[22] << 8 | head[23];
    CHECK(width == 960);
    CHECK(height == 540);
    CHECK(fs::file_size(png) > 5000);  // curves, labels: more than an empty frame
  }
  CHECK_THROWS_WITH(plot_probes(dir, {"speed"}), Catch::Contains("no probe column ends in .speed"));
  CHECK_THROWS_WITH(plot_probes(dir + "/none", {"ux"}), Catch::Contains("probes.csv does not exist"));
}

TEST_CASE("the --out directory replaces a default output directory, never one the script names", "[io][lua]") {
  const std::string cli = fresh_dir("out_rule_cli"), named = fresh_dir("out_rule_named");
  const std::string model = R"(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
    b = m:body{ material = mat, shape = mpm.shape.rectangle{ 0.2, 0.2, 0.6, 0.6 } }
  )";
  test::LuaFixture f;
  f.session.out_dir = cli;
  CHECK(f.error_of(model + "assert(mpm.out_dir('out/default') == '" + cli + "')") == "");
  CHECK(f.error_of(model + "m:output{ dir = '" + named + "', every = 0.1 }") == "");
  CHECK(fs::exists(named + "/particles.pvd"));
  CHECK_FALSE(fs::exists(cli));
  CHECK(f.error_of(model + "m:output{ every = 0.1 }") == "");  // no dir: the --out one
  CHECK(fs::exists(cli + "/particles.pvd"));
  test::LuaFixture plain;  // no --out: the default as given, and m:output needs its dir
  CHECK(plain.error_of("assert(mpm.out_dir('out/default') == 'out/default' and mpm.out_dir() == nil)") == "");
  CHECK_THAT(plain.error_of(model + "m:output{ every = 0.1 }"), Catch::Contains("missing key 'dir'"));
}

TEST_CASE("particle files are in id order across the kernel's sorts, id the global ids, with the phase time",
          "[io][vtu]") {
  const std::string dir = fresh_dir("vtu_id_order");
  test::LuaFixture f;
  const std::string error = f.error_of(R"(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    mat = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
    -- Two bodies side by side: made one after the other, their particles interleave once sorted by cell.
    local a = m:body{ name = "left", material = mat, shape = mpm.shape.rectangle{ 0, 0, 0.5, 0.5 }, ppc = 3 }
    local b = m:body{ name = "right", material = mat, shape = mpm.shape.rectangle{ 0.5, 0, 1, 0.5 }, ppc = 3 }
    m:fix{ side = "bottom" }
    m:output{ dir = ")" + dir + R"(", every = 0.05 }
    m:run{ duration = 0.1 }
    m:dynamic_phase{ duration = 0.1 }
    ids, xs = a:field("id"), a:field("x")
    for i, id in ipairs(b:field("id")) do ids[#ids + 1] = id end
    for i, x in ipairs(b:field("x")) do xs[#xs + 1] = x end
  )");
  REQUIRE(error == "");
  lua_State* L = f.runtime.state();
  // In storage the kernel's sort by cell interleaves the rows of the two bodies; the files must not.
  lua_getglobal(L, "ids");
  lua_getglobal(L, "xs");
  const int n = static_cast<int>(lua_rawlen(L, -2));
  REQUIRE(n == 450);
  std::vector<double> x_of_id(n);
  for (int i = 1; i <= n; ++i) {
    lua_rawgeti(L, -2, i);
    const int id = static_cast<int>(lua_tonumber(L, -1));
    lua_rawgeti(L, -2, i);
    x_of_id[id] = lua_tonumber(L, -1);
    lua_pop(L, 2);
  }
  lua_pop(L, 2);
  const auto files = read_pvd(dir + "/particles.pvd");
  REQUIRE(files.size() >= 4);
  for (const auto& [t, file] : files) {
    auto grid = read_vtu(dir + "/" + file);
    auto* ids = grid->GetPointData()->GetGlobalIds();
    REQUIRE(ids != nullptr);
    CHECK(std::string(ids->GetName()) == "id");
    bool in_order = true;
    for (vtkIdType k = 0; k < grid->GetNumberOfPoints(); ++k) in_order = in_order && ids->GetTuple1(k) == k;
    CHECK(in_order);
    REQUIRE(grid->GetFieldData()->GetArray("phase_time") != nullptr);
  }
  // The last file: point k is particle k, and the phase time is the dynamic phase's own clock.
  auto last = read_vtu(dir + "/" + files.back().second);
  double worst = 0.0;
  for (int k = 0; k < n; ++k) worst = std::max(worst, std::abs(last->GetPoint(k)[0] - x_of_id[k]));
  CHECK(worst == 0.0);
  CHECK(last->GetFieldData()->GetArray("TimeValue")->GetTuple1(0) == Approx(0.2));
  CHECK(last->GetFieldData()->GetArray("phase_time")->GetTuple1(0) == Approx(0.1));
}

// open_in_paraview.py comes with the first particle file, beside particles.pvd, and opens the files
// it finds beside itself: no path of the run's directory is written into it, so the folder can move.
// (The ctest paraview_script_is_python compiles a written script with python3.)
TEST_CASE("the ParaView script is written beside particles.pvd and names the files relative to its folder",
          "[io][vtu][paraview]") {
  const std::string dir = fresh_dir("paraview_script");
  const std::string script = dir + "/" + kParaViewScript;
  auto m = block_on_base("base");  // cell 0.05, 2 particles per cell: a radius of 0.0125 m
  Output<2> out(OutputSettings{dir, 0.1});
  CHECK_FALSE(fs::exists(script));
  out.write(*m, {}, "gravity");
  REQUIRE(fs::exists(script));
  const std::string text = read_text(script);
  CHECK(text == paraview_script_text(ParaViewScriptSettings{2, 0.0125, 0.0125}));
  CHECK(fs::path(script).parent_path() == fs::path(dir + "/particles.pvd").parent_path());
  CHECK(text.find(dir) == std::string::npos);
  CHECK(text.find("seismpm_test_paraview_script") == std::string::npos);
  for (const char* file : {"particles.pvd", "rigid.pvd", "grid.pvd"})
    CHECK(text.find("os.path.join(folder, \"" + std::string(file) + "\")") != std::string::npos);
  CHECK(text.find("ColorBy(display, (\"POINTS\", \"displacement\", \"Magnitude\"))") != std::string::npos);
  CHECK(text.find("\nDIM = 2 ") != std::string::npos);
  CHECK(text.find("\nPARTICLE_RADIUS = 0.0125 ") != std::string::npos);
  // The folder from __file__ (pvpython, --state) and else from the program's arguments (--script).
  CHECK(text.find("os.path.dirname(os.path.abspath(here))") != std::string::npos);
  CHECK(text.find("/proc/self/cmdline") != std::string::npos);
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().extension() != ".tmp");
  // A 3D model's script keeps ParaView's 3D interaction.
  CHECK(paraview_script_text(ParaViewScriptSettings{3, 0.1, 0.2}).find("\nDIM = 3 ") != std::string::npos);
}

TEST_CASE("probes.csv grows by appended rows and always equals the whole table", "[io][probes][robustness]") {
  const std::string dir = fresh_dir("probes_append");
  const std::string csv = dir + "/probes.csv";
  auto model = block_on_base("base");
  auto& m = *model;
  OutputSettings settings;
  settings.dir = dir;
  Output<2> out(settings);
  // Names that a naive CSV writer would split or break: a comma, quotes.
  std::vector<std::shared_ptr<Probe<2>>> probes = {std::make_shared<Probe<2>>(m, "a,b", 0),
                                                   std::make_shared<Probe<2>>(m, "say \"hi\"", 5)};
  out.write(m, probes, "run");
  ino_t inode = inode_of(csv);
  std::string text = read_text(csv);
  REQUIRE(text == probes_csv_text(probes));
  // After each write: the file is what a whole rewrite gives, it is the same file (appended in place,
  // not renamed over), and what was on file before is still there.
  auto check_write = [&](const std::string& what) {
    const std::string now = read_text(csv);
    CAPTURE(what, m.time());
    CHECK(now == probes_csv_text(probes));
    CHECK(inode_of(csv) == inode);
    CHECK(extends(text, now));
    text = now;
  };
  SECTION("many outputs, the probes sampled at different times") {
    for (int k = 1; k <= 58; ++k) {  // the last output at a time the second probe has no sample
      m.step();
      probes[0]->sample(m, "run");
      if (k % 3 == 0) probes[1]->sample(m, "run");
      if (k % 2 == 0) {
        out.write(m, probes, "run");
        check_write("output " + std::to_string(k / 2));
      }
    }
    CHECK(lines_of(csv).size() == 60u);  // the header and a row per step (and t = 0)
    SECTION("a probe sampled at a row time already written fills that row in") {
      const std::string last_row = lines_of(csv).back();
      probes[1]->sample(m, "run");  // as at a run's end, after the output at the same time
      out.write_probes(probes);
      check_write("row filled in");
      CHECK(lines_of(csv).size() == 60u);
      CHECK(lines_of(csv).back() != last_row);
      out.write_probes(probes);  // nothing new: nothing changes
      check_write("nothing new");
    }
    SECTION("a probe added between runs: the table is written whole once, then appended again") {
      probes.push_back(std::make_shared<Probe<2>>(m, "third", 10));
      m.step();
      for (auto& p : probes) p->sample(m, "run");
      out.write(m, probes, "run");
      CHECK(read_text(csv) == probes_csv_text(probes));
      inode = inode_of(csv);
      text = read_text(csv);
      for (int k = 0; k < 10; ++k) {
        m.step();
        for (auto& p : probes) p->sample(m, "run");
        out.write(m, probes, "run");
        check_write("after the new probe");
      }
    }
    SECTION("the columns read back by their quoted names; seismpm plot takes the same columns") {
      const auto c = read_csv_columns(csv, {"time (s)", "a,b.ux", "a,b.y"});
      REQUIRE(c.columns[0].size() == probes[0]->samples());
      const auto ux = probes[0]->series(Field::Ux), y = probes[0]->series(Field::Y);
      for (std::size_t k = 0; k < ux.size(); ++k) {
        CAPTURE(k);
        CHECK(c.columns[0][k] == Approx(probes[0]->times()[k]));
        CHECK(c.columns[1][k] == Approx(ux[k]).margin(1e-12));
        CHECK(c.columns[2][k] == Approx(y[k]));
      }
      // Column numbers from the field order, independent of any CSV parsing: time, phase, phase time,
      // then each probe's fields.
      const auto fields = particle_fields(2);
      const std::size_t ux_at = std::find(fields.begin(), fields.end(), Field::Ux) - fields.begin();
      const auto columns = probe_columns(csv, "ux");
      using Column = std::pair<std::size_t, std::string>;
      CHECK(columns == std::vector<Column>{{4 + ux_at, "a,b"}, {4 + fields.size() + ux_at, "say \"hi\""}});
    }
  }
}

TEST_CASE("reactions.csv grows by appended rows, quoted names keeping their columns", "[io][reactions][robustness]") {
  const std::string dir = fresh_dir("reactions_append");
  const std::string csv = dir + "/reactions.csv";
  auto model = block_on_base("ba\"se,1");
  auto& m = *model;
  OutputSettings settings;
  settings.dir = dir;
  Output<2> out(settings);
  out.write(m, {}, "gravity, settling");
  const ino_t inode = inode_of(csv);
  std::string text = read_text(csv);
  for (int k = 1; k <= 30; ++k) {
    m.step();
    out.write(m, {}, "dynamic");
    const std::string now = read_text(csv);
    CAPTURE(k);
    CHECK(inode_of(csv) == inode);
    CHECK(now.compare(0, text.size(), text) == 0);  // every earlier byte unchanged
    text = now;
  }
  TextLines in(csv);
  std::string line;
  REQUIRE(in.next(line));
  CHECK(split_csv_fields(line) ==
        std::vector<std::string>{"time (s)", "phase", "ba\"se,1.fx (N/m)", "ba\"se,1.fy (N/m)"});
  int rows = 0;
  while (in.next(line)) {
    const auto cells = split_csv_fields(line);
    CAPTURE(line);
    CHECK(cells.size() == 4u);
    CHECK(cells[1] == (rows == 0 ? "gravity, settling" : "dynamic"));
    ++rows;
  }
  CHECK(rows == 31);
  const auto c = read_csv_columns(csv, {"time (s)", "ba\"se,1.fy (N/m)"});
  CHECK(c.columns[0].back() == Approx(m.time()));
}

TEST_CASE("a rigid body added between runs widens reactions.csv: every row keeps the header's columns",
          "[io][reactions]") {
  const std::string dir = fresh_dir("reactions_widened");
  const std::string csv = dir + "/reactions.csv";
  auto model = block_on_base("base");
  auto& m = *model;
  Output<2> out(OutputSettings{dir, 0.1});
  out.write(m, {}, "gravity");
  m.step();
  out.write(m, {}, "gravity");
  std::array<std::shared_ptr<const History>, 2> v = {std::make_shared<ConstantHistory>(0.0),
                                                     std::make_shared<ConstantHistory>(0.0)};
  m.fill_box(m.add_rigid_body("wall", 2, 2000, v), -1, Vec<2>(0.1, 0.1), Vec<2>(0.15, 0.9));
  for (int k = 0; k < 3; ++k) {
    m.step();
    out.write(m, {}, "dynamic");
  }
  TextLines in(csv);
  std::string line;
  REQUIRE(in.next(line));
  CHECK(split_csv_fields(line) == std::vector<std::string>{"time (s)", "phase", "base.fx (N/m)", "base.fy (N/m)",
                                                           "wall.fx (N/m)", "wall.fy (N/m)"});
  int rows = 0;
  while (in.next(line)) {
    const auto cells = split_csv_fields(line);
    CAPTURE(line);
    REQUIRE(cells.size() == 6u);
    CHECK(cells[4].empty() == (rows < 2));  // the wall's cells are empty before it existed
    ++rows;
  }
  CHECK(rows == 5);
  const auto c = read_csv_columns(csv, {"time (s)", "base.fy (N/m)"});
  CHECK(c.columns[0].size() == 5u);
}
