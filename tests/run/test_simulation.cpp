// The simulation's runs: probes and outputs at the schedule's times, a periodic call that ends a run,
// an interrupt flag that stops one with the model intact, and no run from inside a run.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "materials/linear_elastic.hpp"
#include "run/simulation.hpp"

using namespace seismpm;

namespace {

// A 0.4 m x 0.4 m elastic block falling freely in a 1 m box (nothing else in the run changes its steps).
std::unique_ptr<Simulation<2>> falling_block() {
  ModelSettings<2> s;
  s.cell = 0.05;
  s.gravity = Vec<2>(0.0, -9.81);
  auto sim = std::make_unique<Simulation<2>>(s);
  auto& m = sim->model();
  const int mat = m.add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  m.fill_box(m.add_body("block", 2), mat, Vec<2>(0.3, 0.5), Vec<2>(0.7, 0.9));
  return sim;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

int pvd_entries(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) n += line.find("<DataSet") != std::string::npos;
  return n;
}

}  // namespace

TEST_CASE("simulation: probes and outputs at the schedule's times, and the run's end", "[run][simulation]") {
  const auto dir = (std::filesystem::temp_directory_path() / "seismpm_simulation_outputs").string();
  std::filesystem::remove_all(dir);
  auto sim = falling_block();
  const auto probe = sim->add_probe("top", 0, 0.01);
  OutputSettings out;
  out.dir = dir;
  out.every = 0.05;
  sim->set_output(out);
  CHECK(sim->run(0.12) == RunEnd::Completed);
  CHECK(sim->model().time() == 0.12);
  // Samples at 0, 0.01, ..., 0.12 exactly: k * 0.01, the run's end 0.12 among them.
  std::vector<double> expected;
  for (int k = 0; k <= 12; ++k) expected.push_back(k * 0.01);
  expected.back() = 0.12;
  CHECK(probe->times() == expected);
  CHECK(sim->probe_every(*probe) == 0.01);
  // Files at 0 (the start), 0.05, 0.1 and 0.12 (the end of the run); probes.csv with all samples.
  CHECK(pvd_entries(dir + "/particles.pvd") == 4);
  std::ifstream csv(dir + "/probes.csv");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  CHECK(rows == 1 + 13);
  // m:step-style runs sample at their end but do not write it.
  sim->step(3);
  CHECK(probe->samples() == 14);
  CHECK(pvd_entries(dir + "/particles.pvd") == 4);
  sim->write();
  CHECK(pvd_entries(dir + "/particles.pvd") == 5);
  sim->write();  // on file already
  CHECK(pvd_entries(dir + "/particles.pvd") == 5);
}

TEST_CASE("simulation: a periodic call comes at its times and at the end, and can end the run", "[run][simulation]") {
  auto sim = falling_block();
  std::vector<double> times;
  const RunCall record{0.05, [&] {
                         times.push_back(sim->model().time());
                         CHECK(sim->running());
                         return false;
                       }};
  CHECK(sim->run(0.12, record) == RunEnd::Completed);
  CHECK(times == std::vector<double>{0.05, 0.1, 0.12});
  CHECK_FALSE(sim->running());

  auto stopped = falling_block();
  const RunCall stop{0.02, [&] { return stopped->model().time() > 0.05; }};
  CHECK(stopped->run(1.0, stop) == RunEnd::ByCall);
  CHECK(stopped->model().time() == Approx(0.06).epsilon(1e-12));
  // A call may not run the simulation itself.
  const RunCall nested{0.02, [&] {
                         stopped->run(1.0);
                         return false;
                       }};
  CHECK_THROWS_WITH(stopped->run(0.1, nested), "a run's call may not step the model");
  CHECK_FALSE(stopped->running());
  const double t = stopped->model().time();
  stopped->run(0.01);
  CHECK(stopped->model().time() == Approx(t + 0.01).epsilon(1e-12));
}

TEST_CASE("simulation: an interrupt flag stops a run at a step boundary with the model intact", "[run][simulation]") {
  std::atomic<bool> flag{false};
  auto interrupted = falling_block();
  interrupted->set_interrupt(&flag);
  // Ctrl-C arrives while the run is on (here: during its call at 0.03 s).
  const RunCall press{0.01, [&] {
                        if (interrupted->model().time() > 0.025) flag = true;
                        return false;
                      }};
  try {
    interrupted->run(1.0, press);
    FAIL("the run went on");
  } catch (const RunInterrupted& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("interrupted (Ctrl-C) at t = 0.03 s, step ") &&
                             Catch::EndsWith("; the model is intact"));
  }
  CHECK_FALSE(interrupted->running());
  // The same as a run its call ended at that time, bit for bit; and both go on alike.
  auto ended = falling_block();
  const RunCall end{0.01, [&] { return ended->model().time() > 0.025; }};
  CHECK(ended->run(1.0, end) == RunEnd::ByCall);
  auto& a = interrupted->model();
  auto& b = ended->model();
  CHECK(a.time() == b.time());
  CHECK(a.steps() == b.steps());
  CHECK(same_bits(a.particles().x, b.particles().x));
  flag = false;
  interrupted->run(0.05);
  ended->run(0.05);
  CHECK(a.steps() == b.steps());
  CHECK(same_bits(a.particles().x, b.particles().x));
  CHECK(same_bits(a.particles().v, b.particles().v));
  CHECK(same_bits(a.particles().stress, b.particles().stress));
  // A flag already set stops the next run before its first step.
  flag = true;
  const long steps = a.steps();
  CHECK_THROWS_AS(interrupted->run(0.05), RunInterrupted);
  CHECK(a.steps() == steps);
}

TEST_CASE("simulation: phases name themselves and start their clock", "[run][simulation]") {
  auto sim = falling_block();
  CHECK(sim->phase() == "run");
  sim->run(0.02);
  CHECK(sim->dynamic_phase(0.03, 0.0) == RunEnd::Completed);
  CHECK(sim->phase() == "dynamic");
  CHECK(sim->model().phase_time() == Approx(0.03).epsilon(1e-12));
  CHECK(sim->model().time() == Approx(0.05).epsilon(1e-12));
  CHECK_THROWS_AS(sim->set_damping(1.0), InputError);
  Simulation<2> empty(ModelSettings<2>{});
  CHECK_THROWS_WITH(empty.dynamic_phase(1.0, 0.0), "the model has no particles");
  CHECK_THROWS_WITH(empty.write(), "no output directory yet");
}
