// The particle-field table: names and their parsing, the derived quantities (pressure, von Mises q,
// equivalent shear strain) on tensors worked out by hand, the values of a hand-made particle, and the
// mapping of fields onto the VTU arrays and their components.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/particle_fields.hpp"
#include "io/vtu_writer.hpp"

using namespace seismpm;

namespace {
Sym sym(double xx, double yy, double zz, double xy, double yz, double xz) {
  Sym s;
  s << xx, yy, zz, xy, yz, xz;
  return s;
}
}  // namespace

TEST_CASE("field names: the 2D and 3D lists in output order", "[core][fields]") {
  CHECK(field_names(2) ==
        "id body material mass volume density x y ux uy vx vy sxx syy szz sxy pressure q shear_strain "
        "plastic_strain yield");
  CHECK(field_names(3) ==
        "id body material mass volume density x y z ux uy uz vx vy vz sxx syy szz sxy syz sxz pressure q "
        "shear_strain plastic_strain yield");
  CHECK(particle_fields(2).size() == 21);
  CHECK(particle_fields(3).size() == 26);
}

TEST_CASE("every field name parses back to its field", "[core][fields]") {
  const int dim = GENERATE(2, 3);
  for (Field f : particle_fields(dim)) {
    INFO(field_name(f));
    const auto parsed = parse_field(field_name(f), dim);
    REQUIRE(parsed);
    CHECK(*parsed == f);
  }
}

TEST_CASE("unknown names and 3D-only fields in 2D do not parse", "[core][fields]") {
  const std::string name = GENERATE(as<std::string>{}, "z", "uz", "vz", "syz", "sxz");
  CHECK_FALSE(parse_field(name, 2));
  CHECK(parse_field(name, 3));
  CHECK_FALSE(parse_field("speed", 3));
  CHECK_FALSE(parse_field("UX", 2));  // names are case-sensitive
  CHECK_FALSE(parse_field("", 2));
}

TEST_CASE("each field has the unit of its quantity", "[core][fields]") {
  CHECK(field_unit(Field::Uy) == "m");
  CHECK(field_unit(Field::Z) == "m");
  CHECK(field_unit(Field::Vx) == "m/s");
  CHECK(field_unit(Field::Sxy) == "Pa");
  CHECK(field_unit(Field::Pressure) == "Pa");
  CHECK(field_unit(Field::Density) == "kg/m^3");
  CHECK(field_unit(Field::ShearStrain) == "-");
}

TEST_CASE("pressure is the mean stress, compression positive", "[core][fields]") {
  // -(-100 - 200 - 300) / 3 = 200; shear does not count.
  CHECK(pressure(sym(-100, -200, -300, 10, 20, 30)) == 200.0);
  CHECK(pressure(sym(30, 0, 0, 0, 0, 0)) == -10.0);
}

TEST_CASE("von Mises q = sqrt(3 J2) on known tensors", "[core][fields]") {
  SECTION("uniaxial: q is the axial stress's magnitude") {
    // s = (-300, 0, 0): deviator (-200, 100, 100), s:s = 60000, q = sqrt(1.5 * 60000) = 300.
    CHECK(von_mises(sym(-300, 0, 0, 0, 0, 0)) == Approx(300.0).epsilon(1e-15));
  }
  SECTION("pure shear: q = sqrt(3) tau") {
    const int component = GENERATE(3, 4, 5);  // xy, yz, xz alike
    Sym s = Sym::Zero();
    s[component] = 50.0;
    CHECK(von_mises(s) == Approx(std::sqrt(3.0) * 50.0).epsilon(1e-15));
  }
  SECTION("hydrostatic: q = 0") { CHECK(von_mises(sym(-7, -7, -7, 0, 0, 0)) == 0.0); }
  SECTION("general: J2 = ((10-20)^2 + (20-30)^2 + (30-10)^2) / 6 + 4^2 + 5^2 + 6^2 = 177") {
    CHECK(von_mises(sym(10, 20, 30, 4, 5, 6)) == Approx(std::sqrt(3.0 * 177.0)).epsilon(1e-14));
  }
}

