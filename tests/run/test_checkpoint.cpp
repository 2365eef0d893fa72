// Checkpoints: a run restored from one ends bit for bit where the uninterrupted run ends (contact, a
// rigid body following a record, Mohr-Coulomb plasticity, Rayleigh damping, probes, outputs, a gravity
// phase interrupted mid-way), function histories must be given again, the output directory's lists match
// the restored state, and a version 2 file (before Rayleigh damping) is still read.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "io/checkpoint_file.hpp"
#include "materials/mohr_coulomb.hpp"
#include "run/checkpoint.hpp"
#include "run/simulation.hpp"

using namespace seismpm;

namespace {

std::string temp_dir(const char* name) {
  const auto dir = (std::filesystem::temp_directory_path() / name).string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string read_text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A Mohr-Coulomb slope on a rigid base shaken by a tabulated record, in frictional contact, with a fixity,
// two probes and an output directory. `function_base`: the base follows a function history instead.
std::unique_ptr<Simulation<2>> shaken_slope(const std::string& dir, bool function_base = false,
                                            Transfer transfer = Transfer::Flip, const Rayleigh& damping = {}) {
  ModelSettings<2> s;
  s.transfer = transfer;
  s.lower = Vec<2>(-0.2, -0.1);
  s.upper = Vec<2>(1.4, 0.6);
  s.cell = 0.05;
  s.gravity = Vec<2>(0.0, -9.81);
  auto sim = std::make_unique<Simulation<2>>(s);
  auto& m = sim->model();
  MohrCoulombParameters p;
  p.density = 1700;
  p.young = 5e6;
  p.poisson = 0.3;
  p.cohesion = 3000;
  p.friction = 30;
  auto material = std::make_shared<MohrCoulomb>(p);
  material->set_rayleigh(damping);
  const int soil = m.add_material(material, "soil");
  const int body = m.add_body("soil", 2);
  m.fill(body, soil, Vec<2>(0, 0), Vec<2>(1, 0.45), [](const Vec<2>& x) { return x[1] < 0.45 - 0.5 * x[0]; });
  std::array<std::shared_ptr<const History>, 2> v;
  if (function_base)
    v[0] = std::make_shared<FunctionHistory>([](double t) { return 0.2 * t; }, "a function");
  else
    v[0] = std::make_shared<TableHistory>(std::vector<double>{0, 0.1, 0.3, 0.5}, std::vector<double>{0, 0.2, -0.2, 0});
  v[1] = std::make_shared<ConstantHistory>(0.0);
  const int base = m.add_rigid_body("base", 2, 2000, v);
  m.fill_box(base, -1, Vec<2>(-0.15, -0.05), Vec<2>(1.15, 0.0));
  m.add_contact(body, base, 0.5);
  m.grid().fix(Side::Top, FixY);
  const int crest = static_cast<int>(m.particles().size() / 2);
  sim->add_probe("crest", crest, 0.01);
  sim->add_probe("toe", 3, 0.0);
  // Relative probes: the crest against the base's motion and against the toe (their relative
  // displacement and the reference are state a restart must bring back).
  sim->add_probe("crest on base", crest, 0.01, ProbeRelativeTo{ProbeRelativeTo::Kind::Body, base, "body 'base'"});
  sim->add_probe("crest on toe", crest, 0.02, ProbeRelativeTo{ProbeRelativeTo::Kind::Particle, 3, "probe 'toe'"});
  OutputSettings out;
  out.dir = dir;
  out.every = 0.05;
  sim->set_output(out);
  return sim;
}

// A damped Mohr-Coulomb layer 12 m x 6 m on a compliant base shaken by a tabulated outcrop velocity
// (computed in its moving frame), with free-field sides: the edges' recorded reactions, their
// free-field columns and the frame are state a restart must bring back.
std::unique_ptr<Simulation<2>> layer_on_rock(const std::string& dir) {
  ModelSettings<2> s;
  s.upper = Vec<2>(12.0, 6.0);
  s.cell = 1.0;
  s.gravity = Vec<2>(0.0, -9.81);
  auto sim = std::make_unique<Simulation<2>>(s);
  auto& m = sim->model();
  MohrCoulombParameters p;
  p.density = 1800;
  p.young = 5e7;
  p.poisson = 0.3;
  p.cohesion = 5000;
  p.friction = 30;
  auto material = std::make_shared<MohrCoulomb>(p);
  material->set_rayleigh(Rayleigh::from_ratio(0.05, 2.0, 10.0));
  const int soil = m.add_material(material, "soil");
  m.fill(m.add_body("soil", 2), soil, Vec<2>(0, 0), Vec<2>(12, 6),
         [](const Vec<2>& x) { return x[1] < 6.0 - 0.25 * x[0]; });
  BoundarySettings<2> base;
  base.side = Side::Bottom;
  base.kind = BoundaryKind::Compliant;
  base.density = 2400, base.vs = 600, base.vp = 1100;
  base.input[0] = std::make_shared<TableHistory>(std::vector<double>{0, 0.05, 0.15, 0.25, 0.3},
                                                 std::vector<double>{0, 0.3, -0.3, 0.1, 0});
  sim->add_boundary(base);
  for (Side side : {Side::Left, Side::Right}) {
    BoundarySettings<2> b;
    b.side = side;
    b.kind = BoundaryKind::FreeField;
    sim->add_boundary(b);
  }
  sim->add_probe("top", static_cast<int>(m.particles().size()) - 1, 0.01);
  OutputSettings out;
  out.dir = dir;
  out.every = 0.1;
  sim->set_output(out);
  return sim;
}

// Every particle field, and the clock, bit for bit.
void require_same_state(const Simulation<2>& a, const Simulation<2>& b) {
  const auto& pa = a.model().particles();
  const auto& pb = b.model().particles();
  REQUIRE(pa.size() == pb.size());
  REQUIRE(a.model().steps() == b.model().steps());
  CHECK(a.model().time() == b.model().time());
  int member = 0;
  std::vector<int> differing;
  std::vector<std::size_t> sizes_a, sizes_b;
  std::vector<std::string> bytes_a, bytes_b;
  pa.for_each_member(
      [&](const auto& v) { bytes_a.emplace_back(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0])); });
  pb.for_each_member(
      [&](const auto& v) { bytes_b.emplace_back(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0])); });
  REQUIRE(bytes_a.size() == bytes_b.size());
  for (std::size_t k = 0; k < bytes_a.size(); ++k, ++member)
    if (bytes_a[k] != bytes_b[k]) differing.push_back(member);
  CAPTURE(differing);  // the members in Particles::for_each_member's order
  CHECK(differing.empty());
  REQUIRE(a.probes().size() == b.probes().size());
  for (std::size_t k = 0; k < a.probes().size(); ++k) {
    const Probe<2>& pa_ = *a.probes()[k];
    const Probe<2>& pb_ = *b.probes()[k];
    CHECK(pa_.times() == pb_.times());
    for (Field f : particle_fields(2)) CHECK(pa_.series(f) == pb_.series(f));
    // The phase of every sample and its time, and the relative displacement, bit for bit.
    REQUIRE(pa_.samples() == pb_.samples());
    bool same_phases = true;
    for (std::size_t s = 0; s < pa_.samples(); ++s)
      same_phases = same_phases && pa_.phase(s) == pb_.phase(s) && pa_.phase_time(s) == pb_.phase_time(s);
    CHECK(same_phases);
    CHECK(pa_.relative_to().kind == pb_.relative_to().kind);
    CHECK(pa_.relative_to().index == pb_.relative_to().index);
    CHECK(pa_.relative_to().what == pb_.relative_to().what);
    if (pa_.relative_to().active())
      for (int d = 0; d < 2; ++d) CHECK(pa_.relative_series(d) == pb_.relative_series(d));
  }
}

}  // namespace

