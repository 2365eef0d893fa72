// Outputs that give the engineering answer: probes.csv carries each row's phase and the time since that
// phase began; the .vtu files carry the phase and its time; a probe relative to another probe or a body
// records its displacement less the reference's (ux_rel, uy_rel), consistent with ux across the gravity
// phase's reset; the probe plots keep one phase's rows and put them on its own clock.
#include <catch2/catch.hpp>

#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "io/csv_table.hpp"
#include "io/phases_file.hpp"
#include "lua/lua_fixture.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace seismpm;
using Catch::Contains;

using seismpm::test::fresh_dir;

namespace {

std::vector<std::vector<std::string>> csv_rows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(split_csv_fields(line));
  return rows;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  REQUIRE(it != header.end());
  return static_cast<std::size_t>(it - header.begin());
}

// The displacement of a rigid body from rest under vx = table{ {0, 0}, {0.1, 0.5}, {0.2, 0.5} }.
double table_displacement(double t) { return t <= 0.1 ? 2.5 * t * t : 0.025 + 0.5 * (t - 0.1); }

}  // namespace

TEST_CASE("probes.csv: each row's phase and phase_time = time - the phase's start; the .vtu files carry both",
          "[io][probes][phases]") {
  const std::string dir = fresh_dir("probe_phases");
  test::LuaFixture f;
  const std::string error = f.error_of("local dir = '" + dir + "'" + R"lua(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    local mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
    local b = m:body{ material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
    m:fix{ side = "bottom" }
    m:probe{ name = "crest", body = b, at = {0.5, 0.5}, every = 0.01 }
    m:output{ dir = dir, every = 0.1 }
    m:run{ duration = 0.05 }
    m:gravity_phase{ damping = 0.7, tolerance = 0.01, max_time = 2 }
    gravity_end = m:time()
    m:dynamic_phase{ duration = 0.2 }
    t_end = m:time()
  )lua");
  REQUIRE(error == "");
  const double gravity_end = f.number("gravity_end"), t_end = f.number("t_end");
  REQUIRE(gravity_end > 0.05);
  const auto rows = csv_rows(dir + "/probes.csv");
  REQUIRE(rows.size() > 10);
  const auto& header = rows[0];
  REQUIRE(header.size() > 3);
  CHECK(header[0] == "time (s)");
  CHECK(header[1] == "phase");
  CHECK(header[2] == "phase_time (s)");
  CHECK(header[3] == "crest.id");  // the probes' columns as before, after the phase columns
  const std::map<std::string, double> start{{"run", 0.0}, {"gravity", 0.05}, {"dynamic", gravity_end}};
  std::map<std::string, int> count;
  std::string previous = "run";
  for (std::size_t r = 1; r < rows.size(); ++r) {
    CAPTURE(r, rows[r][0], rows[r][1], rows[r][2]);
    const double t = std::stod(rows[r][0]), phase_time = std::stod(rows[r][2]);
    const std::string& phase = rows[r][1];
    REQUIRE(start.count(phase) == 1);
    CHECK(phase_time == Approx(t - start.at(phase)).margin(1e-9));
    CHECK(phase_time >= -1e-12);
    CHECK(start.at(phase) >= start.at(previous));  // phases in order
    previous = phase;
    ++count[phase];
  }
  CHECK(count["run"] == 6);  // 0, 0.01, ..., 0.05
  CHECK(count["gravity"] > 2);
  // Samples at multiples of 0.01 s of model time and at the run's end: 20 or 21 in 0.2 s of shaking.
  CHECK(count["dynamic"] >= 20);
  CHECK(count["dynamic"] <= 21);
  // The gravity phase's end is its own row (sampled before the displacements' reset); the last row is
  // 0.2 s into the dynamic phase.
  const auto at_gravity_end = std::find_if(rows.begin() + 1, rows.end(), [&](const auto& row) {
    return std::abs(std::stod(row[0]) - gravity_end) < 1e-9;
  });  // 10 digits
  REQUIRE(at_gravity_end != rows.end());
  CHECK((*at_gravity_end)[1] == "gravity");
  CHECK(rows.back()[1] == "dynamic");
  CHECK(std::stod(rows.back()[2]) == Approx(0.2).margin(1e-9));
  CHECK(std::stod(rows.back()[0]) == Approx(t_end).margin(1e-9));
  // The numeric columns still read as before (mpm.history.csv, read_csv_columns skip the text column).
  const auto c = read_csv_columns(dir + "/probes.csv", {"time (s)", "phase_time (s)", "crest.uy"});
  CHECK(c.columns[0].size() == rows.size() - 1);

  // The last .vtu: the model time, and the phase with its own time as field data.
  const std::string last = dir + "/particles_" + [&] {
    int n = 0;
    while (fs::exists(dir + "/particles_" + std::string(6 - std::to_string(n + 1).size(), '0') + std::to_string(n + 1) +
                      ".vtu"))
      ++n;
    std::string s = std::to_string(n);
    return std::string(6 - s.size(), '0') + s;
  }() + ".vtu";
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(last.c_str());
  reader->Update();
  vtkFieldData* fd = reader->GetOutput()->GetFieldData();
  REQUIRE(fd->GetArray("TimeValue") != nullptr);
  REQUIRE(fd->GetArray("phase_time") != nullptr);
  CHECK(fd->GetArray("TimeValue")->GetTuple1(0) == Approx(t_end));
  CHECK(fd->GetArray("phase_time")->GetTuple1(0) == Approx(0.2));
  auto* phase = vtkStringArray::SafeDownCast(fd->GetAbstractArray("phase"));
  REQUIRE(phase != nullptr);
  CHECK(phase->GetValue(0) == "dynamic");
}

TEST_CASE("relative probes: zero on a rigidly moving body, minus the displacement of a rigid body's history",
          "[io][probes][relative]") {
  const std::string dir = fresh_dir("probe_relative");
  test::LuaFixture f;
  const std::string error = f.error_of("local dir = '" + dir + "'" + R"lua(
    m = mpm.model{ domain = {{0, 0}, {2, 1}}, cell = 0.1, gravity = {0, 0} }
    local mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
    -- A block at rest, far from the base (no node in common): no force, no motion.
    local block = m:body{ name = "block", material = mat, shape = mpm.shape.rectangle{ 1.4, 0.5, 1.8, 0.9 } }
    local vx = mpm.history.table{ {0, 0}, {0.1, 0.5}, {0.2, 0.5} }
    base = m:rigid{ name = "base", shape = mpm.shape.rectangle{ 0.1, 0.1, 0.6, 0.2 }, velocity = {vx, 0} }
    a = m:probe{ name = "a", body = base, at = {0.15, 0.15} }
    b = m:probe{ name = "b", body = base, at = {0.55, 0.15}, relative_to = a }
    c = m:probe{ name = "c", body = block, at = {1.6, 0.7}, relative_to = base }
    m:output{ dir = dir, every = 0.05 }
    m:dynamic_phase{ duration = 0.2 }
    b_ux, b_ux_rel, c_ux, c_ux_rel, c_uy_rel = b:get("ux"), b:get("ux_rel"), c:get("ux"), c:get("ux_rel"), c:get("uy_rel")
    local t, rel = b:series("ux_rel")
    local _, ux = b:series("ux")
    b_rel_worst, b_moved = 0, 0
    for k = 1, #t do
      b_rel_worst = math.max(b_rel_worst, math.abs(rel[k]))
      b_moved = math.max(b_moved, math.abs(ux[k]))
    end
    c_t, c_rel = c:series("ux_rel")
    description = tostring(c)
  )lua");
  REQUIRE(error == "");
  // Two points of one rigidly moving body: each moves, their relative displacement is zero throughout.
  CHECK(f.number("b_ux") == Approx(table_displacement(0.2)).epsilon(1e-9));
  CHECK(f.number("b_moved") > 0.07);
  CHECK(f.number("b_ux_rel") == 0.0);
  CHECK(f.number("b_rel_worst") == 0.0);
  // A point at rest relative to the moving base: minus the base's displacement, the history's integral.
  CHECK(f.number("c_ux") == 0.0);
  CHECK(f.number("c_ux_rel") == Approx(-table_displacement(0.2)).epsilon(1e-9));
  CHECK(f.number("c_uy_rel") == 0.0);
  lua_State* L = f.runtime.state();
  lua_getglobal(L, "c_t");
  lua_getglobal(L, "c_rel");
  const int n = static_cast<int>(lua_rawlen(L, -2));
  REQUIRE(n == 21);  // 0, 0.01, ..., 0.2
  for (int k = 1; k <= n; ++k) {
    lua_rawgeti(L, -2, k);
    lua_rawgeti(L, -2, k);
    const double t = lua_tonumber(L, -2), rel = lua_tonumber(L, -1);
    lua_pop(L, 2);
    CAPTURE(t);
    CHECK(rel == Approx(-table_displacement(t)).margin(1e-9));
  }
  lua_pop(L, 2);
  lua_getglobal(L, "description");
  const std::string description = lua_tostring(L, -1) ? lua_tostring(L, -1) : "";
  lua_pop(L, 1);
  CHECK_THAT(description, Contains("relative to body 'base'"));
  // probes.csv: the relative columns after each relative probe's fields, the same values.
  const auto rows = csv_rows(dir + "/probes.csv");
  CHECK(column(rows[0], "b.ux_rel") == column(rows[0], "b.yield") + 1);  // after b's fields, before c's
  CHECK(column(rows[0], "c.id") == column(rows[0], "b.uy_rel") + 1);
  CHECK(column(rows[0], "b.uy_rel") == column(rows[0], "b.ux_rel") + 1);
  CHECK(std::find(rows[0].begin(), rows[0].end(), "a.ux_rel") == rows[0].end());  // a has no reference
  const auto c = read_csv_columns(dir + "/probes.csv", {"time (s)", "c.ux_rel", "b.ux_rel", "b.ux"});
  REQUIRE(c.columns[0].size() == 21);
  for (std::size_t k = 0; k < c.columns[0].size(); ++k) {
    CAPTURE(k);
    CHECK(c.columns[1][k] == Approx(-table_displacement(c.columns[0][k])).margin(1e-9));
    CHECK(c.columns[2][k] == 0.0);
  }
  CHECK(c.columns[3].back() > 0.07);
}

TEST_CASE("relative probes: relative to a body's centroid, reset with ux at the gravity phase's end",
          "[io][probes][relative]") {
  test::LuaFixture f;
  const std::string error = f.error_of(R"lua(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    local mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
    local soil = m:body{ name = "soil", material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
    m:fix{ side = "bottom" }
    top = m:probe{ name = "top", body = soil, at = {0.5, 0.5}, relative_to = soil }
    m:gravity_phase{ damping = 0.7, tolerance = 0.01, max_time = 2 }
    local _, rel = top:series("uy_rel")
    settled_rel = rel[#rel]          -- the last gravity sample, before the reset
    after_reset = top:get("uy_rel")  -- like uy: zero after the reset
    after_reset_uy = top:get("uy")
    m:dynamic_phase{ duration = 0.05 }
    -- The reference is the mass-weighted mean displacement of the body's particles.
    local mass, uy = soil:field("mass"), soil:field("uy")
    local sum, total = 0, 0
    for i = 1, #mass do sum, total = sum + mass[i] * uy[i], total + mass[i] end
    expected = top:get("uy") - sum / total
    got = top:get("uy_rel")
  )lua");
  REQUIRE(error == "");
  CHECK(f.number("settled_rel") < -1e-5);  // the top settles more than the centroid
  CHECK(f.number("after_reset") == 0.0);
  CHECK(f.number("after_reset_uy") == 0.0);
  CHECK(f.number("got") == Approx(f.number("expected")).margin(1e-15));
  CHECK(std::abs(f.number("got")) < 0.1 * std::abs(f.number("settled_rel")));  // measured from the reset
}

TEST_CASE(
    "relative probes: a reference of another model, of the wrong type or collected is an error naming "
    "relative_to; ux_rel needs a reference",
    "[lua][probes][relative][robustness]") {
  test::LuaFixture f;
  REQUIRE(f.error_of(R"lua(
    local function model()
      local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
      local mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
      return m, m:body{ name = "soil", material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
    end
    m, soil = model()
    other, other_soil = model()
    p = m:probe{ name = "p", body = soil, at = {0.5, 0.5} }
    q = other:probe{ name = "q", body = other_soil, at = {0.5, 0.5} }
  )lua") == "");
  CHECK_THAT(f.error_of("m:probe{ body = soil, at = {0.5, 0.2}, relative_to = q }"),
             Contains("key 'relative_to' belongs to another model"));
  CHECK_THAT(f.error_of("m:probe{ body = soil, at = {0.5, 0.2}, relative_to = other_soil }"),
             Contains("key 'relative_to' belongs to another model"));
  CHECK_THAT(f.error_of("m:probe{ body = soil, at = {0.5, 0.2}, relative_to = 3 }"),
             Contains("key 'relative_to' must be a probe or a body, got number"));
  CHECK_THAT(f.error_of("local x = m:probe{ body = soil, at = {0.1, 0.1} }; getmetatable(x).__gc(x); "
                        "m:probe{ body = soil, at = {0.5, 0.2}, relative_to = x }"),
             Contains("key 'relative_to': probe used after it was collected"));
  CHECK_THAT(f.error_of("m:probe{ body = soil, at = {0.5, 0.2}, relative_to = {} }"), Contains("relative_to"));
  CHECK_THAT(f.error_of("print(p:get('ux_rel'))"), Contains("probe 'p' has no reference"));
  CHECK_THAT(f.error_of("print(p:series('uy_rel'))"), Contains("probe 'p' has no reference"));
  CHECK(f.error_of("r = m:probe{ name = 'r', body = soil, at = {0.5, 0.2}, relative_to = p }; "
                   "assert(r:get('ux_rel') == 0 and #select(2, r:series('uy_rel')) == 1)") == "");
}

TEST_CASE("m:plot keeps one phase's rows on its own clock; bad x or phase values name their key",
          "[io][plot][probes][lua]") {
  const std::string dir = fresh_dir("plot_phase_rows");
  test::LuaFixture f;
  const std::string error = f.error_of("local dir = '" + dir + "'" + R"lua(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    local mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
    local b = m:body{ material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
    m:fix{ side = "bottom" }
    local base = m:probe{ name = "base", body = b, at = {0.5, 0.0}, every = 0.01 }
    m:probe{ name = "crest", body = b, at = {0.5, 0.5}, every = 0.01, relative_to = base }
    m:output{ dir = dir, every = 0.1 }
    m:gravity_phase{ damping = 0.7, tolerance = 0.01, max_time = 2 }
    m:dynamic_phase{ duration = 0.1 }
    pngs = m:plot{ quantities = {"uy", "uy_rel"}, x = "phase_time", phase = "dynamic" }
  )lua");
  REQUIRE(error == "");
  std::ifstream in(dir + "/probe_uy_rel.svg");
  std::stringstream svg;
  svg << in.rdbuf();
  CHECK_THAT(svg.str(), Contains("time since the dynamic phase began (s)"));
  CHECK_THAT(svg.str(), Contains("relative to the reference"));
  CHECK_THAT(f.error_of("m:plot{ x = 'shaking' }"), Contains("'x' must be one of auto|time|phase_time"));
  CHECK_THAT(f.error_of("m:plot{ phase = 'shaking' }"), Contains("'phase' must be one of current|run|gravity|dynamic"));
  CHECK_THAT(f.error_of("m:plot{ quantities = {'ux_relative'} }"), Contains("key 'quantities'"));
  // A phase the run did not have.
  CHECK_THAT(f.error_of("m:plot{ phase = 'run' }"), Contains("phase 'run': the run had no such phase"));
}
