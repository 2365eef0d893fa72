// The plots' gnuplot scripts (key outside the curves, margins, units, the time axis of the shaking,
// reference curves, an SVG beside each PNG) and, with gnuplot, the pictures they draw.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/csv_plot.hpp"
#include "io/gnuplot.hpp"
#include "io/phases_file.hpp"
#include "io/probe_plot.hpp"
#include "lua/lua_fixture.hpp"
#include "support/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace seismpm;
using Catch::Contains;

using seismpm::test::fresh_dir;

namespace {

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A probes.csv of two probes, sampled during a gravity phase (0 to 0.2 s) and the shaking after it.
std::string probes_dir(const std::string& name) {
  const std::string dir = fresh_dir(name);
  write(dir + "/probes.csv",
        "time (s),crest.ux,crest.uy,toe.ux,toe.uy\n0,0,0,0,0\n0.1,0,-0.001,0,0\n0.2,0,-0.002,0,0\n"
        "0.3,0.01,-0.002,0.02,0\n0.4,0.02,-0.003,0.03,0\n");
  return dir;
}

}  // namespace

TEST_CASE("every picture is drawn as a PNG and an SVG beside it, in the report style", "[io][plot]") {
  CHECK(svg_path("out/a/probe_ux.png") == "out/a/probe_ux.svg");
  CHECK(svg_path("out/picture") == "out/picture.svg");
  const std::string script = picture_script("plot 'a.csv' using 1:2\n", "out/a.png");
  CHECK(contains(script, "set terminal pngcairo size 960,540"));
  CHECK(contains(script, "set output 'out/a.png.tmp'"));
  CHECK(contains(script, "set terminal svg size 960,540"));
  CHECK(contains(script, "set output 'out/a.svg.tmp'"));
  CHECK(script.find("set terminal svg") > script.find("plot 'a.csv'"));  // the same plot, drawn again
  CHECK(contains(script, "replot"));
  // The key (legend) outside the plotting area, never over the curves; margins above and below them.
  CHECK(contains(script, "set key outside below"));
  CHECK(contains(script, "set offsets graph 0, graph 0, graph 0.08, graph 0.08"));
  CHECK_FALSE(contains(script, "set key top left"));
}

TEST_CASE("a CSV plot of one curve has no key; reference columns are dashed black curves", "[io][plot]") {
  const std::string dir = fresh_dir("csv_plot_script");
  write(dir + "/table_velocity.csv", "t,value\n0,0\n0.5,0.15\n1,-0.15\n");
  CsvPlot p;
  p.csv = dir + "/table_velocity.csv";
  p.png = dir + "/table_velocity.png";
  p.x = "t";
  p.y = {"value"};
  p.xlabel = "time since the dynamic phase began (s)";
  p.ylabel = "table velocity vx (m/s)";
  std::string body = csv_plot_body(p);
  CHECK(contains(body, "set key off"));  // no meaningless "value" entry
  CHECK(contains(body, "using 1:2 with lines lw 2 notitle"));
  CHECK_FALSE(contains(body, "title 'value'"));
  CHECK(contains(body, "set xlabel 'time since the dynamic phase began (s)'"));
  CHECK(contains(body, "set ylabel 'table velocity vx (m/s)'"));

  write(dir + "/motion.csv", "# a comment\ntime (s),ux (m),closed form (m)\n0,0,0\n1,1.4,1.5\n");
  p.csv = dir + "/motion.csv";
  p.x = "time (s)";
  p.y = {"ux (m)"};
  p.reference = {"closed form (m)"};
  body = csv_plot_body(p);
  CHECK_FALSE(contains(body, "set key off"));
  CHECK(contains(body, "using 1:2 with lines lw 2 title 'ux (m)'"));
  CHECK(contains(body, "using 1:3 with lines lw 2 dt 2 lc rgb 'black' title 'closed form (m)'"));
  CHECK_FALSE(contains(body, "set logscale x"));
  p.log_x = true;  // a response spectrum's periods
  CHECK(contains(csv_plot_body(p), "set logscale x\n"));
  p.reference = {"exact (m)"};
  CHECK_THROWS_WITH(csv_plot_body(p), Contains("no column 'exact (m)'"));
}

