// A body: a named set of particles made at once, deformable or rigid.
#pragma once

#include <string>

namespace seismpm {

// Particles per cell along each axis when a body is filled: 1 to this many (16 x 16 in a cell is far
// finer than any result needs, and beyond it the fill would exhaust memory on a large domain first).
inline constexpr int kMaxParticlesPerCell = 16;

struct Body {
  std::string name;
  int ppc = 2;         // particles per cell per axis at creation
  bool rigid = false;  // prescribed-velocity particles (shaking-table box, sliding surface)
  int material = -1;   // a rigid body's stand-in material (RigidMaterial)
};

}  // namespace seismpm