TEST_CASE("checkpoint: a dynamic phase restored mid-way ends bit for bit as the uninterrupted one",
          "[run][checkpoint]") {
  const std::string dir_a = temp_dir("seismpm_ckpt_a"), dir_b = temp_dir("seismpm_ckpt_b");
  const std::string file = dir_b + "/mid.chk";
  // APIC: the particles' velocity gradients are state the restart must bring back.
  const Transfer transfer = GENERATE(Transfer::Flip, Transfer::Apic);
  CAPTURE(transfer == Transfer::Apic);
  GravityPhaseSettings g;
  g.max_time = 3;
  auto a = shaken_slope(dir_a, false, transfer);
  a->gravity_phase(g);
  a->dynamic_phase(0.3, 0.0, RunCall{0.12, [] { return false; }});  // its call's times are landed on too

  {
    auto b = shaken_slope(dir_b, false, transfer);
    b->gravity_phase(g);
    // The periodic checkpoint once, after the step that lands on the call at t = 0.12 s of the phase; the
    // run goes on (and writes files after the checkpoint that the restore must drop from the lists).
    bool written = false;
    b->set_periodic_checkpoint(file, 0.0, [&] {
      if (written || b->model().phase_time() < 0.12 - 1e-9) return false;
      written = true;
      return true;
    });
    const RunCall call{0.12, [] { return false; }};
    b->dynamic_phase(0.3, 0.0, call);
    REQUIRE(written);
  }
  const CheckpointReader checkpoint(file);
  Simulation<2> c(checkpoint_settings<2>(checkpoint));
  restore_checkpoint(checkpoint, c);
  REQUIRE(c.interrupted_run() == RunKind::Dynamic);
  CHECK(c.phase() == "dynamic");
  CHECK(c.model().phase_time() > 0.119);
  CHECK(c.model().phase_time() < 0.121);
  // The restored directory lists only what was written up to the checkpoint: the uninterrupted run's
  // list holds more.
  const auto entries = [](const std::string& pvd) {
    const std::string text = read_text(pvd);
    int n = 0;
    for (std::size_t at = text.find("<DataSet"); at != std::string::npos; at = text.find("<DataSet", at + 1)) ++n;
    return n;
  };
  CHECK(entries(dir_b + "/particles.pvd") + 3 < entries(dir_a + "/particles.pvd"));
  CHECK(read_text(dir_b + "/probes.csv").size() < read_text(dir_a + "/probes.csv").size());

  SECTION("without its call again, the run refuses to go on") {
    CHECK_THROWS_WITH(c.resume(), Catch::Contains("every 0.12 s"));
  }
  SECTION("finished with its call, it ends where the uninterrupted run ends") {
    const RunCall call{0.12, [] { return false; }};
    const ResumedRun r = c.resume(call);
    CHECK(r.kind == RunKind::Dynamic);
    CHECK(r.how == RunEnd::Completed);
    CHECK_FALSE(c.has_interrupted_run());
    require_same_state(*a, c);
    for (const char* f : {"particles.pvd", "rigid.pvd", "probes.csv", "reactions.csv"})
      CHECK(read_text(dir_a + "/" + f) == read_text(dir_b + "/" + f));
    // And a phase after it, as in the uninterrupted script.
    a->run(0.05);
    c.run(0.05);
    require_same_state(*a, c);
  }
}

