#include "probe.hpp"

#include "core/error.hpp"
#include "core/model.hpp"

namespace seismpm {

template <int Dim>
Probe<Dim>::Probe(const Model<Dim>& model, std::string name, int particle_id)
    : name_(std::move(name)), id_(particle_id), fields_(particle_fields(Dim)) {
  if (particle_id < 0 || particle_id >= static_cast<int>(model.particles().size()))
    throw InputError("probe '" + name_ + "': no particle with id " + std::to_string(particle_id));
  sample(model);
}

template <int Dim>
void Probe<Dim>::sample(const Model<Dim>& model) {
  if (!times_.empty() && times_.back() == model.time()) return;
  const std::size_t p = model.index_of(id_);
  times_.push_back(model.time());
  for (Field f : fields_) values_.push_back(field_value(model.particles(), p, f));
}

template <int Dim>
std::vector<double> Probe<Dim>::series(Field f) const {
  std::size_t column = 0;
  while (fields_[column] != f) ++column;
  std::vector<double> out(times_.size());
  for (std::size_t k = 0; k < times_.size(); ++k) out[k] = values_[k * fields_.size() + column];
  return out;
}

template class Probe<2>;
template class Probe<3>;

}  // namespace seismpm
