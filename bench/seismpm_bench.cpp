// Step-loop benchmark: particle-steps per second (particles x steps / wall seconds) for a 2D
// elastic block settling under gravity on a fixed base, MUSL, FLIP.
//   seismpm_bench [--steps N] [--repeat R] [--threads "1 2"] [--sizes "25000 100000"] [--digest]
// Each case runs R times (after warm-up steps); the median is printed, one line per case. --digest
// adds a hash of the first run's final particle state (positions, velocities, stresses, by creation
// index), so that two binaries' results can be compared bit for bit.
#include <omp.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cases/moving_base_block.hpp"
#include "cases/shaking_table.hpp"
#include "core/model.hpp"
#include "materials/linear_elastic.hpp"
#include "materials/mohr_coulomb.hpp"

using namespace seismpm;

namespace {

std::vector<int> parse_list(const char* text) {
  std::vector<int> out;
  std::istringstream is(text);
  for (int v; is >> v;) out.push_back(v);
  return out;
}

// A square block of about `particles` particles (2 x 2 per cell) on a fixed base.
std::unique_ptr<Model<2>> block(int particles, ShapeKind shape) {
  const int side = static_cast<int>(std::round(std::sqrt(particles / 4.0)));  // cells per side
  const double h = 1.0 / side;
  ModelSettings<2> s;
  s.lower = Vec<2>(-2 * h, 0.0);
  s.upper = Vec<2>(1.0 + 2 * h, 1.0 + 4 * h);
  s.cell = h;
  s.shape = shape;
  s.scheme = Scheme::Musl;
  s.gravity = Vec<2>(0.0, -9.81);
  auto m = std::make_unique<Model<2>>(s);
  const int mat = m->add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  const int body = m->add_body("block", 2);
  m->fill_box(body, mat, Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0));
  m->grid().fix(Side::Bottom, FixX | FixY);
  return m;
}

// Dry sand column collapse (Bui et al. 2008): 0.2 m wide, 0.1 m high, against a smooth left wall on a
// rough floor; density 2650, E 0.84 MPa, nu 0.3, phi 19.8, c 0; 2.5 mm cells, 2 x 2 particles per cell.
std::unique_ptr<Model<2>> sand_column(bool profile) {
  ModelSettings<2> s;
  s.profile = profile;
  s.lower = Vec<2>(0.0, 0.0);
  s.upper = Vec<2>(0.5, 0.12);
  s.cell = 0.0025;
  s.shape = ShapeKind::Gimp;
  s.gravity = Vec<2>(0.0, -9.81);
  auto m = std::make_unique<Model<2>>(s);
  MohrCoulombParameters p;
  p.density = 2650, p.young = 0.84e6, p.poisson = 0.3;
  p.cohesion = 0.0, p.friction = 19.8, p.dilation = 0.0, p.tension = 0.0;
  const int mat = m->add_material(std::make_shared<MohrCoulomb>(p));
  const int body = m->add_body("sand", 2);
  m->fill_box(body, mat, Vec<2>(0.0, 0.0), Vec<2>(0.2, 0.1));
  m->grid().fix(Side::Left, FixX);
  m->grid().fix(Side::Bottom, FixX | FixY);
  return m;
}

struct Options {
  int steps = 100, repeat = 5;
  bool profile = false, digest = false;
  std::vector<int> threads = {1, 2}, sizes = {25000, 100000};
  std::vector<std::string> cases = {"linear", "gimp", "mc-sand", "contact", "glued", "no-base", "shaking-table"};
  std::string baseline, save;
  bool wants(const std::string& c) const { return std::find(cases.begin(), cases.end(), c) != cases.end(); }
};

// One measured median: "case particles threads" identifies it across binaries.
struct Figure {
  std::string name;
  std::size_t particles;
  int threads;
  double rate;  // particle-steps per second
};
std::vector<Figure> figures;

void record(const std::string& name, std::size_t particles, int threads, double rate) {
  figures.push_back({name, particles, threads, rate});
}

// FNV-1a over the bits of the particles' positions, velocities and stresses in creation order: equal
// digests mean (all but surely) bit-identical states.
std::uint64_t state_digest(const Model<2>& m) {
  const Particles<2>& p = m.particles();
  std::vector<int> by_id(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) by_id[p.id[i]] = static_cast<int>(i);
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](const double* v, int n) {
    for (int k = 0; k < n; ++k) {
      const auto bits = std::bit_cast<std::uint64_t>(v[k]);
      for (int b = 0; b < 8; ++b) h = (h ^ ((bits >> (8 * b)) & 0xff)) * 1099511628211ull;
    }
  };
  for (int i : by_id) {
    mix(p.x[i].data(), 2);
    mix(p.v[i].data(), 2);
    mix(p.stress[i].data(), static_cast<int>(p.stress[i].size()));
  }
  return h;
}
std::string last_digest;  // of the latest median_rate's first run, with --digest

