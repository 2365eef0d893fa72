#include "methods/limit_equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"
#include "methods/spencer.hpp"

namespace seismpm {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Bishop's m_alpha = cos(a) + sin(a) tan(phi) / F falls towards zero (and below) where the base of a
// deep circle rises steeply at the toe; the slice's base force N = W / m_alpha would then grow without
// bound. Following Whitman & Bailey (1967), m_alpha is held at 0.2 or more: it caps that force at five
// times the slice's weight instead of letting one slice decide the circle.
constexpr double kMinMAlpha = 0.2;

// The solver works on slopes that descend to the right: a slope that descends to the left is mirrored
// (x -> -x) on the way in and its results on the way out.
bool descends_left(const LemSlope& s) { return s.surface.front().y < s.surface.back().y; }

LemSlope mirrored(const LemSlope& s) {
  LemSlope m = s;
  std::reverse(m.surface.begin(), m.surface.end());
  for (auto& p : m.surface) p.x = -p.x;
  return m;
}

void validate(const LemSlope& s) {
  if (s.surface.size() < 2) throw InputError("limit equilibrium: the surface needs two points or more");
  for (std::size_t i = 1; i < s.surface.size(); ++i)
    if (!(s.surface[i].x > s.surface[i - 1].x))
      throw InputError("limit equilibrium: the surface's x must increase strictly");
  if (s.bands.empty()) throw InputError("limit equilibrium: no soil");
  for (const auto& b : s.bands)
    if (!(b.soil.unit_weight > 0) || b.soil.cohesion < 0 || b.soil.friction < 0 || b.soil.friction >= 90)
      throw InputError("limit equilibrium: soil needs unit_weight > 0, cohesion >= 0, friction in [0, 90)");
  for (const auto& p : s.surface)
    if (p.y < s.base) throw InputError("limit equilibrium: the surface lies below the firm base");
}

double ground(const LemSlope& s, double x) {
  const auto& p = s.surface;
  auto it = std::upper_bound(p.begin(), p.end(), x, [](double v, const LemPoint& q) { return v < q.x; });
  if (it == p.begin()) return p.front().y;
  if (it == p.end()) return p.back().y;
  const LemPoint& a = *(it - 1);
  const LemPoint& b = *it;
  return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
}

// The bands sorted from the top down; the lowest band extends downwards without end.
std::vector<LemBand> sorted_bands(const LemSlope& s) {
  auto b = s.bands;
  std::sort(b.begin(), b.end(), [](const LemBand& l, const LemBand& r) { return l.bottom > r.bottom; });
  return b;
}

const LemSoil& soil_at(const std::vector<LemBand>& bands, double y) {
  for (const auto& b : bands)
    if (y >= b.bottom) return b.soil;
  return bands.back().soil;
}

struct Column {
  double weight = 0;    // per unit width (N/m2)
  double centroid = 0;  // elevation of its centre of gravity
};

Column column(const std::vector<LemBand>& bands, double bottom, double top) {
  Column c;
  double moment = 0, upper = kInf;
  for (std::size_t k = 0; k < bands.size(); ++k) {
    const double lower = k + 1 == bands.size() ? -kInf : bands[k].bottom;
    const double lo = std::max(bottom, lower), hi = std::min(top, upper);
    if (hi > lo) {
      const double w = bands[k].soil.unit_weight * (hi - lo);
      c.weight += w;
      moment += w * 0.5 * (lo + hi);
    }
    upper = bands[k].bottom;
  }
  c.centroid = c.weight > 0 ? moment / c.weight : bottom;
  return c;
}

double arc(const LemCircle& c, double x) {
  const double d = c.r * c.r - (x - c.xc) * (x - c.xc);
  return c.yc - std::sqrt(std::max(d, 0.0));
}

// Where the circle's lower half crosses the surface, in increasing x.
std::vector<double> crossings(const LemSlope& s, const LemCircle& c) {
  std::vector<double> xs;
  for (std::size_t i = 1; i < s.surface.size(); ++i) {
    const LemPoint a = s.surface[i - 1], b = s.surface[i];
    const double dx = b.x - a.x, dy = b.y - a.y, fx = a.x - c.xc, fy = a.y - c.yc;
    const double qa = dx * dx + dy * dy, qb = 2 * (fx * dx + fy * dy), qc = fx * fx + fy * fy - c.r * c.r;
    const double disc = qb * qb - 4 * qa * qc;
    if (disc < 0) continue;
    for (double sign : {-1.0, 1.0}) {
      const double t = (-qb + sign * std::sqrt(disc)) / (2 * qa);
      if (t >= 0 && t <= 1 && a.y + t * dy <= c.yc) xs.push_back(a.x + t * dx);
    }
  }
  std::sort(xs.begin(), xs.end());
  return xs;
}

// Entry and exit of the sliding mass: the widest span between crossings where the ground lies above
// the arc. The polyline's ends count as crossings where the arc passes under them, so that a mass that
// would reach past an end (soil the slope does not describe) is found, and the circle rejected; so is
// one that enters the firm base.
std::optional<std::pair<double, double>> sliding_span(const LemSlope& s, const LemCircle& c) {
  auto xs = crossings(s, c);
  const double x0 = s.surface.front().x, x1 = s.surface.back().x;
  auto under = [&](double xe) { return std::abs(xe - c.xc) < c.r && arc(c, xe) < ground(s, xe); };
  if (under(x0)) xs.insert(xs.begin(), x0);
  if (under(x1)) xs.push_back(x1);
  std::optional<std::pair<double, double>> best;
  for (std::size_t i = 1; i < xs.size(); ++i) {
    const double xm = 0.5 * (xs[i - 1] + xs[i]);
    if (xs[i] - xs[i - 1] > 1e-9 * c.r && ground(s, xm) > arc(c, xm) &&
        (!best || xs[i] - xs[i - 1] > best->second - best->first))
      best = std::make_pair(xs[i - 1], xs[i]);
  }
  if (!best || (best->first == x0 && under(x0)) || (best->second == x1 && under(x1))) return std::nullopt;
  if (c.xc > best->first && c.xc < best->second && c.yc - c.r < s.base - 1e-9 * c.r) return std::nullopt;
  return best;
}

// One slice by its mid-line x: the height there times the width (the midpoint rule); c and phi of the
// band at the base's middle.
LemSlice slice_at(const std::vector<LemBand>& bands, const LemSlope& s, double xm, double yb, double width,
                  double sin_a, double cos_a) {
  const Column col = column(bands, yb, std::max(ground(s, xm), yb));
  const LemSoil& soil = soil_at(bands, yb);
  return {col.weight * width,
          col.centroid,
          xm,
          yb,
          width,
          sin_a,
          cos_a,
          soil.cohesion,
          std::tan(soil.friction * std::numbers::pi / 180)};
}

std::vector<LemSlice> slices_of(const LemSlope& s, const LemCircle& c, std::pair<double, double> span, int n) {
  const auto bands = sorted_bands(s);
  const double b = (span.second - span.first) / n;
  std::vector<LemSlice> out;
  out.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double xm = span.first + (i + 0.5) * b, yb = arc(c, xm);
    out.push_back(slice_at(bands, s, xm, yb, b, (c.xc - xm) / c.r, (c.yc - yb) / c.r));
  }
  return out;
}

