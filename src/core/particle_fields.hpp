// Named particle fields, shared by Lua (body:field, probe:get), VTU and CSV output
// (DESIGN.md §3): id body material mass volume density x y ux uy vx vy sxx syy szz sxy
// pressure q shear_strain plastic_strain yield (3D adds z, uz, vz, syz, sxz).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "particles.hpp"

namespace seismpm {

enum class Field {
  Id, Body, Material, Mass, Volume, Density,
  X, Y, Z, Ux, Uy, Uz, Vx, Vy, Vz,
  Sxx, Syy, Szz, Sxy, Syz, Sxz,
  Pressure, Q, ShearStrain, PlasticStrain, Yield
};

// The fields of a Dim-dimensional model, in output order.
std::vector<Field> particle_fields(int dim);
std::string_view field_name(Field f);
std::optional<Field> parse_field(std::string_view name, int dim);
// Comma-separated list of the names, for error messages.
std::string field_names(int dim);

template <int Dim>
double field_value(const Particles<Dim>& p, std::size_t i, Field f);

// Mean stress as a pressure (compression positive), von Mises equivalent stress q = sqrt(3 J2), and
// the equivalent deviatoric strain sqrt(2/3 e:e).
double pressure(const Sym& stress);
double von_mises(const Sym& stress);
double equivalent_shear_strain(const Sym& strain);

}  // namespace seismpm