TEST_CASE("equivalent shear strain sqrt(2/3 e:e)", "[core][fields]") {
  SECTION("pure shear: tensor shear e_xy = gamma / 2 gives gamma / sqrt(3)") {
    // e:e = 2 e_xy^2 = 2 * 0.003^2, sqrt(2/3 * 2 * 0.003^2) = 0.006 / sqrt(3).
    CHECK(equivalent_shear_strain(sym(0, 0, 0, 0.003, 0, 0)) == Approx(0.006 / std::sqrt(3.0)).epsilon(1e-14));
  }
  SECTION("uniaxial strain eps: deviator (2, -1, -1) eps / 3 gives 2 eps / 3") {
    CHECK(equivalent_shear_strain(sym(0.03, 0, 0, 0, 0, 0)) == Approx(0.02).epsilon(1e-14));
  }
  SECTION("volumetric strain has none") {
    // 0.25 each: the mean 0.75 / 3 is exact, so the deviator is exactly zero.
    CHECK(equivalent_shear_strain(sym(0.25, 0.25, 0.25, 0, 0, 0)) == 0.0);
  }
}

TEST_CASE("field values of a hand-made 2D particle", "[core][fields]") {
  Particles<2> p;
  p.add(Vec<2>(0.0, 0.0), 1.0, 1.0, 0.25, 0, 0);
  const std::size_t i = p.add(Vec<2>(1.5, -2.0), 8.0, 4.0, 0.25, 3, 1);
  p.u[i] = Vec<2>(0.1, -0.2);
  p.v[i] = Vec<2>(3.0, 4.0);
  p.stress[i] = sym(-100, -200, -300, 10, 0, 0);
  p.strain[i] = sym(0, 0, 0, 0.003, 0, 0);
  p.plastic_strain[i] = 0.05;
  p.yield[i] = 1;
  auto value = [&](Field f) { return field_value(p, i, f); };
  CHECK(value(Field::Id) == 1.0);
  CHECK(value(Field::Body) == 3.0);
  CHECK(value(Field::Material) == 1.0);
  CHECK(value(Field::Mass) == 8.0);
  CHECK(value(Field::Volume) == 4.0);
  CHECK(value(Field::Density) == 2.0);  // 8 kg / 4 m^3
  CHECK(value(Field::X) == 1.5);
  CHECK(value(Field::Y) == -2.0);
  CHECK(value(Field::Z) == 0.0);  // not a 2D field, but zero when asked
  CHECK(value(Field::Ux) == 0.1);
  CHECK(value(Field::Uy) == -0.2);
  CHECK(value(Field::Vx) == 3.0);
  CHECK(value(Field::Vy) == 4.0);
  CHECK(value(Field::Sxx) == -100.0);
  CHECK(value(Field::Syy) == -200.0);
  CHECK(value(Field::Szz) == -300.0);
  CHECK(value(Field::Sxy) == 10.0);
  CHECK(value(Field::Pressure) == 200.0);
  // Deviator (100, 0, -100) and shear 10: s:s = 20000 + 2 * 100, q = sqrt(1.5 * 20200) = sqrt(30300).
  CHECK(value(Field::Q) == Approx(std::sqrt(30300.0)).epsilon(1e-15));
  CHECK(value(Field::ShearStrain) == Approx(0.006 / std::sqrt(3.0)).epsilon(1e-14));
  CHECK(value(Field::PlasticStrain) == 0.05);
  CHECK(value(Field::Yield) == 1.0);
}