TEST_CASE("phases.csv: each phase with its start; a phase that begins again replaces what came after", "[io][plot]") {
  const std::string dir = fresh_dir("phases_file");
  CHECK(read_phases(dir).empty());
  record_phase(dir, "run", 0.0);
  record_phase(dir, "gravity", 0.0);  // began at the same time: the run before it took no time
  record_phase(dir, "gravity", 0.0);  // already on file
  record_phase(dir, "dynamic", 0.25);
  record_phase(dir, "dynamic", 0.25 + 1e-15);  // the same start, up to rounding
  auto phases = read_phases(dir);
  REQUIRE(phases.size() == 2);
  CHECK(phases[0].phase == "gravity");
  CHECK(phases[0].start == 0.0);
  CHECK(phases[1].phase == "dynamic");
  CHECK(phases[1].start == 0.25);
  CHECK(shaking_start(phases) == 0.25);
  record_phase(dir, "gravity", 0.0);  // a restart from a checkpoint in the gravity phase
  phases = read_phases(dir);
  REQUIRE(phases.size() == 1);
  CHECK(std::isnan(shaking_start(phases)));
  write(dir + "/phases.csv", "phase,start (s)\ngravity,zero\n");
  CHECK_THROWS_WITH(read_phases(dir), Contains("phases.csv:2:"));
}

TEST_CASE("probe plots: time since the dynamic phase began, earlier phases shaded, units, a reference curve",
          "[io][plot]") {
  const std::string dir = probes_dir("probe_plot_script");
  SECTION("without phases.csv: the model time") {
    const std::string body = probe_plot_body(dir, "ux");
    CHECK(contains(body, "set xlabel 'time (s)'"));
    CHECK(contains(body, "using 1:2 with lines lw 2 title 'crest'"));
    CHECK(contains(body, "using 1:4 with lines lw 2 title 'toe'"));
    CHECK(contains(body, "set ylabel 'Horizontal displacement ux (m)'"));
  }
  SECTION("after a dynamic phase: its time, the gravity phase at negative times") {
    write(dir + "/phases.csv", "phase,start (s)\ngravity,0\ndynamic,0.2\n");
    const std::string body = probe_plot_body(dir, "uy");
    // The shaded phase is named on the axis, not over the curves of the phase after it.
    CHECK(contains(body, "set xlabel 'time since the dynamic phase began (s); shaded: gravity phase'"));
    CHECK(contains(body, "using ($1 - 0.2):3 with lines lw 2 title 'crest'"));
    CHECK(contains(body, "set object 1 rectangle from first -0.2, graph 0 to first 0, graph 1 behind"));
    CHECK_FALSE(contains(body, "set label 'gravity phase'"));
    CHECK(contains(body, "set ylabel 'Vertical displacement uy (m)'"));
  }
  SECTION("a closed form drawn with the quantity it belongs to, not with the others") {
    write(dir + "/phases.csv", "phase,start (s)\ngravity,0\ndynamic,0.2\n");
    write(dir + "/closed_form.csv", "t (s),centroid ux (m)\n0,0\n0.2,0.02\n");
    const std::vector<ProbeReference> refs{{"ux", dir + "/closed_form.csv", "t (s)", "centroid ux (m)", "closed form"}};
    const std::string ux = probe_plot_body(dir, "ux", refs);
    CHECK(contains(ux, "closed_form.csv' every ::1 using 1:2 with lines lw 2 dt 2 lc rgb 'black' title 'closed form'"));
    CHECK_FALSE(contains(probe_plot_body(dir, "uy", refs), "closed_form.csv"));
    const std::vector<ProbeReference> wrong{{"ux", dir + "/closed_form.csv", "t (s)", "exact (m)", ""}};
    CHECK_THROWS_WITH(probe_plot_body(dir, "ux", wrong), Contains("no column 'exact (m)'"));
  }
  SECTION("stresses in Pa, with what they are") {
    write(dir + "/probes.csv", "time (s),crest.syy\n0,0\n1,-1000\n");
    CHECK(contains(probe_plot_body(dir, "syy"), "set ylabel 'Normal stress syy (Pa)'"));
  }
}