// Median particle-steps per second over `repeat` models from `make`, each timed over `steps` steps
// after 5 warm-up steps (first touches, first sort); `after(model, r)` looks at each one.
template <class Make, class After>
double median_rate(const Options& o, Make&& make, After&& after, int warm_up = 5) {
  std::vector<double> rates;
  for (int r = 0; r < o.repeat; ++r) {
    auto holder = make();
    Model<2>& m = holder.model();
    const std::size_t particles = m.particles().size();
    for (int k = 0; k < warm_up; ++k) m.step();
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < o.steps; ++k) m.step();  // throws on a NaN
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rates.push_back(particles * o.steps / wall);
    if (o.digest && r == 0) {
      char text[32];
      std::snprintf(text, sizeof text, "  digest %016llx", static_cast<unsigned long long>(state_digest(m)));
      last_digest = text;
    }
    after(m, r);
  }
  std::sort(rates.begin(), rates.end());
  return rates[rates.size() / 2];
}

// A model owned by a unique_ptr, or by a case's build, behind one accessor.
struct OwnedModel {
  std::unique_ptr<Model<2>> m;
  Model<2>& model() { return *m; }
};
// A case's build (its simulation owns the model).
template <class Built>
struct CaseModel {
  Built b;
  Model<2>& model() { return *b.model; }
};

void print_stages(const Options& o, const Model<2>& m, int warm_up = 5) {
  for (const auto& [stage, seconds] : m.stage_times())
    std::printf("    %-20s %8.3f ms/step\n", stage, 1e3 * seconds / (o.steps + warm_up));
}

void print_line(const std::string& name, std::size_t particles, int threads, double rate, const std::string& extra) {
  std::printf("%-14s %-10zu %8d %10.3f %14.3fM   %s%s\n", name.c_str(), particles, threads, 1e3 * particles / rate,
              rate / 1e6, extra.c_str(), last_digest.c_str());
  last_digest.clear();
  std::fflush(stdout);
  record(name, particles, threads, rate);
}

std::size_t yielding_count(const Model<2>& m) {
  std::size_t n = 0;
  for (auto y : m.particles().yield) n += y;
  return n;
}

void bench_blocks(const Options& o) {
  std::printf("%-14s %-10s %8s %10s %14s\n", "case", "particles", "threads", "ms/step", "particle-steps/s");
  std::printf("2D elastic block under gravity, MUSL, FLIP\n");
  for (ShapeKind shape : {ShapeKind::Linear, ShapeKind::Gimp}) {
    const std::string name(to_string(shape));
    if (!o.wants(name)) continue;
    for (int n : o.sizes)
      for (int t : o.threads) {
        omp_set_num_threads(t);
        std::size_t particles = 0;
        const double rate = median_rate(
            o, [&] { return OwnedModel{block(n, shape)}; },
            [&](const Model<2>& m, int) { particles = m.particles().size(); });
        print_line(name, particles, t, rate, "");
      }
  }
}

// Mohr-Coulomb column collapse: the first `steps` steps of the release, where most particles yield.
void bench_sand_column(const Options& o) {
  if (!o.wants("mc-sand")) return;
  std::printf("Mohr-Coulomb sand column collapse (c = 0), uGIMP, MUSL\n");
  for (int t : o.threads) {
    omp_set_num_threads(t);
    std::size_t particles = 0, yielding = 0;
    const double rate = median_rate(
        o, [&] { return OwnedModel{sand_column(o.profile)}; },
        [&](const Model<2>& m, int r) {
          particles = m.particles().size();
          yielding = yielding_count(m);
          if (o.profile && r == 0) print_stages(o, m);
        });
    print_line("mc-sand", particles, t, rate, "(" + std::to_string(yielding) + " particles yielding, no NaN)");
  }
}

// The moving-base block at a fine resolution: the cost of the contact fields.
void bench_moving_base(const Options& o) {
  struct Variant {
    const char* name;
    bool base;
    cases::BaseContact contact;
  };
  bool header = false;
  for (const Variant& v :
       {Variant{"contact", true, cases::BaseContact::Friction}, Variant{"glued", true, cases::BaseContact::None},
        Variant{"no-base", false, cases::BaseContact::None}}) {
    if (!o.wants(v.name)) continue;
    if (!header)
      std::printf("Moving base under an elastic block (1 m x 1 m, 1 cm cells, uGIMP), base sliding at 2 m/s\n");
    header = true;
    for (int t : o.threads) {
      omp_set_num_threads(t);
      std::size_t particles = 0, shared = 0;
      auto make = [&] {
        cases::MovingBaseBlock c;
        c.cell = 0.01;
        c.contact = v.contact;
        c.with_base = v.base;
        c.profile = o.profile;
        CaseModel<cases::MovingBaseBlock::Built> built{c.build()};
        if (v.base)
          built.model().set_rigid_velocity(
              built.b.base, {std::make_shared<ConstantHistory>(2.0), std::make_shared<ConstantHistory>(0.0)});
        return built;
      };
      const double rate = median_rate(o, make, [&](const Model<2>& m, int r) {
        particles = m.particles().size();
        shared = m.contact().nodes().count();
        if (o.profile && r == 0) print_stages(o, m);
      });
      print_line(v.name, particles, t, rate, "(" + std::to_string(shared) + " shared nodes)");
    }
  }
}