namespace {

// The same checkpoint as format version 2 wrote it: no Rayleigh coefficients after each deformable
// material, no damping stress among the particle members (the 9th). Valid only for an undamped model.
std::string as_version_2(const std::string& v3) {
  const auto take = [](const std::string& b, std::size_t& at, std::size_t n) {
    at += n;
    return b.substr(at - n, n);
  };
  const auto u32 = [](const std::string& b, std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return static_cast<std::size_t>(v);
  };
  const auto u64 = [](const std::string& b, std::size_t at) {
    std::uint64_t v;
    std::memcpy(&v, b.data() + at, 8);
    return static_cast<std::size_t>(v);
  };
  std::string out = v3.substr(0, 16);
  out[10] = 2;
  for (std::size_t at = 16; at < v3.size();) {
    const std::string tag = v3.substr(at, 8);
    std::string payload = v3.substr(at + 16, u64(v3, at + 8));
    at += 16 + payload.size() + 4;
    std::string kept;
    std::size_t p = 0;
    if (tag.rfind("MATERIAL", 0) == 0) {
      kept += take(payload, p, 8);
      for (std::size_t k = 0, n = u64(payload, 0); k < n; ++k) {
        kept += take(payload, p, 4 + u32(payload, p));  // name
        const std::string kind = payload.substr(p + 4, u32(payload, p));
        kept += take(payload, p, 4 + kind.size());
        const std::size_t bytes = kind == "linear_elastic" ? 24
                                  : kind == "mohr_coulomb" ? 81
                                  : kind == "rigid"        ? 8
                                                           : 57;
        kept += take(payload, p, bytes);
        if (kind != "rigid") take(payload, p, 16);  // alpha, beta
      }
      payload = kept;
    } else if (tag.rfind("PARTICLE", 0) == 0) {
      kept += take(payload, p, 8);
      for (int member = 0; p < payload.size(); ++member) {
        const std::string v = take(payload, p, 12 + u64(payload, p) * u32(payload, p + 8));
        if (member != 8) kept += v;  // damping_stress
      }
      payload = kept;
    }
    std::string section = tag;
    const std::uint64_t length = payload.size();
    section.append(reinterpret_cast<const char*>(&length), 8);
    section += payload;
    const std::uint32_t crc = crc32(section.data(), section.size());
    section.append(reinterpret_cast<const char*>(&crc), 4);
    out += section;
  }
  return out;
}

}  // namespace

