// 2D regions that bodies are filled from: rectangles, simple polygons (concave ones too) and
// polylines with a thickness. Pure geometry, no grid.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "types.hpp"

namespace seismpm {

class Region {
 public:
  virtual ~Region() = default;
  virtual bool contains(const Vec<2>& x) const = 0;
  virtual std::string describe() const = 0;
  // The outward unit normal of the contact face a rigid body made of this region presents near the
  // point x, where the region defines one: a one-sided polyline band faces its free side everywhere
  // (its far face is not a contact face). Zero where it does not (rectangles and polygons: their
  // faces' normals cancel across thin walls; contact then takes normals from the particles' volume).
  virtual Vec<2> outward_normal(const Vec<2>& x) const = 0;
  // Axis-aligned bounding box.
  const Vec<2>& lower() const { return lower_; }
  const Vec<2>& upper() const { return upper_; }

 protected:
  Vec<2> lower_ = Vec<2>::Zero(), upper_ = Vec<2>::Zero();
};

class RectangleRegion : public Region {
 public:
  // Throws InputError unless x0 < x1 and y0 < y1.
  RectangleRegion(double x0, double y0, double x1, double y1);
  bool contains(const Vec<2>& x) const override;
  Vec<2> outward_normal(const Vec<2>& x) const override;
  std::string describe() const override;
};

class PolygonRegion : public Region {
 public:
  // Throws InputError for fewer than 3 vertices, a zero area, or edges that cross.
  explicit PolygonRegion(std::vector<Vec<2>> vertices);
  bool contains(const Vec<2>& x) const override;  // even-odd rule; edges count as inside
  Vec<2> outward_normal(const Vec<2>& x) const override;
  std::string describe() const override;
  const std::vector<Vec<2>>& vertices() const { return vertices_; }
  double area() const;  // signed: > 0 counter-clockwise

 private:
  std::vector<Vec<2>> vertices_;
};

// The band of points within thickness/2 of a polyline (side "both"), or the strip of full thickness
// on its left or right (seen walking from the first point to the last).
class PolylineRegion : public Region {
 public:
  enum class Side { Both, Left, Right };
  PolylineRegion(std::vector<Vec<2>> points, double thickness, Side side);
  bool contains(const Vec<2>& x) const override;
  Vec<2> outward_normal(const Vec<2>& x) const override;
  std::string describe() const override;

 private:
  struct Nearest {
    double distance = std::numeric_limits<double>::infinity();
    double side = 0.0;             // > 0 on the left of the nearest segment
    Vec<2> left = Vec<2>::Zero();  // that segment's unit normal to its left
  };
  Nearest nearest(const Vec<2>& x) const;

  std::vector<Vec<2>> points_;
  double thickness_;
  Side side_;
};

// True when the closed polygon has two non-adjacent edges that intersect (or adjacent ones that overlap).
bool polygon_self_intersects(const std::vector<Vec<2>>& vertices);

}  // namespace seismpm
