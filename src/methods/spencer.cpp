#include "methods/spencer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace seismpm {

namespace {

// As for Bishop's m_alpha (Whitman & Bailey 1967): the slice's divisor cos(a + theta) (1 + tan(a +
// theta) tan(phi) / F) is held at 0.2 or more, so that one steep slice at the toe cannot take an
// unbounded base force.
constexpr double kMinDivisor = 0.2;

// The net interslice force Q = Z_left - Z_right of a slice (along theta), from its equilibrium along
// and normal to the base with the base shear S = (c l + N tan phi) / F:
//   Q = ([c l + W (cos a - kh sin a) tan phi] / F - W (sin a + kh cos a)) / (cos(a+t) + sin(a+t) tan phi / F).
struct SliceTerms {
  double resist, drive, c, s;  // c l + W (cos a - kh sin a) tan phi; W (sin a + kh cos a); cos, sin of a + theta
};

SliceTerms terms(const LemSlice& sl, double kh, double theta) {
  const double length = sl.width / sl.cos_a;
  const double cs = sl.cos_a * std::cos(theta) - sl.sin_a * std::sin(theta);
  const double sn = sl.sin_a * std::cos(theta) + sl.cos_a * std::sin(theta);
  return {sl.cohesion * length + sl.weight * (sl.cos_a - kh * sl.sin_a) * sl.tan_phi,
          sl.weight * (sl.sin_a + kh * sl.cos_a), cs, sn};
}

double divisor(const SliceTerms& t, const LemSlice& sl, double f) {
  return std::max(t.c + t.s * sl.tan_phi / f, kMinDivisor);
}

// The factor of safety from force equilibrium (sum of Q = 0) at one theta: F = sum(R / m) / sum(D / m),
// m depending on F: fixed-point iteration from `start`.
std::optional<double> force_fos(const std::vector<LemSlice>& slices, double kh, double theta, double start,
                                const LemSettings& st) {
  std::vector<SliceTerms> t;
  t.reserve(slices.size());
  for (const auto& sl : slices) t.push_back(terms(sl, kh, theta));
  double f = start;
  for (int it = 0; it < st.max_iterations; ++it) {
    double resist = 0, drive = 0;
    for (std::size_t i = 0; i < slices.size(); ++i) {
      const double m = divisor(t[i], slices[i], f);
      resist += t[i].resist / m;
      drive += t[i].drive / m;
    }
    if (!(drive > 0)) return std::nullopt;
    const double next = resist / drive;
    if (std::abs(next - f) < st.tolerance) return next;
    f = next;
  }
  return f;
}

// The moment residual of the whole mass at (F, theta): each Q through its base's middle, the seismic
// force kh W at the centre of gravity; about the first base's middle (with sum Q = 0 any point gives
// the same):  sum Q (x sin t - y cos t) + kh sum W (y_g - y_b), divided by sum W times the span.
double moment_residual(const std::vector<LemSlice>& slices, double kh, double theta, double f) {
  const double x0 = slices.front().x, y0 = slices.front().base_y;
  double m = 0, scale = 0;
  for (const auto& sl : slices) {
    const SliceTerms t = terms(sl, kh, theta);
    const double q = (t.resist / f - t.drive) / divisor(t, sl, f);
    m += q * ((sl.x - x0) * std::sin(theta) - (sl.base_y - y0) * std::cos(theta)) +
         kh * sl.weight * (sl.centroid - sl.base_y);
    scale += sl.weight;
  }
  return m / (scale * (slices.back().x - x0 + slices.front().width));
}

struct Trial {
  double theta, fos, residual;
};

std::optional<Trial> trial(const std::vector<LemSlice>& slices, double kh, double theta, double start,
                           const LemSettings& st) {
  const auto f = force_fos(slices, kh, theta, start, st);
  if (!f || !(*f > 0)) return std::nullopt;
  return Trial{theta, *f, moment_residual(slices, kh, theta, *f)};
}

}  // namespace

std::optional<SpencerSolution> spencer(const std::vector<LemSlice>& slices, double kh, const LemSettings& st) {
  if (slices.empty()) return std::nullopt;
  const double deg = std::numbers::pi / 180;
  // Bracket the inclination: from theta = 0 outwards in 5-degree steps, towards either side.
  auto a = trial(slices, kh, 0, 1, st);
  if (!a) return std::nullopt;
  std::optional<Trial> b;
  for (int k = 1; k <= 16 && !b; ++k)
    for (double sign : {1.0, -1.0}) {
      const double theta = sign * 5 * k * deg;
      if (theta <= -60 * deg || theta >= 80 * deg) continue;
      const auto t = trial(slices, kh, theta, a->fos, st);
      if (t && (t->residual == 0 || (t->residual > 0) != (a->residual > 0))) {
        // The nearest pair around the sign change: the previous step on this side and this one.
        const auto inner = trial(slices, kh, sign * 5 * (k - 1) * deg, a->fos, st);
        if (inner) a = inner;
        b = t;
        break;
      }
    }
  if (!b) return a->residual == 0 ? std::optional<SpencerSolution>({a->fos, 0}) : std::nullopt;
  // Regula falsi with the Illinois modification on the residual.
  double side = 0;
  for (int it = 0; it < 100; ++it) {
    if (std::abs(b->theta - a->theta) < 1e-9 || b->residual == 0) break;
    const double theta = b->theta - b->residual * (b->theta - a->theta) / (b->residual - a->residual);
    const auto c = trial(slices, kh, theta, b->fos, st);
    if (!c) return std::nullopt;
    if (std::abs(c->fos - b->fos) < st.tolerance && std::abs(c->theta - b->theta) < 1e-7) {
      b = c;
      break;
    }
    if ((c->residual > 0) == (b->residual > 0)) {
      a->residual *= side == 1 ? 0.5 : 1;
      side = 1;
    } else {
      a = b;
      side = -1;
    }
    b = c;
  }
  return SpencerSolution{b->fos, b->theta};
}

}  // namespace seismpm
