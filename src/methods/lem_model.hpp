// The slope of limit equilibrium read from an MPM model: the ground surface from the deformable
// particles, the soil's strength and unit weight from their materials, the firm base below them.
#pragma once

#include "core/model.hpp"
#include "methods/limit_equilibrium.hpp"

namespace seismpm {

// Throws InputError when the model has no deformable particles or one of their materials has no
// Mohr-Coulomb strength (linear elastic, rigid).
LemSlope slope_of_model(const Model<2>& m);

}  // namespace seismpm
