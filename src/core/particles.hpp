// Material points as a structure of arrays: one std::vector per field, indexed by particle.
// The order changes when particles are sorted by cell; `id` is the stable identity.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "types.hpp"

namespace seismpm {

// Aligned raw storage that sorting reuses from one sort to the next. A fresh array per field and sort
// cost a page fault per 4 KiB each time (13 MB for 40,000 particles in 2D), more than the copying.
// A copy starts empty: the storage is scratch, not state.
class PermuteBuffer {
 public:
  PermuteBuffer() = default;
  PermuteBuffer(const PermuteBuffer&) {}
  PermuteBuffer& operator=(const PermuteBuffer&) { return *this; }
  // At least `bytes` of storage aligned for any particle field; valid until the next call.
  std::byte* storage(std::size_t bytes) {
    if (bytes > size_) {
      data_.reset(static_cast<std::byte*>(::operator new (bytes, std::align_val_t{kAlign})));
      size_ = bytes;
    }
    return data_.get();
  }

 private:
  static constexpr std::size_t kAlign = 64;
  struct Free {
    void operator()(std::byte* p) const { ::operator delete (p, std::align_val_t{kAlign}); }
  };
  std::unique_ptr<std::byte, Free> data_;
  std::size_t size_ = 0;
};

template <int Dim>
struct Particles {
  std::vector<Vec<Dim>> x;             // position (m)
  std::vector<Vec<Dim>> u;             // displacement since the last reset (m)
  std::vector<Vec<Dim>> v;             // velocity (m/s)
  std::vector<Mat<Dim>> affine;        // APIC: the velocity gradient the particle carries (1/s); FLIP: 0
  std::vector<double> mass;            // kg (per metre out of plane in 2D)
  std::vector<double> volume;          // m^3 (m^2 per metre in 2D)
  std::vector<double> half_width;      // uGIMP half-width l in cell units, fixed at creation
  std::vector<Sym> stress;             // Cauchy stress (Pa), tension positive
  std::vector<Sym> damping_stress;     // Rayleigh: the viscous stress beta D : (de / dt) of the last step; else 0
  std::vector<Sym> strain;             // total strain since the last reset
  std::vector<double> plastic_strain;  // accumulated plastic shear strain
  std::vector<std::uint8_t> yield;     // 1 when the last update was plastic
  std::vector<Vec<Dim>> normal;        // rigid particles: outward unit normal of their body's nearest face (else 0)
  std::vector<std::int32_t> id;        // creation index, unchanged by sorting
  std::vector<std::uint16_t> body;
  std::vector<std::uint16_t> material;

  // Calls f(member) for every per-particle vector above: the one list that add and permute
  // go through, so a new member is its declaration plus its entry here.
  template <class F>
  void for_each_member(F&& f) {
    visit_members(*this, f);
  }
  template <class F>
  void for_each_member(F&& f) const {
    visit_members(*this, f);
  }

  std::size_t size() const { return x.size(); }
  double density(std::size_t p) const { return mass[p] / volume[p]; }

  // Appends a stress-free particle at rest; returns its index.
  std::size_t add(const Vec<Dim>& position, double particle_mass, double particle_volume, double particle_half_width,
                  int body_index, int material_index);

  // Reorders every field so that new index k holds old particle order[k], through `buffer`.
  void permute(const std::vector<int>& order, PermuteBuffer& buffer);
  void permute(const std::vector<int>& order) {
    PermuteBuffer buffer;
    permute(order, buffer);
  }
  // Room for n particles in every array, so that adding them allocates each array once.
  void reserve(std::size_t n) {
    for_each_member([n](auto& field) { field.reserve(n); });
  }

  // Sets displacement and total strain to zero (end of a gravity phase).
  void reset_kinematics();

 private:
  template <class Self, class F>
  static void visit_members(Self& s, F& f) {
    f(s.x);
    f(s.u);
    f(s.v);
    f(s.affine);
    f(s.mass);
    f(s.volume);
    f(s.half_width);
    f(s.stress);
    f(s.damping_stress);
    f(s.strain);
    f(s.plastic_strain);
    f(s.yield);
    f(s.normal);
    f(s.id);
    f(s.body);
    f(s.material);
  }
};

extern template struct Particles<2>;
extern template struct Particles<3>;

}  // namespace seismpm