namespace {

// The points gnuplot draws for a plot body: (x, y) of each curve's points, in order (gnuplot's `set
// table`), so that a test sees which rows a plot keeps.
std::vector<std::pair<double, double>> drawn_points(const std::string& dir, const std::string& body) {
  const std::string script = dir + "/table.gp", table = dir + "/table.txt";
  write(script, "set datafile separator ','\nset table '" + table + "'\n" + body + "unset table\n");
  fs::remove(table);
  REQUIRE(std::system(("gnuplot '" + script + "' 2>/dev/null").c_str()) == 0);
  std::ifstream in(table);
  std::vector<std::pair<double, double>> points;
  for (std::string line; std::getline(in, line);) {
    std::istringstream row(line);
    double x, y;
    if (line.empty() || line[0] == '#' || !(row >> x >> y)) continue;
    points.emplace_back(x, y);
  }
  return points;
}

// probes.csv with the phase columns: a gravity phase (0 to 0.2 s) and two dynamic phases after it.
std::string phase_probes_dir(const std::string& name) {
  const std::string dir = fresh_dir(name);
  write(dir + "/probes.csv",
        "time (s),phase,phase_time (s),crest.ux,crest.uy\n"
        "0,gravity,0,0,0\n0.1,gravity,0.1,0,-0.001\n0.2,gravity,0.2,0,-0.002\n"
        "0.3,dynamic,0.1,0.01,-0.002\n0.4,dynamic,0.2,0.02,-0.003\n"
        "0.45,dynamic,0.05,0.03,-0.003\n0.5,dynamic,0.1,0.04,-0.004\n");
  write(dir + "/phases.csv", "phase,start (s)\ngravity,0\ndynamic,0.2\ndynamic,0.4\n");
  return dir;
}

}  // namespace

TEST_CASE("probe plots keep one phase's rows, on its own clock or the model time", "[io][plot][phases]") {
  const std::string dir = phase_probes_dir("probe_plot_phase");
  using Points = std::vector<std::pair<double, double>>;
  SECTION("the current phase on its own clock: the second dynamic phase's rows only") {
    ProbePlotOptions o;
    o.x = "phase_time";  // without a phase: the current one
    const std::string body = probe_plot_body(dir, "ux", {}, o);
    CHECK(contains(body, "set xlabel 'time since the dynamic phase began (s)'"));
    CHECK(contains(body, "dynamic phase'"));    // in the title
    CHECK_FALSE(contains(body, "set object"));  // no shading of other phases
    CHECK(drawn_points(dir, body) == Points{{0.05, 0.03}, {0.1, 0.04}});
    o.phase = "current";
    CHECK(drawn_points(dir, probe_plot_body(dir, "ux", {}, o)) == Points{{0.05, 0.03}, {0.1, 0.04}});
  }
  SECTION("a phase by name: its last run; x auto is then its own clock, x time the model time") {
    ProbePlotOptions o;
    o.phase = "gravity";
    CHECK(drawn_points(dir, probe_plot_body(dir, "uy", {}, o)) == Points{{0, 0}, {0.1, -0.001}, {0.2, -0.002}});
    o.phase = "dynamic";
    o.x = "time";
    const std::string body = probe_plot_body(dir, "ux", {}, o);
    CHECK(contains(body, "set xlabel 'model time (s)'"));
    CHECK(drawn_points(dir, body) == Points{{0.45, 0.03}, {0.5, 0.04}});
  }
  SECTION("every row by default: the shaking's time from the first dynamic phase, as before") {
    const auto points = drawn_points(dir, probe_plot_body(dir, "ux"));
    REQUIRE(points.size() == 7);
    CHECK(points.front().first == Approx(-0.2));
    CHECK(points.back().first == Approx(0.3));
  }
  SECTION("a phase the run did not have, an unknown axis, a probes.csv without phase columns") {
    ProbePlotOptions o;
    o.phase = "run";
    CHECK_THROWS_WITH(probe_plot_body(dir, "ux", {}, o),
                      Contains("phase 'run': the run had no such phase") && Contains("gravity, dynamic, dynamic"));
    o.phase = "";
    o.x = "shaking";
    CHECK_THROWS_WITH(probe_plot_body(dir, "ux", {}, o), Contains("x 'shaking'"));
    write(dir + "/probes.csv", "time (s),crest.ux\n0,0\n1,1\n");
    o.x = "phase_time";
    CHECK_THROWS_WITH(probe_plot_body(dir, "ux", {}, o), Contains("no columns 'phase' and 'phase_time (s)'"));
    o.x = "auto";
    CHECK_NOTHROW(probe_plot_body(dir, "ux", {}, o));  // an older file still plots on the default axis
  }
}

