// Linear elasticity: Hooke's law in plane strain and bad parameters.
#include <catch2/catch.hpp>

#include "core/error.hpp"
#include "materials/linear_elastic.hpp"

using namespace seismpm;

TEST_CASE("linear elastic stress follows Hooke's law with sigma_zz kept", "[materials][elastic]") {
  const double E = 1e7, nu = 0.25;
  const LinearElastic mat(2000.0, E, nu);
  const double G = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  std::vector<Sym> stress(1, Sym::Zero()), de(1, Sym::Zero());
  std::vector<double> ep(1, 0.0);
  std::vector<std::uint8_t> yield(1, 1);
  const int index = 0;
  de[0] << 1e-4, 0.0, 0.0, 2e-5, 0.0, 0.0;  // plane strain: de_zz = 0
  StressUpdate b{&index, 1, stress.data(), de.data(), ep.data(), yield.data()};
  mat.update_stress(b);
  CHECK(stress[0][0] == Approx((lambda + 2 * G) * 1e-4));
  CHECK(stress[0][1] == Approx(lambda * 1e-4));
  CHECK(stress[0][2] == Approx(lambda * 1e-4));  // sigma_zz = nu (sigma_xx + sigma_yy)
  CHECK(stress[0][2] == Approx(nu * (stress[0][0] + stress[0][1])));
  CHECK(stress[0][3] == Approx(2 * G * 2e-5));
  CHECK(yield[0] == 0);
  CHECK(mat.p_wave_modulus() == Approx(lambda + 2 * G));
}

TEST_CASE("linear elastic parameters out of range are refused by name", "[materials][elastic]") {
  CHECK_THROWS_WITH(LinearElastic(0.0, 1e6, 0.3), Catch::Contains("density"));
  CHECK_THROWS_WITH(LinearElastic(1000.0, -1.0, 0.3), Catch::Contains("young"));
  CHECK_THROWS_WITH(LinearElastic(1000.0, 1e6, 0.5), Catch::Contains("poisson"));
  CHECK_THROWS_WITH(LinearElastic(1000.0, 1e6, -0.1), Catch::Contains("poisson"));
}
