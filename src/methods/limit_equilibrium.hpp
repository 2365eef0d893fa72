// Limit equilibrium of a 2D slope: Bishop's simplified method or Spencer's method of slices on circular
// slip surfaces, a search for the critical circle, Spencer's method on a given (non-circular) slip
// surface, and the pseudo-static yield coefficient ky. No Lua, no model: the slope is a ground-surface
// polyline over soil in horizontal bands, above a firm base no circle may enter.
#pragma once

#include <optional>
#include <vector>

namespace seismpm {

struct LemPoint {
  double x = 0, y = 0;
};

struct LemSoil {
  double unit_weight = 0;  // N/m3
  double cohesion = 0;     // Pa
  double friction = 0;     // degrees
};

// A horizontal band of soil: it holds from `bottom` up to the next band's bottom (the top band up to the
// surface). Bands are given in any order.
struct LemBand {
  double bottom = 0;  // m
  LemSoil soil;
};

struct LemSlope {
  std::vector<LemPoint> surface;  // ground surface, x strictly increasing
  std::vector<LemBand> bands;     // at least one
  double base = 0;                // elevation of the firm base (m)
};

struct LemCircle {
  double xc = 0, yc = 0, r = 0;
};

struct LemSearch {
  std::optional<LemPoint> centre_lower, centre_upper;  // centre box; automatic when absent
  std::optional<double> radius_min, radius_max;        // narrows the radii from cutting to base tangency
  int centres = 15;                                    // grid points per direction, per zoom level
  int zoom_levels = 5;                                 // centre grid shrunk around the best centre
  int radii = 16;                                      // radii sampled per centre before refining
};

enum class LemMethod { bishop, spencer };

struct LemSettings {
  LemMethod method = LemMethod::bishop;
  int slices = 80;
  double tolerance = 1e-6;  // on the factor of safety between Bishop iterations
  int max_iterations = 200;
  double ky_tolerance = 1e-4;  // g
};

struct LemResult {
  double fos = 0;
  LemCircle circle;
  std::vector<LemPoint> surface;  // the slip surface, entry to exit
  double ky = 0;                  // kh at which the minimum FoS is 1 (0 when the static FoS is below 1)
  // Spencer: the interslice forces' inclination (degrees), positive where an upslope slice pushes its
  // downslope neighbour down towards the toe (the usual case); Bishop: 0.
  double theta = 0;
};

// Bishop's factor of safety of one circle under a horizontal seismic coefficient kh; nullopt when the
// circle does not cut the slope, enters the base, or leaves the surface polyline's ends.
std::optional<double> bishop_fos(const LemSlope& slope, const LemCircle& c, double kh, const LemSettings& s = {});

// The circle of least factor of safety under kh. Throws InputError for a malformed slope and when no
// searched circle is admissible.
LemResult critical_circle(const LemSlope& slope, double kh, const LemSearch& search = {}, const LemSettings& s = {});

// critical_circle at kh, plus ky by bisection on kh (each trial a new search).
LemResult limit_equilibrium(const LemSlope& slope, double kh, const LemSearch& search = {}, const LemSettings& s = {});

// The factor of safety (settings' method) of one circle under kh; nullopt as for bishop_fos.
std::optional<double> circle_fos(const LemSlope& slope, const LemCircle& c, double kh, const LemSettings& s = {});

// Spencer's method on a given slip surface (a polyline, x strictly increasing, that starts and ends at
// or above the ground): the mass is the widest span where the ground lies above it. fos, theta and ky
// (bisection on kh for this surface); surface: the part under the mass. Throws InputError for a
// surface that does not cut the slope or ends underground.
LemResult surface_equilibrium(const LemSlope& slope, const std::vector<LemPoint>& surface, double kh,
                              const LemSettings& s = {});

// The slip surface of a circle through the slope (entry to exit, slices + 1 points); empty if none.
std::vector<LemPoint> slip_surface(const LemSlope& slope, const LemCircle& c, int slices);

}  // namespace seismpm