TEST_CASE("field values of a hand-made 3D particle", "[core][fields]") {
  Particles<3> p;
  const std::size_t i = p.add(Vec<3>(1.0, 2.0, 5.0), 1.0, 1.0, 0.25, 0, 0);
  p.u[i] = Vec<3>(0.0, 0.0, -0.5);
  p.v[i] = Vec<3>(0.0, 0.0, 2.0);
  p.stress[i] = sym(1, 2, 3, 4, 5, 6);
  CHECK(field_value(p, i, Field::Z) == 5.0);
  CHECK(field_value(p, i, Field::Uz) == -0.5);
  CHECK(field_value(p, i, Field::Vz) == 2.0);
  CHECK(field_value(p, i, Field::Sxy) == 4.0);
  CHECK(field_value(p, i, Field::Syz) == 5.0);
  CHECK(field_value(p, i, Field::Sxz) == 6.0);
}

TEST_CASE("the VTU arrays: names, components and order", "[core][fields][vtu]") {
  // These are the .vtu files' point-data arrays, byte for byte: a change here changes every file.
  std::string names, components;
  for (VtuArray a : all_vtu_arrays()) {
    names += std::string(names.empty() ? "" : " ") + std::string(quantity_info(a).name);
    components += std::to_string(quantity_info(a).components);
  }
  CHECK(names ==
        "id body material mass volume density displacement velocity stress strain pressure q shear_strain "
        "plastic_strain yield");
  CHECK(components == "111111336611111");
  CHECK(quantity_info(Quantity::Id).integer);
  CHECK(quantity_info(Quantity::Yield).integer);
  CHECK_FALSE(quantity_info(Quantity::Mass).integer);
}

TEST_CASE("a field names its VTU array and component", "[core][fields][vtu]") {
  // Vectors x, y, z; tensors in VTK's order xx, yy, zz, xy, yz, xz.
  struct Case {
    const char* name;
    Quantity array;
    int component;
  };
  const Case c =
      GENERATE(Case{"ux", Quantity::Displacement, 0}, Case{"uz", Quantity::Displacement, 2},
               Case{"vy", Quantity::Velocity, 1}, Case{"sxx", Quantity::Stress, 0}, Case{"szz", Quantity::Stress, 2},
               Case{"sxy", Quantity::Stress, 3}, Case{"syz", Quantity::Stress, 4}, Case{"sxz", Quantity::Stress, 5},
               Case{"pressure", Quantity::Pressure, 0}, Case{"yield", Quantity::Yield, 0});
  INFO(c.name);
  const auto f = parse_field(c.name, 3);
  REQUIRE(f);
  CHECK(field_info(*f).quantity == c.array);
  CHECK(field_info(*f).component == c.component);
  CHECK(parse_vtu_array(c.name) == c.array);
}

TEST_CASE("VTU array names select their array; the position is not one", "[core][fields][vtu]") {
  CHECK(parse_vtu_array("stress") == Quantity::Stress);
  CHECK(parse_vtu_array("strain") == Quantity::Strain);
  CHECK(parse_vtu_array("shear_strain") == Quantity::ShearStrain);
  CHECK_THROWS_AS(parse_vtu_array("x"), InputError);  // the points themselves
  CHECK_THROWS_WITH(parse_vtu_array("position"),
                    "unknown output field 'position' (fields: id body material mass volume density displacement "
                    "velocity stress strain pressure q shear_strain plastic_strain yield, or component names such "
                    "as ux, vy, sxx)");
}

TEST_CASE("a quantity's components as the VTU writer reads them", "[core][fields][vtu]") {
  Particles<2> p;
  const std::size_t i = p.add(Vec<2>(1.0, 2.0), 1.0, 1.0, 0.25, 0, 0);
  p.u[i] = Vec<2>(0.25, -0.5);
  p.strain[i] = sym(1, 2, 3, 4, 5, 6);
  double t[6] = {9, 9, 9, 9, 9, 9};
  quantity_value(p, i, Quantity::Displacement, t);
  CHECK((t[0] == 0.25 && t[1] == -0.5 && t[2] == 0.0));  // 2D vectors written with z = 0
  quantity_value(p, i, Quantity::Strain, t);
  for (int c = 0; c < 6; ++c) CHECK(t[c] == c + 1.0);
}
