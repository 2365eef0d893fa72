// The checks that end a step, and the message that names a failing particle, its body, position,
// step and time.
#include <sstream>

#include "error.hpp"
#include "format.hpp"
#include "model.hpp"
#include "thread_shares.hpp"

namespace seismpm {

template <int Dim>
void Model<Dim>::fail(std::size_t p, const std::string& what) const {
  std::ostringstream os;
  os.precision(6);
  os << "step " << steps_ << " (t = " << time_ << " s): particle " << particles_.id[p] << " of body '"
     << bodies_[particles_.body[p]].name << "' at " << format_point<Dim>(particles_.x[p]) << " " << what;
  if (what.find("grid") != std::string::npos)
    os << " (the domain spans " << format_point<Dim>(grid_.domain_lower()) << " to "
       << format_point<Dim>(grid_.domain_upper()) << ")";
  throw SimulationError(os.str());
}

// Every particle finite with a positive volume, and its centre inside the domain (the next step
// needs its whole support on the grid).
template <int Dim>
void Model<Dim>::check_particles() const {
  const int n = static_cast<int>(particles_.size());
  const auto& P = particles_;
  // One pass: the first invalid particle, and the first one outside (a non-finite one is reported first).
  int bad = n, outside = n;
  const DomainBox<Dim> domain(grid_);
  auto& shares = ThreadShares::of(LoopKind::Particles);
  const auto start = ThreadShares::Clock::now();
#pragma omp parallel reduction(min : bad, outside)
  {
    const auto mine = shares.mine(n);
    for (int p = static_cast<int>(mine.begin); p < mine.end; ++p) {
      // Without branches: 0 * a is 0 for every finite a and NaN for an infinite or NaN one, so the sum
      // of the zeros is 0 exactly when every value is finite.
      const double zeros = (0.0 * P.x[p]).sum() + (0.0 * P.v[p]).sum() + (0.0 * P.stress[p]).sum() + 0.0 * P.volume[p];
      const bool valid = (zeros == 0.0) & (P.volume[p] > 0.0);
      if (!valid) bad = std::min(bad, p);
      if (!domain.contains(P.x[p])) outside = std::min(outside, p);
    }
    shares.finished(start, mine.end - mine.begin);
  }
  if (bad < n) {
    std::ostringstream os;
    os << "has a non-finite or invalid state (velocity " << format_point<Dim>(P.v[bad]) << ", volume " << P.volume[bad]
       << ")";
    fail(bad, os.str());
  }
  if (outside < n) fail(outside, "left the grid");
}

template void Model<2>::fail(std::size_t, const std::string&) const;
template void Model<3>::fail(std::size_t, const std::string&) const;
template void Model<2>::check_particles() const;
template void Model<3>::check_particles() const;

}  // namespace seismpm
