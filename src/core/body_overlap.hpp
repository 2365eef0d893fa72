// Where a new body's particles lie inside the shapes of bodies made before it: there the two bodies
// both hold particles, twice the mass in one space. Bodies that only touch do not overlap, whatever
// their particle spacings: a particle overlaps only when its own position is inside the other's shape
// (on a shared edge counts, since the other body then has a particle at the same place too).
#pragma once

#include <cstddef>
#include <vector>

#include "particles.hpp"
#include "region.hpp"

namespace seismpm {

struct BodyOverlap {
  int body = -1;              // the earlier body
  std::size_t particles = 0;  // particles of the new body inside its shape
  Vec<2> first;               // the first of them in creation order
};

// The earlier bodies (shapes[b], null when unknown) that body `new_body` overlaps, in body order.
std::vector<BodyOverlap> overlaps_of_body(const Particles<2>& particles, const std::vector<const Region*>& shapes,
                                          int new_body);

}  // namespace seismpm
