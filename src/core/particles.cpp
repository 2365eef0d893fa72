#include "particles.hpp"

namespace seismpm {

template <int Dim>
std::size_t Particles<Dim>::add(const Vec<Dim>& position, double particle_mass, double particle_volume,
                                double particle_half_width, int body_index, int material_index) {
  x.push_back(position);
  u.push_back(Vec<Dim>::Zero());
  v.push_back(Vec<Dim>::Zero());
  normal.push_back(Vec<Dim>::Zero());
  mass.push_back(particle_mass);
  volume.push_back(particle_volume);
  half_width.push_back(particle_half_width);
  stress.push_back(Sym::Zero());
  strain.push_back(Sym::Zero());
  plastic_strain.push_back(0.0);
  yield.push_back(0);
  id.push_back(static_cast<std::int32_t>(id.size()));
  body.push_back(static_cast<std::uint16_t>(body_index));
  material.push_back(static_cast<std::uint16_t>(material_index));
  return x.size() - 1;
}

namespace {
template <class T>
void apply_order(std::vector<T>& field, const std::vector<int>& order, std::vector<T>& scratch) {
  scratch.resize(field.size());
  const int n = static_cast<int>(order.size());
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) scratch[k] = field[order[k]];
  field.swap(scratch);
}
}  // namespace

template <int Dim>
void Particles<Dim>::permute(const std::vector<int>& order) {
  {
    std::vector<Vec<Dim>> s;
    apply_order(x, order, s);
    apply_order(u, order, s);
    apply_order(v, order, s);
    apply_order(normal, order, s);
  }
  {
    std::vector<double> s;
    apply_order(mass, order, s);
    apply_order(volume, order, s);
    apply_order(half_width, order, s);
    apply_order(plastic_strain, order, s);
  }
  {
    std::vector<Sym> s;
    apply_order(stress, order, s);
    apply_order(strain, order, s);
  }
  {
    std::vector<std::uint8_t> s;
    apply_order(yield, order, s);
  }
  {
    std::vector<std::int32_t> s;
    apply_order(id, order, s);
  }
  {
    std::vector<std::uint16_t> s;
    apply_order(body, order, s);
    apply_order(material, order, s);
  }
}

template <int Dim>
void Particles<Dim>::reset_kinematics() {
  for (auto& d : u) d.setZero();
  for (auto& e : strain) e.setZero();
}

template struct Particles<2>;
template struct Particles<3>;

}  // namespace seismpm
