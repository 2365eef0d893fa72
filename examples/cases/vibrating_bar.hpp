// The vibrating elastic bar (Sulsky, Chen & Schreyer 1994), first axial mode: a bar of length L,
// fixed at x = 0 and free at x = L, starts with v(x, 0) = v0 sin(beta x), beta = pi / (2 L).
// Closed form: v(x, t) = v0 cos(omega t) sin(beta x), omega = beta sqrt(E / rho); the centre of mass
// moves with v_cm(t) = (2 / pi) v0 cos(omega t), period T = 4 L / sqrt(E / rho).
// Plane strain with nu = 0 makes the 2D model a 1D bar.
#pragma once

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "core/model.hpp"
#include "materials/linear_elastic.hpp"

namespace seismpm::cases {

struct VibratingBar {
  double length = 25.0;  // m
  double young = 100.0;  // Pa
  double density = 1.0;  // kg/m^3
  double v0 = 0.1;       // m/s
  int cells = 25;        // cells along the bar
  int ppc = 2;
  ShapeKind shape = ShapeKind::Gimp;
  Scheme scheme = Scheme::Musl;
  double cfl = 0.1;
  Rayleigh rayleigh;  // none by default

  double wave_speed() const { return std::sqrt(young / density); }
  double omega() const { return std::numbers::pi / (2.0 * length) * wave_speed(); }
  double period() const { return 4.0 * length / wave_speed(); }
  double amplitude() const { return 2.0 / std::numbers::pi * v0; }
  double exact_velocity(double t) const { return amplitude() * std::cos(omega() * t); }

  std::unique_ptr<Model<2>> build() const {
    const double h = length / cells;
    ModelSettings<2> s;
    s.lower = Vec<2>(0.0, 0.0);
    s.upper = Vec<2>(length + 4.0 * h, 2.0 * h);
    s.cell = h;
    s.shape = shape;
    s.scheme = scheme;
    s.cfl = cfl;
    auto m = std::make_unique<Model<2>>(s);
    auto material = std::make_shared<LinearElastic>(density, young, 0.0);
    material->set_rayleigh(rayleigh);
    const int mat = m->add_material(material);
    const int body = m->add_body("bar", ppc);
    m->fill_box(body, mat, Vec<2>(0.0, 0.0), Vec<2>(length, h));
    m->grid().fix(Side::Left, FixX);
    auto& p = m->particles();
    const double beta = std::numbers::pi / (2.0 * length);
    for (std::size_t i = 0; i < p.size(); ++i) p.v[i] = Vec<2>(v0 * std::sin(beta * p.x[i][0]), 0.0);
    return m;
  }
};

// Centre-of-mass velocity history and what it says about period and amplitude.
struct BarResult {
  std::vector<double> t, v;  // centre-of-mass x-velocity over time
  double period = 0.0;       // from the first and third zero crossings
  double amplitude = 0.0;    // largest |v_cm| after the start
  std::size_t particles = 0;
};

inline BarResult run_vibrating_bar(const VibratingBar& bar, double periods = 2.0) {
  auto m = bar.build();
  BarResult r;
  r.particles = m->particles().size();
  const double end = periods * bar.period();
  std::vector<double> crossings;
  auto record = [&] {
    const double v = m->momentum()[0] / [&] {
      double s = 0.0;
      for (double mp : m->particles().mass) s += mp;
      return s;
    }();
    if (!r.v.empty() && (r.v.back() > 0.0) != (v > 0.0))  // zero crossing, interpolated
      crossings.push_back(r.t.back() + (m->time() - r.t.back()) * r.v.back() / (r.v.back() - v));
    r.t.push_back(m->time());
    r.v.push_back(v);
    r.amplitude = std::max(r.amplitude, std::abs(v));
  };
  record();
  while (m->time() < end - 1e-12) {
    m->step(end - m->time());
    record();
  }
  if (crossings.size() >= 3) r.period = crossings[2] - crossings[0];
  return r;
}

}  // namespace seismpm::cases
