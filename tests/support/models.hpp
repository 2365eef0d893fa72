// Small models the tests share.
#pragma once

#include <memory>

#include "core/model.hpp"
#include "materials/linear_elastic.hpp"

namespace seismpm::test {

// An elastic block [lo, hi] in the domain [0, size]^Dim with cells of size h.
template <int Dim>
std::unique_ptr<Model<Dim>> elastic_block(double size, double h, const Vec<Dim>& lo, const Vec<Dim>& hi,
                                          ShapeKind shape = ShapeKind::Gimp, int ppc = 2, double young = 1e6,
                                          double poisson = 0.3, double density = 1000.0) {
  ModelSettings<Dim> s;
  s.lower = Vec<Dim>::Zero();
  s.upper = Vec<Dim>::Constant(size);
  s.cell = h;
  s.shape = shape;
  auto m = std::make_unique<Model<Dim>>(s);
  const int mat = m->add_material(std::make_shared<LinearElastic>(density, young, poisson));
  const int body = m->add_body("block", ppc);
  m->fill_box(body, mat, lo, hi);
  return m;
}

template <int Dim>
std::unique_ptr<Model<Dim>> elastic_block(ModelSettings<Dim> s, const Vec<Dim>& lo, const Vec<Dim>& hi, int ppc = 2,
                                          double young = 1e6, double poisson = 0.3, double density = 1000.0) {
  auto m = std::make_unique<Model<Dim>>(s);
  const int mat = m->add_material(std::make_shared<LinearElastic>(density, young, poisson));
  const int body = m->add_body("block", ppc);
  m->fill_box(body, mat, lo, hi);
  return m;
}

}  // namespace seismpm::test
