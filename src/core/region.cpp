#include "region.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "error.hpp"

namespace seismpm {

namespace {

double cross(const Vec<2>& a, const Vec<2>& b) { return a[0] * b[1] - a[1] * b[0]; }

// Orientation of c relative to the line a -> b, with a tolerance relative to the segment lengths.
int orientation(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {
  const double v = cross(b - a, c - a);
  const double tol = 1e-12 * (b - a).norm() * (c - a).norm();
  return (v > tol) - (v < -tol);
}

bool on_segment(const Vec<2>& a, const Vec<2>& b, const Vec<2>& c) {  // c collinear with a-b
  return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= c[1] &&
         c[1] <= std::max(a[1], b[1]);
}

bool segments_intersect(const Vec<2>& p1, const Vec<2>& p2, const Vec<2>& q1, const Vec<2>& q2) {
  const int o1 = orientation(p1, p2, q1), o2 = orientation(p1, p2, q2);
  const int o3 = orientation(q1, q2, p1), o4 = orientation(q1, q2, p2);
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) return true;
  if (o1 == 0 && on_segment(p1, p2, q1)) return true;
  if (o2 == 0 && on_segment(p1, p2, q2)) return true;
  if (o3 == 0 && on_segment(q1, q2, p1)) return true;
  if (o4 == 0 && on_segment(q1, q2, p2)) return true;
  return false;
}

void bounding_box(const std::vector<Vec<2>>& pts, double pad, Vec<2>& lo, Vec<2>& hi) {
  lo = Vec<2>::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo.array() -= pad;
  hi.array() += pad;
}

std::string point(const Vec<2>& p) {
  std::ostringstream os;
  os << "{" << p[0] << ", " << p[1] << "}";
  return os.str();
}

}  // namespace

bool polygon_self_intersects(const std::vector<Vec<2>>& v) {
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<2>&a = v[i], &b = v[(i + 1) % n];
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec<2>&c = v[j], &d = v[(j + 1) % n];
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) {
        // Adjacent edges share a vertex; they may not fold back onto each other.
        const Vec<2>& shared = j == i + 1 ? b : a;
        const Vec<2>& e1 = j == i + 1 ? a : b;
        const Vec<2>& e2 = j == i + 1 ? d : c;
        if (orientation(e1, shared, e2) == 0 && (e1 - shared).dot(e2 - shared) > 0) return true;
        continue;
      }
      if (segments_intersect(a, b, c, d)) return true;
    }
  }
  return false;
}

RectangleRegion::RectangleRegion(double x0, double y0, double x1, double y1) {
  if (!(x1 > x0) || !(y1 > y0) || !std::isfinite(x0 + y0 + x1 + y1))
    throw InputError("rectangle needs x0 < x1 and y0 < y1 (given {x0, y0, x1, y1})");
  lower_ = Vec<2>(x0, y0);
  upper_ = Vec<2>(x1, y1);
}

bool RectangleRegion::contains(const Vec<2>& x) const {
  return x[0] >= lower_[0] && x[0] <= upper_[0] && x[1] >= lower_[1] && x[1] <= upper_[1];
}

Vec<2> RectangleRegion::outward_normal(const Vec<2>&) const { return Vec<2>::Zero(); }

std::string RectangleRegion::describe() const { return "rectangle " + point(lower_) + " to " + point(upper_); }

PolygonRegion::PolygonRegion(std::vector<Vec<2>> vertices) : vertices_(std::move(vertices)) {
  if (vertices_.size() >= 2 && (vertices_.front() - vertices_.back()).norm() == 0.0) vertices_.pop_back();
  if (vertices_.size() < 3) throw InputError("polygon needs at least 3 points");
  for (const auto& p : vertices_)
    if (!p.allFinite()) throw InputError("polygon has a non-finite coordinate");
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    if ((vertices_[i] - vertices_[(i + 1) % vertices_.size()]).norm() == 0.0)
      throw InputError("polygon repeats point " + std::to_string(i + 1) + " " + point(vertices_[i]));
  if (polygon_self_intersects(vertices_)) throw InputError("polygon edges cross each other (self-intersecting)");
  if (std::abs(area()) == 0.0) throw InputError("polygon has zero area");
  bounding_box(vertices_, 0.0, lower_, upper_);
}

double PolygonRegion::area() const {
  double a = 0.0;
  for (std::size_t i = 0; i < vertices_.size(); ++i) a += cross(vertices_[i], vertices_[(i + 1) % vertices_.size()]);
  return 0.5 * a;
}

bool PolygonRegion::contains(const Vec<2>& x) const {
  bool inside = false;
  const std::size_t n = vertices_.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec<2>&a = vertices_[i], &b = vertices_[j];
    // On an edge: inside.
    if (orientation(a, b, x) == 0 && on_segment(a, b, x)) return true;
    if ((a[1] > x[1]) != (b[1] > x[1]) && x[0] < (b[0] - a[0]) * (x[1] - a[1]) / (b[1] - a[1]) + a[0]) inside = !inside;
  }
  return inside;
}

Vec<2> PolygonRegion::outward_normal(const Vec<2>&) const { return Vec<2>::Zero(); }

std::string PolygonRegion::describe() const {
  return "polygon of " + std::to_string(vertices_.size()) + " points, area " + std::to_string(std::abs(area()));
}

PolylineRegion::PolylineRegion(std::vector<Vec<2>> points, double thickness, Side side)
    : points_(std::move(points)), thickness_(thickness), side_(side) {
  if (points_.size() < 2) throw InputError("polyline needs at least 2 points");
  if (!(thickness > 0.0) || !std::isfinite(thickness)) throw InputError("polyline thickness must be > 0 (m)");
  for (std::size_t i = 0; i + 1 < points_.size(); ++i)
    if ((points_[i + 1] - points_[i]).norm() == 0.0)
      throw InputError("polyline repeats point " + std::to_string(i + 1));
  bounding_box(points_, side == Side::Both ? 0.5 * thickness : thickness, lower_, upper_);
}

PolylineRegion::Nearest PolylineRegion::nearest(const Vec<2>& x) const {
  // The nearest segment decides the side, so a point is on one side of the whole line.
  Nearest n;
  for (std::size_t i = 0; i + 1 < points_.size(); ++i) {
    const Vec<2> a = points_[i], d = points_[i + 1] - points_[i];
    const double s = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const double dist = (x - (a + s * d)).norm();
    if (dist < n.distance - 1e-15) {
      n.distance = dist;
      n.side = cross(d, x - a);
      n.left = Vec<2>(-d[1], d[0]).normalized();
    }
  }
  return n;
}

bool PolylineRegion::contains(const Vec<2>& x) const {
  const double reach = side_ == Side::Both ? 0.5 * thickness_ : thickness_;
  const Nearest n = nearest(x);
  if (n.distance > reach * (1.0 + 1e-12)) return false;
  if (side_ == Side::Both || n.distance == 0.0) return true;
  return side_ == Side::Left ? n.side > 0.0 : n.side < 0.0;
}

Vec<2> PolylineRegion::outward_normal(const Vec<2>& x) const {
  // A one-sided band's contact face is the line itself: every particle of it faces the free side.
  switch (side_) {
    case Side::Right:
      return nearest(x).left;
    case Side::Left:
      return -nearest(x).left;
    case Side::Both:
      break;
  }
  return Vec<2>::Zero();
}

std::string PolylineRegion::describe() const {
  return "polyline of " + std::to_string(points_.size()) + " points, thickness " + std::to_string(thickness_);
}

}  // namespace seismpm
