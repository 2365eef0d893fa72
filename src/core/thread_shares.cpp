#include "thread_shares.hpp"

#include <algorithm>
#include <cmath>

namespace seismpm {

namespace {
// Each step moves a share this fraction of the way to the measured speeds: one step's timing (a page
// fault, an interrupt) moves it little, and the cores' speeds keep for hundreds of steps.
constexpr double kBlend = 0.15;
// Speeds within this fraction of an even split count as even: where the cores run alike, the shares
// stay equal instead of following the timing's noise.
constexpr double kDeadBand = 0.06;
}  // namespace

ThreadShares& ThreadShares::of(LoopKind kind) {
  static ThreadShares shares[kLoopKinds];
  return shares[static_cast<int>(kind)];
}

void ThreadShares::prepare_all(int threads) {
  for (int k = 0; k < kLoopKinds; ++k) of(static_cast<LoopKind>(k)).prepare(threads);
}

void ThreadShares::update_all() {
  for (int k = 0; k < kLoopKinds; ++k) of(static_cast<LoopKind>(k)).update();
}

void ThreadShares::prepare(int threads) {
  if (threads == threads_) return;
  threads_ = std::max(threads, 1);
  const int n = std::min(threads_, kMaxThreads);
  for (int t = 0; t < n; ++t) share_[t] = 1.0 / n, busy_[t] = Busy{};
  set_cumulative();
}

// Each thread's speed is the work it did over the time it took. The shares are held within [1/2, 3/2]
// of an even split, whatever the timing said.
void ThreadShares::update() {
  const int n = threads_;
  if (n <= 1 || n > kMaxThreads) return;
  bool timed = true;
  for (int t = 0; t < n; ++t) timed = timed && busy_[t].seconds > 0.0 && busy_[t].work > 0.0;
  if (timed) {
    double speed[kMaxThreads], total = 0.0;
    for (int t = 0; t < n; ++t) total += speed[t] = busy_[t].work / busy_[t].seconds;
    double sum = 0.0;
    for (int t = 0; t < n; ++t) {
      double target = speed[t] / total;
      if (std::abs(target * n - 1.0) < kDeadBand) target = 1.0 / n;
      share_[t] = std::clamp((1.0 - kBlend) * share_[t] + kBlend * target, 0.5 / n, 1.5 / n);
      sum += share_[t];
    }
    for (int t = 0; t < n; ++t) share_[t] /= sum;
    set_cumulative();
  }
  for (int t = 0; t < n; ++t) busy_[t] = Busy{};
}

void ThreadShares::set(const std::vector<double>& shares) {
  const int n = std::min(threads_, kMaxThreads);
  double sum = 0.0;
  for (int t = 0; t < n; ++t) sum += share_[t] = t < static_cast<int>(shares.size()) ? std::max(shares[t], 0.0) : 0.0;
  for (int t = 0; t < n; ++t) share_[t] = sum > 0.0 ? share_[t] / sum : 1.0 / n;
  set_cumulative();
}

void ThreadShares::set_cumulative() {
  const int n = std::min(threads_, kMaxThreads);
  const long long one = 1LL << kBits;
  double running = 0.0;
  cumulative_[0] = 0;
  for (int t = 1; t < n; ++t) {
    running += share_[t - 1];
    cumulative_[t] = std::clamp(static_cast<long long>(running * one), cumulative_[t - 1], one);
  }
  cumulative_[n] = one;
}

}  // namespace seismpm
