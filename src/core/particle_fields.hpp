// The particle-field table: every named field that Lua (body:field, probe:get), the .vtu files and
// probes.csv show, with its unit and the quantity it is a component of. Everything that lists fields
// (names, parsing, values, the VTU arrays, the CSV columns) is derived from the two tables below, so a
// new field is a row here (plus, for a new quantity, its case in quantity_value and, for a new stored
// member, that member in Particles).
//
// 2D fields, in output order: id body material mass volume density x y ux uy vx vy sxx syy szz sxy
// pressure q shear_strain plastic_strain yield; 3D adds z, uz, vz, syz, sxz. The CSV column of a field
// is "<probe>.<field name>".
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "particles.hpp"

namespace seismpm {

// What a field is a component of: a stored member of Particles or a value derived from them. All but
// the position are written as one VTU point-data array each, in this order (the position is the
// points themselves).
enum class Quantity {
  Position,
  Id,
  Body,
  Material,
  Mass,
  Volume,
  Density,
  Displacement,
  Velocity,
  Stress,
  Strain,
  Pressure,
  Q,
  ShearStrain,
  PlasticStrain,
  Yield
};

struct QuantityInfo {
  Quantity quantity;
  std::string_view name;  // the VTU array's name
  // 1 for a scalar; 3 for a vector (x, y, z; z = 0 in 2D); 6 for a symmetric tensor in VTK's order
  // xx, yy, zz, xy, yz, xz (the order of Sym).
  int components;
  bool integer;    // written as a VTK integer array (ids and flags), else as doubles
  bool vtu_array;  // written as a point-data array
  // SI; in 2D mass and volume are per metre out of plane ("-": dimensionless or a count).
  std::string_view unit;
  std::string_view meaning;
};

// Rows in the order of the enum (checked below).
inline constexpr QuantityInfo kQuantities[] = {
    {Quantity::Position, "position", 3, false, false, "m", "position"},
    {Quantity::Id, "id", 1, true, true, "-", "creation index, stable when particles are reordered"},
    {Quantity::Body, "body", 1, true, true, "-", "body index, in creation order"},
    {Quantity::Material, "material", 1, true, true, "-",
     "material index, in creation order (its name: m:materials(), the .vtu field data material_names)"},
    {Quantity::Mass, "mass", 1, false, true, "kg", "mass"},
    {Quantity::Volume, "volume", 1, false, true, "m^3", "current volume"},
    {Quantity::Density, "density", 1, false, true, "kg/m^3", "mass over current volume"},
    {Quantity::Displacement, "displacement", 3, false, true, "m", "displacement since the end of the gravity phase"},
    {Quantity::Velocity, "velocity", 3, false, true, "m/s", "velocity"},
    {Quantity::Stress, "stress", 6, false, true, "Pa", "Cauchy stress, tension positive; plane strain fills zz"},
    {Quantity::Strain, "strain", 6, false, true, "-", "total strain since the end of the gravity phase"},
    {Quantity::Pressure, "pressure", 1, false, true, "Pa", "mean stress, compression positive"},
    {Quantity::Q, "q", 1, false, true, "Pa", "von Mises equivalent stress sqrt(3 J2)"},
    {Quantity::ShearStrain, "shear_strain", 1, false, true, "-", "equivalent deviatoric strain sqrt(2/3 e:e)"},
    {Quantity::PlasticStrain, "plastic_strain", 1, false, true, "-", "accumulated plastic shear strain"},
    {Quantity::Yield, "yield", 1, true, true, "-", "1 where the last stress update was plastic, else 0"},
};

enum class Field {
  Id,
  Body,
  Material,
  Mass,
  Volume,
  Density,
  X,
  Y,
  Z,
  Ux,
  Uy,
  Uz,
  Vx,
  Vy,
  Vz,
  Sxx,
  Syy,
  Szz,
  Sxy,
  Syz,
  Sxz,
  Pressure,
  Q,
  ShearStrain,
  PlasticStrain,
  Yield
};

struct FieldInfo {
  Field field;
  std::string_view name;  // Lua's name and the CSV column's suffix
  Quantity quantity;
  int component;  // within the quantity (its VTU array)
  int min_dim;    // 3: a field of 3D models only
};

// Rows in the order of the enum (checked below), which is the output order.
inline constexpr FieldInfo kFields[] = {
    {Field::Id, "id", Quantity::Id, 0, 2},
    {Field::Body, "body", Quantity::Body, 0, 2},
    {Field::Material, "material", Quantity::Material, 0, 2},
    {Field::Mass, "mass", Quantity::Mass, 0, 2},
    {Field::Volume, "volume", Quantity::Volume, 0, 2},
    {Field::Density, "density", Quantity::Density, 0, 2},
    {Field::X, "x", Quantity::Position, 0, 2},
    {Field::Y, "y", Quantity::Position, 1, 2},
    {Field::Z, "z", Quantity::Position, 2, 3},
    {Field::Ux, "ux", Quantity::Displacement, 0, 2},
    {Field::Uy, "uy", Quantity::Displacement, 1, 2},
    {Field::Uz, "uz", Quantity::Displacement, 2, 3},
    {Field::Vx, "vx", Quantity::Velocity, 0, 2},
    {Field::Vy, "vy", Quantity::Velocity, 1, 2},
    {Field::Vz, "vz", Quantity::Velocity, 2, 3},
    {Field::Sxx, "sxx", Quantity::Stress, 0, 2},
    {Field::Syy, "syy", Quantity::Stress, 1, 2},
    {Field::Szz, "szz", Quantity::Stress, 2, 2},
    {Field::Sxy, "sxy", Quantity::Stress, 3, 2},
    {Field::Syz, "syz", Quantity::Stress, 4, 3},
    {Field::Sxz, "sxz", Quantity::Stress, 5, 3},
    {Field::Pressure, "pressure", Quantity::Pressure, 0, 2},
    {Field::Q, "q", Quantity::Q, 0, 2},
    {Field::ShearStrain, "shear_strain", Quantity::ShearStrain, 0, 2},
    {Field::PlasticStrain, "plastic_strain", Quantity::PlasticStrain, 0, 2},
    {Field::Yield, "yield", Quantity::Yield, 0, 2},
};

namespace detail {
constexpr bool tables_consistent() {
  for (std::size_t k = 0; k < std::size(kQuantities); ++k)
    if (static_cast<std::size_t>(kQuantities[k].quantity) != k) return false;
  for (std::size_t k = 0; k < std::size(kFields); ++k) {
    const FieldInfo& f = kFields[k];
    if (static_cast<std::size_t>(f.field) != k) return false;
    if (f.component < 0 || f.component >= kQuantities[static_cast<int>(f.quantity)].components) return false;
    if (f.min_dim != 2 && f.min_dim != 3) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::tables_consistent(), "field tables: rows out of enum order or a component out of range");

constexpr const QuantityInfo& quantity_info(Quantity q) { return kQuantities[static_cast<int>(q)]; }
constexpr const FieldInfo& field_info(Field f) { return kFields[static_cast<int>(f)]; }
constexpr std::string_view field_name(Field f) { return field_info(f).name; }
constexpr std::string_view field_unit(Field f) { return quantity_info(field_info(f).quantity).unit; }

// The fields of a Dim-dimensional model, in output order.
std::vector<Field> particle_fields(int dim);
std::optional<Field> parse_field(std::string_view name, int dim);
// Space-separated list of the names, for error messages.
std::string field_names(int dim);

// The quantity's components of particle i into out[0 .. components) (vector components beyond Dim are 0).
template <int Dim>
void quantity_value(const Particles<Dim>& p, std::size_t i, Quantity q, double* out);
template <int Dim>
double field_value(const Particles<Dim>& p, std::size_t i, Field f);

// Mean stress as a pressure (compression positive), von Mises equivalent stress q = sqrt(3 J2), and
// the equivalent deviatoric strain sqrt(2/3 e:e).
double pressure(const Sym& stress);
double von_mises(const Sym& stress);
double equivalent_shear_strain(const Sym& strain);

}  // namespace seismpm
