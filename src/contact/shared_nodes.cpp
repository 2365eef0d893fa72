#include "shared_nodes.hpp"

namespace seismpm {

template <int Dim>
void SharedNodes<Dim>::clear(int node_count) {
  FieldSet empty;
  empty.fill(-1);
  if (static_cast<int>(present_.size()) != node_count) {
    present_.assign(node_count, empty);
    index_.assign(node_count, -1);
  } else {
    for (const int i : touched_) {
      present_[i] = empty;
      index_[i] = -1;
    }
  }
  touched_.clear();
}

namespace {

bool kept_apart(const FieldSet& set, int count, const ContactRules& rules) {
  for (int a = 0; a < count; ++a) {
    if (rules.rigid(set[a])) return true;
    for (int b = a + 1; b < count; ++b)
      if (!rules.glued(set[a], set[b])) return true;
  }
  return false;
}

}  // namespace

template <int Dim>
void SharedNodes<Dim>::build(const ContactRules& rules) {
  node_.clear();
  fields_.clear();
  for (const int i : touched_) {
    if (present_[i][1] < 0) continue;  // one field or none: the common grid fields serve
    int c = 2;
    while (c < kSlots && present_[i][c] >= 0) ++c;
    if (!kept_apart(present_[i], c, rules)) continue;
    index_[i] = static_cast<int>(node_.size());
    node_.push_back(i);
    fields_.push_back(c);
  }
  const std::size_t slots = node_.size() * kSlots;
  mass.assign(slots, 0.0);
  momentum.assign(slots, Vec<Dim>::Zero());
  force.assign(slots, Vec<Dim>::Zero());
  gradient.assign(slots, Vec<Dim>::Zero());
  velocity.assign(slots, Vec<Dim>::Zero());
  acceleration.assign(slots, Vec<Dim>::Zero());
  face.assign(slots, Vec<Dim>::Zero());
}

template class SharedNodes<2>;
template class SharedNodes<3>;

}  // namespace seismpm
