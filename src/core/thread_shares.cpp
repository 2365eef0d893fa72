#include "thread_shares.hpp"

#include <algorithm>
#include <cmath>

namespace seismpm {

namespace {
// Each step moves a share this fraction of the way to the measured speeds.
constexpr double kBlend = 0.3;
// Of the last kWindow steps, this many must find a thread faster (or slower) than an even split for
// its share to grow (or shrink), and then only as far as all of those reach (the least of them for a
// faster thread, the greatest for a slower one). A thread that another program preempts now and then
// is slow in some loops and not in others, and a share taken from it in every loop made the other
// thread the slow one in the rest (mc-sand, 2 threads, a loop busy 30 % of each millisecond on one
// core: about 8 % slower following each step's speeds, 5 % by the median of 9 steps); a core that is
// slower throughout is slower in every step.
constexpr int kAgreeing = 7;
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
  measured_ = 0;
  set_cumulative();
}

// Each thread's speed is the work it did over the time it took, kept as its proportion of the team's
// for the last kWindow timed steps. The shares move toward the proportions that kAgreeing steps reach,
// and are clamped to [1/2, 3/2] of an even split before they are normalised, whatever the timing said
// (for two threads that keeps them within those bounds; for more, about).
void ThreadShares::update() {
  const int n = threads_;
  if (n <= 1 || n > kMaxThreads) return;
  bool timed = true;
  for (int t = 0; t < n; ++t) timed = timed && busy_[t].seconds > 0.0 && busy_[t].work > 0.0;
  if (timed) {
    double speed[kMaxThreads], total = 0.0;
    for (int t = 0; t < n; ++t) total += speed[t] = busy_[t].work / busy_[t].seconds;
    for (int t = 0; t < n; ++t) proportion_[t][measured_ % kWindow] = speed[t] / total;
    measured_ = measured_ + 1 < 2 * kWindow ? measured_ + 1 : kWindow;  // full from kWindow on; the slot cycles
  }
  for (int t = 0; t < n; ++t) busy_[t] = Busy{};
  if (measured_ < kWindow) return;
  double agreed[kMaxThreads], total = 0.0;
  for (int t = 0; t < n; ++t) {
    auto window = proportion_[t];
    std::sort(window.begin(), window.end());
    // Sorted, the kAgreeing-th fastest and the kAgreeing-th slowest; even unless one of them says so.
    const double fast = window[kWindow - kAgreeing], slow = window[kAgreeing - 1];
    total += agreed[t] = fast > 1.0 / n ? fast : slow < 1.0 / n ? slow : 1.0 / n;
  }
  double sum = 0.0;
  for (int t = 0; t < n; ++t) {
    double target = agreed[t] / total;
    if (std::abs(target * n - 1.0) < kDeadBand) target = 1.0 / n;
    share_[t] = std::clamp((1.0 - kBlend) * share_[t] + kBlend * target, 0.5 / n, 1.5 / n);
    sum += share_[t];
  }
  for (int t = 0; t < n; ++t) share_[t] /= sum;
  set_cumulative();
}

void ThreadShares::set(const std::vector<double>& shares) {
  const int n = std::min(threads_, kMaxThreads);
  double sum = 0.0;
  for (int t = 0; t < n; ++t) {
    const double v = t < static_cast<int>(shares.size()) ? shares[t] : 0.0;
    sum += share_[t] = std::isfinite(v) && v > 0.0 ? v : 0.0;
  }
  const bool usable = std::isfinite(sum) && sum > 0.0;  // else even shares
  for (int t = 0; t < n; ++t) share_[t] = usable ? share_[t] / sum : 1.0 / n;
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
