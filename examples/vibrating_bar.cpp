// Verification example 1: the vibrating elastic bar against its closed form.
// Prints period and amplitude errors for a grid refinement and writes the history as CSV.
//   vibrating_bar [--out DIR]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "cases/vibrating_bar.hpp"

int main(int argc, char** argv) {
  std::string out = "out/vibrating_bar";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
      out = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s [--out DIR]\n", argv[0]);
      return 2;
    }
  }
  seismpm::cases::VibratingBar bar;
  std::printf("seismpm: vibrating elastic bar (Sulsky et al. 1994), first mode, uGIMP, MUSL, FLIP\n");
  std::printf("  L = %g m, E = %g Pa, rho = %g kg/m3, v0 = %g m/s\n", bar.length, bar.young, bar.density, bar.v0);
  std::printf("  exact: period %.5f s, centre-of-mass velocity amplitude %.6f m/s\n\n", bar.period(), bar.amplitude());
  std::printf("  %6s %10s %12s %10s %12s %10s %9s\n", "cells", "particles", "period (s)", "error", "amplitude", "error",
              "wall (s)");
  seismpm::cases::BarResult finest;
  for (int cells : {13, 25, 50, 100}) {
    bar.cells = cells;
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = seismpm::cases::run_vibrating_bar(bar);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("  %6d %10zu %12.5f %9.3f%% %12.6f %9.3f%% %9.2f\n", cells, r.particles, r.period,
                100.0 * (r.period - bar.period()) / bar.period(), r.amplitude,
                100.0 * (r.amplitude - bar.amplitude()) / bar.amplitude(), wall);
    if (cells == 25) finest = r;
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  const std::string file = out + "/centre_of_mass_velocity.csv";
  std::ofstream csv(file);
  if (!csv) {
    std::fprintf(stderr, "seismpm: cannot write %s\n", file.c_str());
    return 1;
  }
  csv << "time (s),v_cm (m/s),v_cm exact (m/s)\n";
  for (std::size_t k = 0; k < finest.t.size(); ++k)
    csv << finest.t[k] << ',' << finest.v[k] << ',' << bar.exact_velocity(finest.t[k]) << '\n';
  std::printf("\n  history at 25 cells written to %s\n", file.c_str());
  return 0;
}