// Bishop's simplified method: moment equilibrium about the centre, vertical equilibrium of each slice,
// interslice shear neglected. F appears on both sides (in m_alpha): fixed-point iteration from F = 1.
std::optional<double> bishop(const std::vector<LemSlice>& slices, const LemCircle& c, double kh,
                             const LemSettings& st) {
  double drive = 0;
  for (const auto& sl : slices) drive += sl.weight * (sl.sin_a + kh * (c.yc - sl.centroid) / c.r);
  if (!(drive > 0)) return std::nullopt;
  double f = 1;
  for (int it = 0; it < st.max_iterations; ++it) {
    double resist = 0;
    for (const auto& sl : slices) {
      const double m_alpha = std::max(sl.cos_a + sl.sin_a * sl.tan_phi / f, kMinMAlpha);
      resist += (sl.cohesion * sl.width + sl.weight * sl.tan_phi) / m_alpha;
    }
    const double next = resist / drive;
    if (std::abs(next - f) < st.tolerance) return next;
    f = next;
  }
  return f;
}

std::optional<double> of_method(const std::vector<LemSlice>& slices, const LemCircle& c, double kh,
                                const LemSettings& st) {
  if (st.method == LemMethod::bishop) return bishop(slices, c, kh, st);
  const auto r = spencer(slices, kh, st);
  if (!r) return std::nullopt;
  return r->fos;
}

