// Failing loudly: a particle leaving the grid or a non-finite state stops the run with an error
// naming the step, the time, the particle and its position. No particle is ever dropped.
#include <catch2/catch.hpp>

#include <limits>

#include "core/error.hpp"
#include "support/models.hpp"

using namespace seismpm;

TEST_CASE("a particle leaving the grid stops the run and names it", "[core][failure]") {
  const auto shape = GENERATE(ShapeKind::Linear, ShapeKind::Gimp);
  CAPTURE(to_string(shape));
  auto m = test::elastic_block<2>(1.0, 0.1, Vec<2>(0.5, 0.4), Vec<2>(0.8, 0.6), shape);
  const std::size_t count = m->particles().size();
  for (auto& v : m->particles().v) v = Vec<2>(5.0, 0.0);  // toward the right edge
  std::string message;
  try {
    m->run(1.0);
  } catch (const SimulationError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK_THAT(message, Catch::Contains("left the grid") && Catch::Contains("step ") && Catch::Contains("t = ") &&
                          Catch::Contains("particle ") && Catch::Contains("body 'block'") &&
                          Catch::Contains("the domain spans"));
  CHECK(m->time() < 0.1);
  CHECK(m->particles().size() == count);
  // Stepping again refuses too: the run cannot go on quietly.
  CHECK_THROWS_AS(m->step(), SimulationError);
}

namespace {

// A material that turns one particle's stress into NaN or an infinity, as a broken constitutive
// update would.
class BrokenMaterial : public LinearElastic {
 public:
  BrokenMaterial(int victim, double value) : LinearElastic(1000.0, 1e6, 0.3), victim_(victim), value_(value) {}
  void update_stress(const StressUpdate& b) const override {
    LinearElastic::update_stress(b);
    for (int k = 0; k < b.count; ++k)
      if (b.index[k] == victim_) b.stress[victim_][1] = value_;
  }

 private:
  int victim_;
  double value_;
};

}  // namespace

TEST_CASE("a NaN in a particle's state stops the run and names the particle", "[core][failure]") {
  const double inf = std::numeric_limits<double>::infinity();
  const double value = GENERATE_COPY(std::numeric_limits<double>::quiet_NaN(), inf, -inf);
  CAPTURE(value);
  ModelSettings<2> s;
  s.cell = 0.1;
  Model<2> m(s);
  const int mat = m.add_material(std::make_shared<BrokenMaterial>(17, value));
  const int body = m.add_body("soil", 2);
  m.fill_box(body, mat, Vec<2>(0.2, 0.2), Vec<2>(0.6, 0.6));
  const int id = m.particles().id[17];
  const Vec<2> x = m.particles().x[17];
  std::string message;
  try {
    m.step();
  } catch (const SimulationError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK_THAT(message, Catch::Contains("particle " + std::to_string(id) + " of body 'soil'") &&
                          Catch::Contains("non-finite") && Catch::Contains("step 1"));
  std::ostringstream pos;
  pos.precision(6);
  pos << "(" << x[0] << ", " << x[1] << ")";
  CHECK_THAT(message, Catch::Contains(pos.str()));
}

TEST_CASE("an infinite velocity given to a particle stops the run", "[core][failure]") {
  auto m = test::elastic_block<2>(1.0, 0.1, Vec<2>(0.2, 0.2), Vec<2>(0.6, 0.6));
  m->particles().v[3] = Vec<2>(std::numeric_limits<double>::infinity(), 0.0);
  CHECK_THROWS_AS(m->step(), SimulationError);
}

TEST_CASE("a collapsing time step stops the run and names the fastest particle", "[core][failure]") {
  auto m = test::elastic_block<2>(1.0, 0.1, Vec<2>(0.2, 0.2), Vec<2>(0.6, 0.6));
  m->step();
  const int id = m->particles().id[5];
  m->particles().v[5] = Vec<2>(0.0, 1e9);  // a particle shot off at 1e9 m/s
  std::string message;
  try {
    m->step();
  } catch (const SimulationError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK_THAT(message, Catch::Contains("time step collapsed") &&
                          Catch::Contains("particle " + std::to_string(id) + " ") && Catch::Contains("step 1 "));
  CHECK(m->steps() == 1);
}

TEST_CASE("a model refuses bad settings by name", "[core][failure]") {
  ModelSettings<2> s;
  s.cfl = 1.5;
  CHECK_THROWS_WITH(Model<2>(s), Catch::Contains("cfl"));
  s.cfl = 0.4;
  s.flip = 2.0;
  CHECK_THROWS_WITH(Model<2>(s), Catch::Contains("flip"));
  s.flip = 1.0;
  s.cell = 1.5;
  CHECK_THROWS_WITH(Model<2>(s), Catch::Contains("2 cells"));
  Model<2> empty(ModelSettings<2>{});
  CHECK_THROWS_WITH(empty.step(), Catch::Contains("no particles"));
}
