#include "methods/lem_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "core/error.hpp"
#include "materials/drucker_prager.hpp"
#include "materials/mohr_coulomb.hpp"

namespace seismpm {

namespace {

// The Mohr-Coulomb strength of a material: both soil models carry c and phi (Drucker-Prager's cone is
// fitted to them), so limit equilibrium uses those; other materials have no strength to slide on.
const StrengthParameters& strength_of(const Material& mat) {
  if (const auto* mc = dynamic_cast<const MohrCoulomb*>(&mat)) return mc->parameters();
  if (const auto* dp = dynamic_cast<const DruckerPrager*>(&mat)) return dp->parameters();
  throw InputError("limit equilibrium: material '" + std::string(mat.kind()) +
                   "' has no shear strength (use mohr_coulomb or drucker_prager)");
}

LemSoil soil_of(const Model<2>& m, int material) {
  const Material& mat = m.material(material);
  const StrengthParameters& s = strength_of(mat);
  const double g = m.settings().gravity.norm();
  // A model without gravity still has soil of a weight: standard gravity.
  return {mat.density() * (g > 0 ? g : 9.80665), s.cohesion, s.friction};
}

bool deformable(const Model<2>& m, std::size_t p) { return !m.bodies()[m.particles().body[p]].rigid; }

// Horizontal bands from the grid rows: each row takes the material most of its deformable particles
// have, and neighbouring rows of one material make one band.
std::vector<LemBand> bands_of(const Model<2>& m, double bottom) {
  const auto& ps = m.particles();
  const double h = m.grid().cell();
  std::map<int, std::map<int, int>> rows;  // row -> material -> count
  for (std::size_t p = 0; p < ps.size(); ++p)
    if (deformable(m, p)) ++rows[static_cast<int>(std::floor((ps.x[p][1] - bottom) / h))][ps.material[p]];
  std::vector<LemBand> bands;
  int previous = -1;
  for (const auto& [row, counts] : rows) {
    const int mat =
        std::max_element(counts.begin(), counts.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
    if (mat == previous) continue;
    bands.push_back({bottom + row * h, soil_of(m, mat)});
    previous = mat;
  }
  bands.front().bottom = bottom;
  return bands;
}

}  // namespace

LemSlope slope_of_model(const Model<2>& m) {
  const auto& ps = m.particles();
  const double h = m.grid().cell(), x0 = m.grid().domain_lower()[0];
  std::map<int, double> top;  // grid column -> top of its highest deformable particle
  double bottom = INFINITY, lowest_centre = INFINITY;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    if (!deformable(m, p)) continue;
    const double half = ps.half_width[p] * h;
    const int col = static_cast<int>(std::floor((ps.x[p][0] - x0) / h));
    auto [it, fresh] = top.emplace(col, ps.x[p][1] + half);
    if (!fresh) it->second = std::max(it->second, ps.x[p][1] + half);
    bottom = std::min(bottom, ps.x[p][1] - half);
    lowest_centre = std::min(lowest_centre, ps.x[p][1]);
  }
  if (top.size() < 2) throw InputError("limit equilibrium: the model has no deformable soil two columns wide");
  LemSlope s;
  for (const auto& [col, y] : top) s.surface.push_back({x0 + (col + 0.5) * h, y});
  // The base is the soil's bottom, or the top of a rigid body under the soil when that lies higher.
  s.base = bottom;
  for (std::size_t p = 0; p < ps.size(); ++p) {
    const double rigid_top = ps.x[p][1] + ps.half_width[p] * h;
    if (!deformable(m, p) && rigid_top <= lowest_centre) s.base = std::max(s.base, rigid_top);
  }
  s.bands = bands_of(m, bottom);
  return s;
}

}  // namespace seismpm
