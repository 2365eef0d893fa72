// Contact fields and how they interact. Bodies that need their own velocity at a node are "contact
// fields": every rigid body, and every deformable body named in a contact pair; all other deformable
// bodies share field 0. Two fields without a declared pair are glued (one velocity, "standard MPM");
// a declared pair slides with Coulomb friction and separates freely. A rigid field has a prescribed
// velocity and infinite mass.
#pragma once

#include <vector>

namespace seismpm {

class ContactRules {
 public:
  static constexpr double kGlued = -1.0;

  void reset(int fields) {
    fields_ = fields;
    friction_.assign(static_cast<std::size_t>(fields) * fields, kGlued);
    rigid_.assign(fields, false);
  }
  int fields() const { return fields_; }
  void set_rigid(int field, bool rigid) { rigid_[field] = rigid; }
  bool rigid(int field) const { return rigid_[field]; }
  void set_friction(int a, int b, double mu) { friction_[a * fields_ + b] = friction_[b * fields_ + a] = mu; }
  // Coulomb coefficient of the pair, or kGlued when no contact is declared between them.
  double friction(int a, int b) const { return friction_[a * fields_ + b]; }
  bool glued(int a, int b) const { return friction(a, b) < 0.0; }

 private:
  int fields_ = 0;
  std::vector<double> friction_;
  std::vector<char> rigid_;
};

}  // namespace seismpm
