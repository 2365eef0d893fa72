#include "particle_fields.hpp"

#include <cmath>

namespace seismpm {

namespace {
constexpr std::string_view kNames[] = {"id",  "body", "material", "mass", "volume", "density", "x",   "y",
                                       "z",   "ux",   "uy",       "uz",   "vx",     "vy",      "vz",  "sxx",
                                       "syy", "szz",  "sxy",      "syz",  "sxz",    "pressure", "q", "shear_strain",
                                       "plastic_strain", "yield"};

bool in_dim(Field f, int dim) {
  if (dim == 3) return true;
  return f != Field::Z && f != Field::Uz && f != Field::Vz && f != Field::Syz && f != Field::Sxz;
}

// Deviatoric part's double contraction s:s of a symmetric tensor (Voigt, tensor shear).
double dev_norm2(const Sym& a) {
  const double m = (a[0] + a[1] + a[2]) / 3.0;
  const double dx = a[0] - m, dy = a[1] - m, dz = a[2] - m;
  return dx * dx + dy * dy + dz * dz + 2.0 * (a[3] * a[3] + a[4] * a[4] + a[5] * a[5]);
}
}  // namespace

std::vector<Field> particle_fields(int dim) {
  std::vector<Field> out;
  for (int k = 0; k <= static_cast<int>(Field::Yield); ++k)
    if (in_dim(static_cast<Field>(k), dim)) out.push_back(static_cast<Field>(k));
  return out;
}

std::string_view field_name(Field f) { return kNames[static_cast<int>(f)]; }

std::optional<Field> parse_field(std::string_view name, int dim) {
  for (Field f : particle_fields(dim))
    if (field_name(f) == name) return f;
  return std::nullopt;
}

std::string field_names(int dim) {
  std::string s;
  for (Field f : particle_fields(dim)) s += (s.empty() ? "" : " ") + std::string(field_name(f));
  return s;
}

double pressure(const Sym& s) { return -(s[0] + s[1] + s[2]) / 3.0; }
double von_mises(const Sym& s) { return std::sqrt(1.5 * dev_norm2(s)); }
double equivalent_shear_strain(const Sym& e) { return std::sqrt(2.0 / 3.0 * dev_norm2(e)); }

template <int Dim>
double field_value(const Particles<Dim>& p, std::size_t i, Field f) {
  auto comp = [](const auto& v, int d) { return d < Dim ? v[d] : 0.0; };
  switch (f) {
    case Field::Id: return p.id[i];
    case Field::Body: return p.body[i];
    case Field::Material: return p.material[i];
    case Field::Mass: return p.mass[i];
    case Field::Volume: return p.volume[i];
    case Field::Density: return p.density(i);
    case Field::X: return comp(p.x[i], 0);
    case Field::Y: return comp(p.x[i], 1);
    case Field::Z: return comp(p.x[i], 2);
    case Field::Ux: return comp(p.u[i], 0);
    case Field::Uy: return comp(p.u[i], 1);
    case Field::Uz: return comp(p.u[i], 2);
    case Field::Vx: return comp(p.v[i], 0);
    case Field::Vy: return comp(p.v[i], 1);
    case Field::Vz: return comp(p.v[i], 2);
    case Field::Sxx: return p.stress[i][0];
    case Field::Syy: return p.stress[i][1];
    case Field::Szz: return p.stress[i][2];
    case Field::Sxy: return p.stress[i][3];
    case Field::Syz: return p.stress[i][4];
    case Field::Sxz: return p.stress[i][5];
    case Field::Pressure: return pressure(p.stress[i]);
    case Field::Q: return von_mises(p.stress[i]);
    case Field::ShearStrain: return equivalent_shear_strain(p.strain[i]);
    case Field::PlasticStrain: return p.plastic_strain[i];
    case Field::Yield: return p.yield[i];
  }
  return 0.0;
}

template double field_value<2>(const Particles<2>&, std::size_t, Field);
template double field_value<3>(const Particles<3>&, std::size_t, Field);

}  // namespace seismpm
