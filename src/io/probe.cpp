#include "probe.hpp"

#include <algorithm>
#include <limits>

#include "core/error.hpp"
#include "core/model.hpp"

namespace seismpm {

template <int Dim>
Vec<Dim> reference_displacement(const Model<Dim>& model, const ProbeRelativeTo& r) {
  const auto& P = model.particles();
  if (r.kind == ProbeRelativeTo::Kind::Particle) return P.u[model.index_of(r.index)];
  if (r.kind != ProbeRelativeTo::Kind::Body) return Vec<Dim>::Zero();
  Vec<Dim> sum = Vec<Dim>::Zero(), plain = Vec<Dim>::Zero();
  double mass = 0.0;
  std::size_t n = 0;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.body[p] == r.index) {
      sum += P.mass[p] * P.u[p];
      plain += P.u[p];
      mass += P.mass[p];
      ++n;
    }
  if (n == 0) throw InputError("relative_to: " + r.what + " has no particles");
  return mass > 0.0 ? Vec<Dim>(sum / mass) : Vec<Dim>(plain / static_cast<double>(n));
}

std::vector<std::string> relative_field_names(int dim) {
  static const char* axis[] = {"x", "y", "z"};
  std::vector<std::string> out;
  for (int d = 0; d < dim; ++d) out.push_back(std::string("u") + axis[d] + "_rel");
  return out;
}

std::optional<int> parse_relative_field(std::string_view name, int dim) {
  const auto names = relative_field_names(dim);
  for (int d = 0; d < dim; ++d)
    if (name == names[d]) return d;
  return std::nullopt;
}

template <int Dim>
Probe<Dim>::Probe(const Model<Dim>& model, std::string name, int particle_id, const std::string& phase,
                  ProbeRelativeTo relative_to)
    : name_(std::move(name)), id_(particle_id), relative_(std::move(relative_to)), fields_(particle_fields(Dim)) {
  if (particle_id < 0 || particle_id >= static_cast<int>(model.particles().size()))
    throw InputError("probe '" + name_ + "': no particle with id " + std::to_string(particle_id));
  using Kind = ProbeRelativeTo::Kind;
  if (relative_.kind == Kind::Particle &&
      (relative_.index < 0 || relative_.index >= static_cast<int>(model.particles().size())))
    throw InputError("probe '" + name_ + "': relative_to: no particle with id " + std::to_string(relative_.index));
  if (relative_.kind == Kind::Body &&
      (relative_.index < 0 || relative_.index >= static_cast<int>(model.bodies().size())))
    throw InputError("probe '" + name_ + "': relative_to: no body " + std::to_string(relative_.index));
  sample(model, phase);
}

template <int Dim>
void Probe<Dim>::sample(const Model<Dim>& model, const std::string& phase) {
  if (!times_.empty() && times_.back() == model.time()) return;
  const std::size_t p = model.index_of(id_);
  // The reference first: it may throw, and a sample is recorded whole or not at all.
  Vec<Dim> relative = Vec<Dim>::Zero();
  if (relative_.active()) relative = model.particles().u[p] - reference_displacement(model, relative_);
  if (phases_.empty() || phases_.back().second != phase) phases_.emplace_back(times_.size(), phase);
  times_.push_back(model.time());
  phase_times_.push_back(model.phase_time());
  for (Field f : fields_) values_.push_back(field_value(model.particles(), p, f));
  if (relative_.active())
    for (int d = 0; d < Dim; ++d) relative_values_.push_back(relative[d]);
}

template <int Dim>
std::vector<double> Probe<Dim>::series(Field f) const {
  std::size_t column = 0;
  while (fields_[column] != f) ++column;
  std::vector<double> out(times_.size());
  for (std::size_t k = 0; k < times_.size(); ++k) out[k] = values_[k * fields_.size() + column];
  return out;
}

template <int Dim>
const std::string& Probe<Dim>::phase(std::size_t k) const {
  // The last entry that starts at or before k.
  auto it = std::upper_bound(phases_.begin(), phases_.end(), k,
                             [](std::size_t s, const std::pair<std::size_t, std::string>& e) { return s < e.first; });
  static const std::string none;
  return it == phases_.begin() ? none : std::prev(it)->second;
}

template <int Dim>
void Probe<Dim>::require_relative(int d) const {
  if (!relative_.active())
    throw InputError("probe '" + name_ +
                     "' has no reference: give m:probe{ ..., relative_to = a probe or a body } for " +
                     relative_field_names(Dim)[std::clamp(d, 0, Dim - 1)]);
}

template <int Dim>
double Probe<Dim>::relative_now(const Model<Dim>& model, int d) const {
  require_relative(d);
  return model.particles().u[model.index_of(id_)][d] - reference_displacement(model, relative_)[d];
}

template <int Dim>
std::vector<double> Probe<Dim>::relative_series(int d) const {
  require_relative(d);
  std::vector<double> out(times_.size());
  for (std::size_t k = 0; k < times_.size(); ++k) out[k] = relative_values_[k * Dim + d];
  return out;
}

template Vec<2> reference_displacement<2>(const Model<2>&, const ProbeRelativeTo&);
template Vec<3> reference_displacement<3>(const Model<3>&, const ProbeRelativeTo&);
template class Probe<2>;
template class Probe<3>;

}  // namespace seismpm
