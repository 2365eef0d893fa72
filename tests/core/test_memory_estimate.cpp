// The memory estimate told before a model is allocated: the figures match what a model takes, and a
// grid or a body that does not fit in the available memory is refused with both figures, before
// anything is allocated for it.
#include <catch2/catch.hpp>

#include <malloc.h>
#include <unistd.h>

#include <fstream>
#include <memory>

#include "core/error.hpp"
#include "core/memory_estimate.hpp"
#include "core/model.hpp"
#include "materials/linear_elastic.hpp"

using namespace seismpm;

namespace {

// Resident memory of this process (bytes). The heap's free pages are handed back first: run after
// other tests in one process, memory they freed but the allocator kept would be reused unseen and
// make the model look smaller than it is.
double resident_bytes() {
  malloc_trim(0);
  std::ifstream in("/proc/self/statm");
  double pages = 0, resident = 0;
  in >> pages >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

ModelSettings<2> square_domain(double side, double cell) {
  ModelSettings<2> s;
  s.lower = Vec<2>(0.0, 0.0);
  s.upper = Vec<2>(side, side);
  s.cell = cell;
  s.gravity = Vec<2>(0.0, -9.81);
  return s;
}

}  // namespace

TEST_CASE("memory figures read as people write them", "[core][memory]") {
  CHECK(format_bytes(512) == "512 bytes");
  CHECK(format_bytes(1536) == "1.5 KiB");
  CHECK(format_bytes(std::uint64_t(3) << 30) == "3 GiB");
  CHECK(available_memory() > 0);  // Linux tells it
}

TEST_CASE("the estimate per particle matches the memory a model takes", "[core][memory]") {
  // 160,000 particles of a block on 0.01 m cells (2 x 2 per cell), stepped twice so that the step's
  // arrays (stencils, strain increments, spin) exist too. The grid is a small share of it.
  auto model = std::make_unique<Model<2>>(square_domain(2.2, 0.01));
  const int mat = model->add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  const int body = model->add_body("block", 2);
  const double before = resident_bytes();
  const std::size_t n = model->fill_box(body, mat, Vec<2>(0.0, 0.0), Vec<2>(2.0, 2.0));
  model->step();
  model->step();
  const double measured = resident_bytes() - before;
  const double estimated = static_cast<double>(n * model->bytes_per_particle());
  CAPTURE(n, model->bytes_per_particle(), measured, estimated);
  REQUIRE(n == 160000);
  CHECK(estimated > 0.7 * measured);
  CHECK(estimated < 1.3 * measured);
}

TEST_CASE("a grid larger than the available memory is refused with both figures", "[core][memory][robustness]") {
  // 1e6 x 1e6 cells: about 4e13 bytes of nodes, more than any machine this runs on has.
  const auto s = square_domain(1e6, 1.0);
  REQUIRE(Model<2>::grid_bytes(s) > 1e13);
  try {
    Model<2> m(s);
    FAIL("the grid was built");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CAPTURE(what);
    CHECK(what.rfind("the grid needs about ", 0) == 0);
    CHECK(what.find("TiB of memory, more than the ") != std::string::npos);
    CHECK(what.find("available now") != std::string::npos);
    CHECK(what.find("check_memory = false") != std::string::npos);
  }
}

TEST_CASE("a body larger than the available memory is refused before it is allocated", "[core][memory][robustness]") {
  // 1000 x 1000 cells (a grid of about 100 MB) filled at 12 x 12 per cell: 144 million particles.
  auto model = std::make_unique<Model<2>>(square_domain(1000.0, 1.0));
  const int mat = model->add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  const int body = model->add_body("huge", 12);
  const double need = 144e6 * static_cast<double>(model->bytes_per_particle());
  if (need < 1.5 * static_cast<double>(available_memory())) {
    WARN("this machine has the memory for the body: not tried");
    return;
  }
  const double before = resident_bytes();
  try {
    model->fill_box(body, mat, Vec<2>(0.0, 0.0), Vec<2>(1000.0, 1000.0));
    FAIL("the body was filled");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CAPTURE(what);
    CHECK(what.rfind("body 'huge' (144000000 particles) needs about ", 0) == 0);
    CHECK(what.find("GiB of memory, more than the ") != std::string::npos);
  }
  CHECK(model->particles().size() == 0);
  CHECK(resident_bytes() - before < 50e6);  // refused before its arrays were allocated
}
