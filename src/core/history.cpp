#include "history.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "error.hpp"

namespace seismpm {

std::string ConstantHistory::describe() const {
  std::ostringstream os;
  os << "constant " << value_;
  return os.str();
}

TableHistory::TableHistory(std::vector<double> times, std::vector<double> values, std::string source)
    : t_(std::move(times)), v_(std::move(values)), source_(std::move(source)) {
  if (t_.empty()) throw InputError(source_ + ": history has no points");
  if (t_.size() != v_.size()) throw InputError(source_ + ": history has unequal numbers of times and values");
  for (std::size_t k = 0; k < t_.size(); ++k) {
    if (!std::isfinite(t_[k]) || !std::isfinite(v_[k]))
      throw InputError(source_ + ": point " + std::to_string(k + 1) + " is not a finite number");
    if (k > 0 && !(t_[k] > t_[k - 1]))
      throw InputError(source_ + ": times must increase (point " + std::to_string(k + 1) + ")");
  }
}

double TableHistory::at(double t) const {
  if (t < t_.front() || t > t_.back()) return 0.0;
  if (t_.size() == 1) return v_.front();
  const auto it = std::upper_bound(t_.begin(), t_.end(), t);
  const std::size_t k = std::min<std::size_t>(it - t_.begin(), t_.size() - 1);  // t in [t_{k-1}, t_k]
  const double s = (t - t_[k - 1]) / (t_[k] - t_[k - 1]);
  return v_[k - 1] + s * (v_[k] - v_[k - 1]);
}

std::string TableHistory::describe() const {
  std::ostringstream os;
  os << source_ << ": " << t_.size() << " points, t = " << t_.front() << " .. " << t_.back() << " s";
  return os.str();
}

}  // namespace seismpm
