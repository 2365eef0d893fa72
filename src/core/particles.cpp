#include "particles.hpp"

#include <new>
#include <type_traits>

namespace seismpm {

namespace {
template <class T>
T zero() {
  if constexpr (std::is_arithmetic_v<T>)
    return T{0};
  else
    return T::Zero();
}

// Copies the reordered field into the buffer, then back: no allocation, no zeroing.
template <class T>
void apply_order(std::vector<T>& field, const std::vector<int>& order, PermuteBuffer& buffer) {
  static_assert(std::is_trivially_destructible_v<T> && alignof(T) <= 64);
  const int n = static_cast<int>(order.size());
  if (n == 0) return;
  std::byte* raw = buffer.storage(sizeof(T) * order.size());
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) ::new (raw + sizeof(T) * k) T(field[order[k]]);
  const T* scratch = std::launder(reinterpret_cast<const T*>(raw));
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) field[k] = scratch[k];
}
}  // namespace

template <int Dim>
std::size_t Particles<Dim>::add(const Vec<Dim>& position, double particle_mass, double particle_volume,
                                double particle_half_width, int body_index, int material_index) {
  // Every member starts at zero (at rest, stress-free, no normal); then the given values.
  for_each_member([](auto& member) { member.push_back(zero<typename std::decay_t<decltype(member)>::value_type>()); });
  const std::size_t p = x.size() - 1;
  x[p] = position;
  mass[p] = particle_mass;
  volume[p] = particle_volume;
  half_width[p] = particle_half_width;
  id[p] = static_cast<std::int32_t>(p);
  body[p] = static_cast<std::uint16_t>(body_index);
  material[p] = static_cast<std::uint16_t>(material_index);
  return p;
}

template <int Dim>
void Particles<Dim>::permute(const std::vector<int>& order, PermuteBuffer& buffer) {
  for_each_member([&](auto& member) { apply_order(member, order, buffer); });
}

template <int Dim>
void Particles<Dim>::reset_kinematics() {
  for (auto& d : u) d.setZero();
  for (auto& e : strain) e.setZero();
}

template struct Particles<2>;
template struct Particles<3>;

}  // namespace seismpm
