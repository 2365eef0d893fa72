#include "body_overlap.hpp"

#include <algorithm>

namespace seismpm {

std::vector<BodyOverlap> overlaps_of_body(const Particles<2>& particles, const std::vector<const Region*>& shapes,
                                          int new_body) {
  std::vector<std::size_t> order;  // the new body's particles in creation order
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (particles.body[p] == new_body) order.push_back(p);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return particles.id[a] < particles.id[b]; });
  std::vector<BodyOverlap> out;
  for (std::size_t b = 0; b < shapes.size(); ++b) {
    if (!shapes[b] || static_cast<int>(b) == new_body) continue;
    const Region& shape = *shapes[b];
    BodyOverlap o{static_cast<int>(b), 0, Vec<2>::Zero()};
    for (std::size_t p : order) {
      const Vec<2>& x = particles.x[p];
      bool in_box = true;  // the bounding box first: most particles are far from most bodies
      for (int d = 0; d < 2; ++d) in_box = in_box && x[d] >= shape.lower()[d] && x[d] <= shape.upper()[d];
      if (in_box && shape.contains(x) && o.particles++ == 0) o.first = x;
    }
    if (o.particles > 0) out.push_back(o);
  }
  return out;
}

}  // namespace seismpm