std::optional<double> fos_right(const LemSlope& s, const LemCircle& c, double kh, const LemSettings& st) {
  if (!(c.r > 0)) return std::nullopt;
  const auto span = sliding_span(s, c);
  if (!span) return std::nullopt;
  return of_method(slices_of(s, c, *span, st.slices), c, kh, st);
}

double fos_or_inf(const LemSlope& s, const LemCircle& c, double kh, const LemSettings& st) {
  return fos_right(s, c, kh, st).value_or(kInf);
}

double distance_to_surface(const LemSlope& s, LemPoint p) {
  double d = kInf;
  for (std::size_t i = 1; i < s.surface.size(); ++i) {
    const LemPoint a = s.surface[i - 1], b = s.surface[i];
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double t = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    d = std::min(d, std::hypot(a.x + t * dx - p.x, a.y + t * dy - p.y));
  }
  return d;
}

struct Trial {
  double fos = kInf;
  LemCircle circle;
};

// The best radius for one centre: a sweep from the smallest cutting circle to base tangency, then a
// golden-section search between the best sample's neighbours.
Trial best_radius(const LemSlope& s, LemPoint centre, double kh, const LemSearch& se, const LemSettings& st) {
  Trial best;
  if (ground(s, centre.x) >= centre.y) return best;
  const double lo = std::max(distance_to_surface(s, centre), se.radius_min.value_or(0.0));
  const double hi = std::min(centre.y - s.base, se.radius_max.value_or(kInf));
  if (!(hi > lo)) return best;
  const int n = std::max(se.radii, 3);
  const double dr = (hi - lo) / n;
  int best_j = -1;
  for (int j = 1; j <= n; ++j) {
    const LemCircle c{centre.x, centre.y, lo + j * dr};
    const double f = fos_or_inf(s, c, kh, st);
    if (f < best.fos) best = {f, c}, best_j = j;
  }
  if (best_j < 0) return best;
  double a = lo + (best_j - 1) * dr, b = std::min(lo + (best_j + 1) * dr, hi);
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 40 && b - a > 1e-7 * hi; ++it) {
    const double r1 = b - g * (b - a), r2 = a + g * (b - a);
    const double f1 = fos_or_inf(s, {centre.x, centre.y, r1}, kh, st);
    const double f2 = fos_or_inf(s, {centre.x, centre.y, r2}, kh, st);
    if (f1 < best.fos) best = {f1, {centre.x, centre.y, r1}};
    if (f2 < best.fos) best = {f2, {centre.x, centre.y, r2}};
    (f1 < f2 ? b : a) = f1 < f2 ? r2 : r1;
  }
  return best;
}

// The automatic centre box: from one slope height behind the crest to one beyond the toe, from a
// quarter height above the toe to three heights above the crest, where critical centres of simple
// slopes lie.
std::pair<LemPoint, LemPoint> centre_box(const LemSlope& s, const LemSearch& se) {
  double ymin = kInf, ymax = -kInf;
  for (const auto& p : s.surface) ymin = std::min(ymin, p.y), ymax = std::max(ymax, p.y);
  const double h = ymax - ymin;
  if (!(h > 0)) throw InputError("limit equilibrium: the surface is flat (no slope)");
  double crest = s.surface.front().x, toe = s.surface.back().x;
  for (const auto& p : s.surface)
    if (p.y >= ymax - 0.01 * h) crest = p.x;
  for (auto it = s.surface.rbegin(); it != s.surface.rend(); ++it)
    if (it->y <= ymin + 0.01 * h) toe = it->x;
  if (toe < crest) std::swap(toe, crest);
  LemPoint lo{crest - h, ymin + 0.25 * h}, hi{toe + h, ymax + 3 * h};
  if (se.centre_lower) lo = *se.centre_lower;
  if (se.centre_upper) hi = *se.centre_upper;
  if (lo.x > hi.x) std::swap(lo.x, hi.x);
  if (lo.y > hi.y) std::swap(lo.y, hi.y);
  return {lo, hi};
}

