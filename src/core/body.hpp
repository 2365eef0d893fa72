// A body: a named set of particles made at once, deformable or rigid.
#pragma once

#include <string>

namespace seismpm {

struct Body {
  std::string name;
  int ppc = 2;         // particles per cell per axis at creation
  bool rigid = false;  // prescribed-velocity particles (shaking-table box, sliding surface)
  int material = -1;   // a rigid body's stand-in material (RigidMaterial)
};

}  // namespace seismpm