TEST_CASE("checkpoint: a Rayleigh-damped run restored mid-way ends bit for bit, its damping kept",
          "[run][checkpoint][rayleigh]") {
  const std::string dir_a = temp_dir("seismpm_ckpt_ra"), dir_b = temp_dir("seismpm_ckpt_rb");
  const std::string file = dir_b + "/mid.chk";
  const Rayleigh damping = Rayleigh::from_ratio(0.02, 2.0, 20.0);
  auto a = shaken_slope(dir_a, false, Transfer::Flip, damping);
  a->dynamic_phase(0.08, 0.0);
  {
    auto b = shaken_slope(dir_b, false, Transfer::Flip, damping);
    bool written = false;
    b->set_periodic_checkpoint(file, 0.0, [&] {
      if (written || b->model().phase_time() < 0.03) return false;
      return written = true;
    });
    b->dynamic_phase(0.08, 0.0);
    REQUIRE(written);
  }
  const CheckpointReader checkpoint(file);
  CHECK(checkpoint.version() == kCheckpointVersion);
  Simulation<2> c(checkpoint_settings<2>(checkpoint));
  restore_checkpoint(checkpoint, c);
  const Rayleigh& restored = c.model().material(0).rayleigh();
  CHECK(restored.alpha == damping.alpha);
  CHECK(restored.beta == damping.beta);
  double largest = 0.0;  // the viscous stress is state the restart must bring back
  for (const Sym& s : c.model().particles().damping_stress) largest = std::max(largest, s.cwiseAbs().maxCoeff());
  CHECK(largest > 0.0);
  REQUIRE(c.interrupted_run() == RunKind::Dynamic);
  c.resume();
  require_same_state(*a, c);
}