Trial search_right(const LemSlope& s, double kh, const LemSearch& se, const LemSettings& st) {
  const auto [box_lo, box_hi] = centre_box(s, se);
  LemPoint lo = box_lo, hi = box_hi;
  const int n = std::max(se.centres, 2);
  Trial best;
  for (int level = 0; level < std::max(se.zoom_levels, 1); ++level) {
    const double dx = (hi.x - lo.x) / (n - 1), dy = (hi.y - lo.y) / (n - 1);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const Trial t = best_radius(s, {lo.x + i * dx, lo.y + j * dy}, kh, se, st);
        if (t.fos < best.fos) best = t;
      }
    if (best.fos == kInf) break;
    // The next grid spans 1.5 spacings either side of the best centre, inside the original box.
    lo = {std::max(best.circle.xc - 1.5 * dx, box_lo.x), std::max(best.circle.yc - 1.5 * dy, box_lo.y)};
    hi = {std::min(best.circle.xc + 1.5 * dx, box_hi.x), std::min(best.circle.yc + 1.5 * dy, box_hi.y)};
  }
  if (best.fos == kInf) throw InputError("limit equilibrium: no admissible slip circle in the search region");
  return best;
}

struct Oriented {
  LemSlope slope;
  bool flipped;
};

Oriented oriented(const LemSlope& s) {
  validate(s);
  if (!descends_left(s)) return {s, false};
  return {mirrored(s), true};
}

LemSearch mirrored(const LemSearch& se) {
  LemSearch m = se;
  // centre_box orders the corners again, so each corner is mirrored on its own.
  if (se.centre_lower) m.centre_lower = LemPoint{-se.centre_lower->x, se.centre_lower->y};
  if (se.centre_upper) m.centre_upper = LemPoint{-se.centre_upper->x, se.centre_upper->y};
  return m;
}

