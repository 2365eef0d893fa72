#include "particle_fields.hpp"

#include <cmath>

namespace seismpm {

namespace {
// Deviatoric part's double contraction s:s of a symmetric tensor (Voigt, tensor shear).
double dev_norm2(const Sym& a) {
  const double m = (a[0] + a[1] + a[2]) / 3.0;
  const double dx = a[0] - m, dy = a[1] - m, dz = a[2] - m;
  return dx * dx + dy * dy + dz * dz + 2.0 * (a[3] * a[3] + a[4] * a[4] + a[5] * a[5]);
}

// A Dim-vector as 3 components, zero beyond Dim (the VTU vectors are 3D in 2D too).
template <int Dim>
void vector3(const Vec<Dim>& v, double* out) {
  for (int d = 0; d < 3; ++d) out[d] = d < Dim ? v[d] : 0.0;
}

void tensor6(const Sym& s, double* out) {
  for (int c = 0; c < 6; ++c) out[c] = s[c];
}
}  // namespace

std::vector<Field> particle_fields(int dim) {
  std::vector<Field> out;
  for (const FieldInfo& f : kFields)
    if (f.min_dim <= dim) out.push_back(f.field);
  return out;
}

std::optional<Field> parse_field(std::string_view name, int dim) {
  for (const FieldInfo& f : kFields)
    if (f.min_dim <= dim && f.name == name) return f.field;
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

// The one place that says how each quantity is read (no default: a new Quantity without its case
// here is a -Wswitch warning).
template <int Dim>
void quantity_value(const Particles<Dim>& p, std::size_t i, Quantity q, double* out) {
  switch (q) {
    case Quantity::Position:
      return vector3<Dim>(p.x[i], out);
    case Quantity::Id:
      out[0] = p.id[i];
      return;
    case Quantity::Body:
      out[0] = p.body[i];
      return;
    case Quantity::Material:
      out[0] = p.material[i];
      return;
    case Quantity::Mass:
      out[0] = p.mass[i];
      return;
    case Quantity::Volume:
      out[0] = p.volume[i];
      return;
    case Quantity::Density:
      out[0] = p.density(i);
      return;
    case Quantity::Displacement:
      return vector3<Dim>(p.u[i], out);
    case Quantity::Velocity:
      return vector3<Dim>(p.v[i], out);
    case Quantity::Stress:
      return tensor6(p.stress[i], out);
    case Quantity::Strain:
      return tensor6(p.strain[i], out);
    case Quantity::Pressure:
      out[0] = pressure(p.stress[i]);
      return;
    case Quantity::Q:
      out[0] = von_mises(p.stress[i]);
      return;
    case Quantity::ShearStrain:
      out[0] = equivalent_shear_strain(p.strain[i]);
      return;
    case Quantity::PlasticStrain:
      out[0] = p.plastic_strain[i];
      return;
    case Quantity::Yield:
      out[0] = p.yield[i];
      return;
  }
}

template <int Dim>
double field_value(const Particles<Dim>& p, std::size_t i, Field f) {
  const FieldInfo& info = field_info(f);
  double value[6];
  quantity_value(p, i, info.quantity, value);
  return value[info.component];
}

template void quantity_value<2>(const Particles<2>&, std::size_t, Quantity, double*);
template void quantity_value<3>(const Particles<3>&, std::size_t, Quantity, double*);
template double field_value<2>(const Particles<2>&, std::size_t, Field);
template double field_value<3>(const Particles<3>&, std::size_t, Field);

}  // namespace seismpm
