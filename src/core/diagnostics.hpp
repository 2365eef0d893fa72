// Whole-model measures: energies, momentum, centroids, and the force balance a gravity phase watches.
#pragma once

#include <vector>

#include "body.hpp"
#include "contact/contact_fields.hpp"
#include "grid.hpp"
#include "particles.hpp"
#include "time_step.hpp"

namespace seismpm {

// Kinetic energy of the deformable bodies (rigid ones have infinite mass).
template <int Dim>
double kinetic_energy(const Particles<Dim>& particles, const std::vector<Body>& bodies);
// Elastic strain energy recovered from the stresses, sum V [(tr s)^2 / 18K + dev s : dev s / 4G].
template <int Dim>
double strain_energy(const Particles<Dim>& particles, const std::vector<Body>& bodies, const MaterialConstants& c);
template <int Dim>
Vec<Dim> centroid(const Particles<Dim>& particles, int body);  // mass-weighted
template <int Dim>
Vec<Dim> momentum(const Particles<Dim>& particles, const std::vector<Body>& bodies);

// Euclidean norms of the out-of-balance force (before damping) over the free degrees of freedom of
// nodes not held by a rigid body, and of the external (gravity) force.
struct Balance {
  double out_of_balance = 0.0, external = 0.0;
};
// `contact` is null when the model has no contact fields; `scratch` is reused between steps.
template <int Dim>
Balance measure_balance(const Grid<Dim>& grid, const ContactFields<Dim>* contact, double min_mass,
                        const Vec<Dim>& gravity, std::vector<double>& scratch);

}  // namespace seismpm