TEST_CASE("checkpoint: edge boundaries restored mid-gravity and mid-shaking end bit for bit",
          "[run][checkpoint][boundary]") {
  const bool in_gravity = GENERATE(false, true);
  CAPTURE(in_gravity);
  const std::string dir_a = temp_dir("seismpm_ckpt_ea"), dir_b = temp_dir("seismpm_ckpt_eb");
  const std::string file = dir_b + "/edges.chk";
  GravityPhaseSettings g;
  g.tolerance = 1e-3;
  auto a = layer_on_rock(dir_a);
  a->gravity_phase(g);
  a->dynamic_phase(0.4, 0.0);
  {
    auto b = layer_on_rock(dir_b);
    bool written = false;
    b->set_periodic_checkpoint(file, 0.0, [&] {
      const bool due = in_gravity ? b->model().steps() == 50 : b->model().phase_time() > 0.2;
      if (written || !due || b->phase() != (in_gravity ? "gravity" : "dynamic")) return false;
      return written = true;
    });
    b->gravity_phase(g);
    b->dynamic_phase(0.4, 0.0);
    REQUIRE(written);
  }
  const CheckpointReader checkpoint(file);
  Simulation<2> c(checkpoint_settings<2>(checkpoint));
  restore_checkpoint(checkpoint, c);
  REQUIRE(c.boundaries().size() == 3);
  CHECK(c.boundaries()[0]->holding() == in_gravity);
  c.resume();
  if (in_gravity) c.dynamic_phase(0.4, 0.0);
  require_same_state(*a, c);
  for (std::size_t k = 0; k < 3; ++k) CHECK(a->boundaries()[k]->last_force() == c.boundaries()[k]->last_force());
}

TEST_CASE("checkpoint: a version 2 file is read as undamped", "[run][checkpoint][rayleigh]") {
  const std::string dir_a = temp_dir("seismpm_ckpt_2a"), dir_b = temp_dir("seismpm_ckpt_2b");
  auto a = shaken_slope(dir_a);
  a->dynamic_phase(0.03, 0.0);
  {
    auto b = shaken_slope(dir_b);
    b->dynamic_phase(0.03, 0.0);
    write_checkpoint(*b, dir_b + "/v3.chk");
  }
  std::ofstream(dir_b + "/v2.chk", std::ios::binary) << as_version_2(read_text(dir_b + "/v3.chk"));
  const CheckpointReader v2(dir_b + "/v2.chk");
  CHECK(v2.version() == 2);
  Simulation<2> c(checkpoint_settings<2>(v2));
  restore_checkpoint(v2, c);
  CHECK_FALSE(c.model().material(0).rayleigh().any());
  require_same_state(*a, c);
  a->dynamic_phase(0.03, 0.0);
  c.dynamic_phase(0.03, 0.0);
  require_same_state(*a, c);
}

TEST_CASE("checkpoint: a gravity phase interrupted mid-way goes on to the same equilibrium and reset",
          "[run][checkpoint]") {
  const std::string dir_a = temp_dir("seismpm_ckpt_ga"), dir_b = temp_dir("seismpm_ckpt_gb");
  const std::string file = dir_b + "/gravity.chk";
  GravityPhaseSettings g;
  g.max_time = 3;
  auto a = shaken_slope(dir_a);
  const GravityPhaseResult ra = a->gravity_phase(g);
  a->dynamic_phase(0.1, 0.0);
  REQUIRE(ra.steps > 40);

  {
    auto b = shaken_slope(dir_b);
    long steps = 0;
    b->set_periodic_checkpoint(file, 0.0, [&] { return ++steps == 30; });  // after the 30th step only
    b->gravity_phase(g);
  }
  const CheckpointReader checkpoint(file);
  Simulation<2> c(checkpoint_settings<2>(checkpoint));
  restore_checkpoint(checkpoint, c);
  REQUIRE(c.interrupted_run() == RunKind::Gravity);
  CHECK(c.model().steps() == 30);
  const ResumedRun r = c.resume();
  REQUIRE(r.gravity);
  CHECK(r.gravity->steps == ra.steps);  // counted from the phase's own start
  CHECK(r.gravity->force_ratio == ra.force_ratio);
  CHECK(r.gravity->energy_ratio == ra.energy_ratio);
  c.dynamic_phase(0.1, 0.0);
  require_same_state(*a, c);
}