// ky: the kh at which fos_at(kh) = 1, bracketed by doubling from 0.1 and bisected; 0 when the slope
// fails without shaking.
template <class FosAt>
double yield_coefficient(double static_fos, FosAt fos_at, const LemSettings& st) {
  if (static_fos < 1) return 0;
  double lo = 0, hi = 0.1;
  while (fos_at(hi) >= 1 && hi < 10) lo = hi, hi *= 2;
  while (hi - lo > st.ky_tolerance) {
    const double mid = 0.5 * (lo + hi);
    (fos_at(mid) >= 1 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The elevation of a polyline at x (x inside its range).
double along(const std::vector<LemPoint>& p, double x) {
  LemSlope line;
  line.surface = p;
  return ground(line, x);
}

// The sliding mass over a given surface: the widest span where the ground lies above it. Ground and
// surface are both piecewise linear, so between the union of their vertices their difference is linear
// and its zeros are found exactly.
std::pair<double, double> surface_span(const LemSlope& s, const std::vector<LemPoint>& path) {
  if (path.size() < 2) throw InputError("limit equilibrium: the slip surface needs two points or more");
  for (std::size_t i = 1; i < path.size(); ++i)
    if (!(path[i].x > path[i - 1].x))
      throw InputError("limit equilibrium: the slip surface's x must increase strictly");
  std::vector<double> xs;
  for (const auto& p : path) xs.push_back(p.x);
  for (const auto& p : s.surface)
    if (p.x > path.front().x && p.x < path.back().x) xs.push_back(p.x);
  std::sort(xs.begin(), xs.end());
  auto depth = [&](double x) { return ground(s, x) - along(path, x); };
  const double tol = 1e-9 * (path.back().x - path.front().x);
  if (depth(xs.front()) > tol || depth(xs.back()) > tol)
    throw InputError("limit equilibrium: the slip surface must start and end at or above the ground");
  std::optional<std::pair<double, double>> best;
  double entry = 0;
  for (std::size_t i = 1; i < xs.size(); ++i) {
    const double d0 = depth(xs[i - 1]), d1 = depth(xs[i]);
    const double cross = xs[i - 1] + (xs[i] - xs[i - 1]) * d0 / (d0 - d1);
    if (d0 <= 0 && d1 > 0) entry = d0 == 0 ? xs[i - 1] : cross;
    if (d0 > 0 && d1 <= 0 && (!best || cross - entry > best->second - best->first)) best = {{entry, cross}};
  }
  if (!best || !(best->second - best->first > tol))
    throw InputError("limit equilibrium: the slip surface does not pass under the ground");
  return *best;
}

// Slices of equal width over a given surface; each base's inclination is that of the surface's segment
// under the slice's middle.
std::vector<LemSlice> slices_under(const LemSlope& s, const std::vector<LemPoint>& path, std::pair<double, double> span,
                                   int n) {
  const auto bands = sorted_bands(s);
  const double b = (span.second - span.first) / n;
  std::vector<LemSlice> out;
  out.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double xm = span.first + (i + 0.5) * b;
    auto it = std::upper_bound(path.begin(), path.end(), xm, [](double v, const LemPoint& q) { return v < q.x; });
    const LemPoint& p1 = *std::min(it, path.end() - 1);
    const LemPoint& p0 = *(std::min(it, path.end() - 1) - 1);
    const double len = std::hypot(p1.x - p0.x, p1.y - p0.y);
    out.push_back(slice_at(bands, s, xm, along(path, xm), b, (p0.y - p1.y) / len, (p1.x - p0.x) / len));
  }
  return out;
}

}  // namespace

std::vector<LemPoint> slip_surface(const LemSlope& slope, const LemCircle& c, int slices) {
  const auto [s, flipped] = oriented(slope);
  const LemCircle cr{flipped ? -c.xc : c.xc, c.yc, c.r};
  const auto span = sliding_span(s, cr);
  std::vector<LemPoint> out;
  if (!span) return out;
  for (int i = 0; i <= slices; ++i) {
    const double x = span->first + (span->second - span->first) * i / slices;
    out.push_back({flipped ? -x : x, arc(cr, x)});
  }
  if (flipped) std::reverse(out.begin(), out.end());
  return out;
}

std::optional<double> circle_fos(const LemSlope& slope, const LemCircle& c, double kh, const LemSettings& st) {
  const auto [s, flipped] = oriented(slope);
  return fos_right(s, {flipped ? -c.xc : c.xc, c.yc, c.r}, kh, st);
}

std::optional<double> bishop_fos(const LemSlope& slope, const LemCircle& c, double kh, const LemSettings& st) {
  LemSettings bishop = st;
  bishop.method = LemMethod::bishop;
  return circle_fos(slope, c, kh, bishop);
}

LemResult critical_circle(const LemSlope& slope, double kh, const LemSearch& search, const LemSettings& st) {
  const auto [s, flipped] = oriented(slope);
  const Trial t = search_right(s, kh, flipped ? mirrored(search) : search, st);
  LemResult r;
  r.fos = t.fos;
  r.circle = {flipped ? -t.circle.xc : t.circle.xc, t.circle.yc, t.circle.r};
  r.surface = slip_surface(slope, r.circle, st.slices);
  if (st.method == LemMethod::spencer) {
    const auto span = sliding_span(s, t.circle);
    const auto sol = span ? spencer(slices_of(s, t.circle, *span, st.slices), kh, st) : std::nullopt;
    if (sol) r.theta = -sol->theta * 180 / std::numbers::pi;
  }
  return r;
}

LemResult limit_equilibrium(const LemSlope& slope, double kh, const LemSearch& search, const LemSettings& st) {
  LemResult r = critical_circle(slope, kh, search, st);
  const double static_fos = kh == 0 ? r.fos : critical_circle(slope, 0, search, st).fos;
  // Each trial kh searches the circles anew, since the critical circle moves with kh.
  r.ky = yield_coefficient(
      static_fos, [&](double k) { return critical_circle(slope, k, search, st).fos; }, st);
  return r;
}

LemResult surface_equilibrium(const LemSlope& slope, const std::vector<LemPoint>& surface, double kh,
                              const LemSettings& st) {
  const auto [s, flipped] = oriented(slope);
  std::vector<LemPoint> path = surface;
  if (flipped) {
    std::reverse(path.begin(), path.end());
    for (auto& p : path) p.x = -p.x;
  }
  const auto span = surface_span(s, path);
  auto solve = [&](double k) {
    const auto sol = spencer(slices_under(s, path, span, st.slices), k, st);
    if (!sol) throw InputError("limit equilibrium: Spencer's method finds no solution on the given surface");
    return *sol;
  };
  const SpencerSolution at_kh = solve(kh);
  LemResult r;
  r.fos = at_kh.fos;
  r.theta = -at_kh.theta * 180 / std::numbers::pi;
  const double static_fos = kh == 0 ? r.fos : solve(0).fos;
  r.ky = yield_coefficient(
      static_fos, [&](double k) { return solve(k).fos; }, st);
  for (int i = 0; i <= st.slices; ++i) {
    const double x = span.first + (span.second - span.first) * i / st.slices;
    r.surface.push_back({flipped ? -x : x, along(path, x)});
  }
  if (flipped) std::reverse(r.surface.begin(), r.surface.end());
  return r;
}

}  // namespace seismpm
