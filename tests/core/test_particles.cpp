// Particle storage: every member is listed once (for_each_member), add starts each one at zero but
// for the given values, and permute moves every member together.
#include <catch2/catch.hpp>

#include <type_traits>

#include "core/particles.hpp"

using namespace seismpm;

TEST_CASE("for_each_member visits every member of Particles", "[core][particles]") {
  // Particles holds nothing but std::vectors, all of one size whatever their element type; a member
  // declared but missing from for_each_member makes the struct larger than the members visited.
  Particles<2> p;
  std::size_t members = 0, bytes = 0;
  p.for_each_member([&](auto& member) {
    ++members;
    bytes += sizeof(member);
  });
  CHECK(members == 16);
  CHECK(bytes == sizeof(Particles<2>));
  CHECK(sizeof(Particles<3>) == sizeof(Particles<2>));
}

TEST_CASE("add appends a particle at rest and stress-free", "[core][particles]") {
  Particles<2> p;
  p.add(Vec<2>(0.0, 0.0), 1.0, 1.0, 0.25, 0, 0);
  const std::size_t i = p.add(Vec<2>(1.5, -2.0), 8.0, 4.0, 0.125, 3, 1);
  CHECK(i == 1);
  const Particles<2>& cp = p;
  cp.for_each_member([](const auto& member) { CHECK(member.size() == 2); });
  CHECK(p.x[1] == Vec<2>(1.5, -2.0));
  CHECK(p.mass[1] == 8.0);
  CHECK(p.volume[1] == 4.0);
  CHECK(p.density(1) == 2.0);
  CHECK(p.half_width[1] == 0.125);
  CHECK(p.id[1] == 1);
  CHECK(p.body[1] == 3);
  CHECK(p.material[1] == 1);
  CHECK(p.u[1] == Vec<2>::Zero());
  CHECK(p.v[1] == Vec<2>::Zero());
  CHECK(p.normal[1] == Vec<2>::Zero());
  CHECK(p.stress[1] == Sym::Zero());
  CHECK(p.damping_stress[1] == Sym::Zero());
  CHECK(p.strain[1] == Sym::Zero());
  CHECK(p.plastic_strain[1] == 0.0);
  CHECK(p.yield[1] == 0);
}

TEST_CASE("permute moves every member of a particle together", "[core][particles]") {
  Particles<3> p;
  for (int k = 0; k < 3; ++k) {
    p.add(Vec<3>(k, 0, 0), 10.0 + k, 1.0, 0.25, k, 2 * k);
    p.u[k] = Vec<3>(0, k, 0);
    p.v[k] = Vec<3>(0, 0, k);
    p.normal[k] = Vec<3>(k, k, k);
    p.stress[k] = Sym::Constant(-k);
    p.damping_stress[k] = Sym::Constant(2.0 * k);
    p.strain[k] = Sym::Constant(0.1 * k);
    p.plastic_strain[k] = 0.5 * k;
    p.yield[k] = static_cast<std::uint8_t>(k % 2);
  }
  p.permute({2, 0, 1});  // new 0 = old 2, new 1 = old 0, new 2 = old 1
  const int old_of[3] = {2, 0, 1};
  for (int k = 0; k < 3; ++k) {
    const int o = old_of[k];
    INFO("new index " << k);
    CHECK(p.id[k] == o);
    CHECK(p.x[k][0] == o);
    CHECK(p.u[k][1] == o);
    CHECK(p.v[k][2] == o);
    CHECK(p.normal[k][2] == o);
    CHECK(p.mass[k] == 10.0 + o);
    CHECK(p.body[k] == o);
    CHECK(p.material[k] == 2 * o);
    CHECK(p.stress[k][5] == -o);
    CHECK(p.damping_stress[k][3] == 2.0 * o);
    CHECK(p.strain[k][4] == 0.1 * o);
    CHECK(p.plastic_strain[k] == 0.5 * o);
    CHECK(p.yield[k] == o % 2);
  }
}

TEST_CASE("reset_kinematics zeroes displacement and strain only", "[core][particles]") {
  Particles<2> p;
  p.add(Vec<2>(1.0, 1.0), 1.0, 1.0, 0.25, 0, 0);
  p.u[0] = Vec<2>(0.5, 0.5);
  p.strain[0] = Sym::Constant(0.01);
  p.stress[0] = Sym::Constant(-3.0);
  p.v[0] = Vec<2>(1.0, 0.0);
  p.reset_kinematics();
  CHECK(p.u[0] == Vec<2>::Zero());
  CHECK(p.strain[0] == Sym::Zero());
  CHECK(p.stress[0] == Sym::Constant(-3.0));
  CHECK(p.v[0] == Vec<2>(1.0, 0.0));
}