TEST_CASE("checkpoint: a checkpoint between phases, restored, and a new phase", "[run][checkpoint]") {
  const std::string dir_a = temp_dir("seismpm_ckpt_pa"), dir_b = temp_dir("seismpm_ckpt_pb");
  const std::string file = dir_b + "/between.chk";
  auto a = shaken_slope(dir_a);
  a->gravity_phase({});
  a->dynamic_phase(0.1, 0.0);
  {
    auto b = shaken_slope(dir_b);
    b->gravity_phase({});
    write_checkpoint(*b, file);
  }
  const CheckpointReader checkpoint(file);
  Simulation<2> c(checkpoint_settings<2>(checkpoint));
  restore_checkpoint(checkpoint, c);
  CHECK_FALSE(c.has_interrupted_run());
  CHECK_THROWS_WITH(c.resume(), Catch::Contains("no interrupted run"));
  // Written again from the restored simulation, the checkpoint is the same file, byte for byte.
  write_checkpoint(c, dir_b + "/again.chk");
  CHECK(read_text(dir_b + "/again.chk") == read_text(file));
  c.dynamic_phase(0.1, 0.0);
  require_same_state(*a, c);
}

TEST_CASE("checkpoint: a function history is named and must be given again", "[run][checkpoint][robustness]") {
  const std::string dir = temp_dir("seismpm_ckpt_fn");
  const std::string file = dir + "/fn.chk";
  {
    auto b = shaken_slope(dir, true);
    write_checkpoint(*b, file);
  }
  const CheckpointReader checkpoint(file);
  {
    Simulation<2> c(checkpoint_settings<2>(checkpoint));
    CHECK_THROWS_WITH(restore_checkpoint(checkpoint, c),
                      Catch::Contains(file) && Catch::Contains("base.vx") && Catch::Contains("give it again"));
  }
  {
    Simulation<2> c(checkpoint_settings<2>(checkpoint));
    CHECK_THROWS_WITH(restore_checkpoint(checkpoint, c,
                                         {{"bse.vx", std::make_shared<ConstantHistory>(1.0)},
                                          {"base.vx", std::make_shared<ConstantHistory>(1.0)}}),
                      Catch::Contains("'bse.vx' names no history") && Catch::Contains("base.vy"));
  }
  Simulation<2> c(checkpoint_settings<2>(checkpoint));
  restore_checkpoint(checkpoint, c, {{"base.vx", std::make_shared<ConstantHistory>(0.25)}});
  CHECK(c.model().rigid_motion(1).velocity[0]->at(3.0) == 0.25);
  CHECK(c.model().rigid_motion(1).velocity[1]->at(3.0) == 0.0);  // the saved constant
}

TEST_CASE("checkpoint: a particle half-width not above 0 or over 0.5 cells is refused",
          "[run][checkpoint][robustness]") {
  const std::string dir = temp_dir("seismpm_ckpt_half_width");
  for (const double bad : {0.0, -0.25, 0.75, std::numeric_limits<double>::quiet_NaN()}) {
    CAPTURE(bad);
    const std::string file = dir + "/half_width.chk";
    {
      auto b = shaken_slope(dir);
      b->model().particles().half_width[5] = bad;
      write_checkpoint(*b, file);
    }
    const CheckpointReader checkpoint(file);
    Simulation<2> c(checkpoint_settings<2>(checkpoint));
    CHECK_THROWS_WITH(restore_checkpoint(checkpoint, c),
                      Catch::Contains(file) && Catch::Contains("half-width") && Catch::Contains("(0, 0.5]"));
  }
  // The written half-widths themselves (1 / (2 ppc)) are read back.
  const std::string file = dir + "/good.chk";
  {
    auto b = shaken_slope(dir);
    write_checkpoint(*b, file);
  }
  const CheckpointReader checkpoint(file);
  Simulation<2> c(checkpoint_settings<2>(checkpoint));
  restore_checkpoint(checkpoint, c);
  CHECK(c.model().particles().half_width[5] == 0.25);
}