// The shaking-table slope as the scenario runs it (Mohr-Coulomb soil in a rigid box with contact,
// 0.75 cm cells), timed after 300 steps of strong shaking from K0 stresses have made it yield.
void bench_shaking_table(const Options& o) {
  if (!o.wants("shaking-table")) return;
  constexpr int kWarmUp = 300;
  std::printf("Shaking-table slope (MC soil, rigid box, contact, uGIMP, FLIP 0.98, 0.75 cm), after %d steps\n",
              kWarmUp);
  for (int t : o.threads) {
    omp_set_num_threads(t);
    std::size_t particles = 0, yielding = 0;
    const double rate = median_rate(
        o,
        [&] {
          cases::ShakingTable c;
          c.profile = o.profile;
          return CaseModel<cases::ShakingTable::Built>{c.build()};
        },
        [&](const Model<2>& m, int r) {
          particles = m.particles().size();
          yielding = yielding_count(m);
          if (o.profile && r == 0) print_stages(o, m, kWarmUp);
        },
        kWarmUp);
    print_line("shaking-table", particles, t, rate, "(" + std::to_string(yielding) + " particles yielding)");
  }
}

std::string key(const std::string& name, std::size_t particles, int threads) {
  return name + " " + std::to_string(particles) + " " + std::to_string(threads);
}

// "case particles threads rate" lines, as --save writes them; '#' starts a comment.
std::map<std::string, double> read_baseline(const std::string& file) {
  std::map<std::string, double> out;
  std::ifstream in(file);
  if (!in) {
    std::fprintf(stderr, "seismpm_bench: cannot read the baseline %s\n", file.c_str());
    return out;
  }
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream is(line);
    std::string name;
    std::size_t particles;
    int threads;
    double rate;
    if (is >> name >> particles >> threads >> rate) out[key(name, particles, threads)] = rate;
  }
  return out;
}

void report_baseline(const Options& o) {
  if (!o.save.empty()) {
    std::ofstream out(o.save);
    out << "# seismpm_bench medians: case particles threads particle-steps/s\n";
    for (const Figure& f : figures) out << f.name << ' ' << f.particles << ' ' << f.threads << ' ' << f.rate << '\n';
  }
  if (o.baseline.empty()) return;
  const auto base = read_baseline(o.baseline);
  std::printf("ratio to %s:", o.baseline.c_str());
  for (const Figure& f : figures) {
    const auto it = base.find(key(f.name, f.particles, f.threads));
    if (it == base.end())
      std::printf("  %s/%zu/%dt -", f.name.c_str(), f.particles, f.threads);
    else
      std::printf("  %s/%zu/%dt %.2fx", f.name.c_str(), f.particles, f.threads, f.rate / it->second);
  }
  std::printf("\n");
}

std::vector<std::string> parse_words(const char* text) {
  std::vector<std::string> out;
  std::istringstream is(text);
  for (std::string w; is >> w;) out.push_back(w);
  return out;
}

bool parse_options(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--steps") && has_value) {
      o.steps = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--repeat") && has_value) {
      o.repeat = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--threads") && has_value) {
      o.threads = parse_list(argv[++i]);
    } else if (!std::strcmp(argv[i], "--digest")) {
      o.digest = true;
    } else if (!std::strcmp(argv[i], "--profile")) {
      o.profile = true;
    } else if (!std::strcmp(argv[i], "--sizes") && has_value) {
      o.sizes = parse_list(argv[++i]);
    } else if (!std::strcmp(argv[i], "--cases") && has_value) {
      o.cases = parse_words(argv[++i]);
    } else if (!std::strcmp(argv[i], "--baseline") && has_value) {
      o.baseline = argv[++i];
    } else if (!std::strcmp(argv[i], "--save") && has_value) {
      o.save = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: %s [--steps N] [--repeat R] [--threads \"1 2\"] [--sizes \"25000 100000\"]\n"
                   "          [--cases \"linear gimp mc-sand contact glued no-base shaking-table\"] [--profile]\n"
                   "          [--baseline FILE] [--save FILE]\n",
                   argv[0]);
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse_options(argc, argv, o)) return 2;
  std::printf("seismpm_bench: median of %d runs of %d steps per case\n", o.repeat, o.steps);
  bench_blocks(o);
  bench_sand_column(o);
  bench_moving_base(o);
  bench_shaking_table(o);
  report_baseline(o);
  return 0;
}