TEST_CASE("a run's plots: PNG and SVG written, phases on file, the closed form in the picture", "[io][plot][lua]") {
  const std::string dir = fresh_dir("plot_run");
  test::LuaFixture f;
  const std::string error = f.error_of("local dir = '" + dir + "'" + R"lua(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
    b = m:body{ material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
    m:fix{ side = "bottom" }
    m:probe{ name = "crest", body = b, at = {0.5, 0.5}, every = 0.01 }
    m:output{ dir = dir, every = 0.1 }
    m:gravity_phase{ damping = 0.7, tolerance = 0.01, max_time = 2 }
    m:dynamic_phase{ duration = 0.2 }
    local f = assert(io.open(dir .. "/closed.csv", "w"))
    f:write("t (s),exact uy (m)\n0,0\n0.2,-0.001\n")
    f:close()
    pngs = m:plot{ quantities = {"ux", "uy"}, reference = { quantity = "uy", file = dir .. "/closed.csv",
                                                            x = "t (s)", y = "exact uy (m)"
}
}
    csv = mpm.plot{ file = dir .. "/closed.csv", x = "t (s)", y = {"exact uy (m)"}, xlabel = "t (s)" }
  )lua");
  REQUIRE(error == "");
  const auto phases = read_phases(dir);
  REQUIRE(phases.size() == 2);
  CHECK(phases[0].phase == "gravity");
  CHECK(phases[1].phase == "dynamic");
  CHECK(phases[1].start > 0.0);
  for (const char* name : {"probe_ux", "probe_uy", "closed"}) {
    const std::string png = dir + "/" + name + ".png", svg = dir + "/" + name + ".svg";
    REQUIRE(fs::exists(png));
    REQUIRE(fs::exists(svg));
    CHECK(fs::file_size(png) > 5000);
    const std::string text = read(svg);
    CHECK(contains(text, "<svg"));
    CHECK(contains(text, "</svg>"));
    CHECK_FALSE(fs::exists(png + ".tmp"));
    CHECK_FALSE(fs::exists(svg + ".tmp"));
  }
  const std::string uy = read(dir + "/probe_uy.svg");
  CHECK(contains(uy, "time since the dynamic phase began (s)"));
  CHECK(contains(uy, "gravity phase"));
  CHECK(contains(uy, "exact uy (m)"));  // the reference curve's key entry
  CHECK_FALSE(contains(read(dir + "/probe_ux.svg"), "exact uy (m)"));
  CHECK_THAT(f.error_of("m:plot{ quantities = {'ux'}, reference = { quantity = 'uy', file = '" + dir +
                        "/closed.csv', x = 't (s)', y = 'exact uy (m)' } }"),
             Contains("not among the quantities plotted"));
}
