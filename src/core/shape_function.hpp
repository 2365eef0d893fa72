// Shape functions on a uniform grid, per axis in cell units (h = 1), combined as tensor products.
// Linear (tent) touches 2 nodes per axis; uGIMP (a particle of fixed half-width l = 1 / (2 ppc) convolved
// with the tent: continuous gradients, so particles crossing cell edges make no force noise) touches 3.
// Each kind gives the first node of its stencil and the weights and derivatives at K consecutive
// nodes from a given first node.
#pragma once

#include <cmath>
#include <string_view>

namespace seismpm {

enum class ShapeKind { Linear, Gimp };

inline std::string_view to_string(ShapeKind k) { return k == ShapeKind::Linear ? "linear" : "gimp"; }

// floor(x), exactly. std::floor vectorises (as a rounding instruction, on AVX2 and AVX-512 alike) once
// floating point may not trap (-fno-trapping-math); the truncating conversion used before vectorises only
// where AVX-512 converts doubles to 64-bit integers, and on AVX2 machines it left make_stencils scalar.
inline double floor_small(double x) { return std::floor(x); }

// Tent function N(r) = 1 - |r|.
struct LinearShape {
  static constexpr int K = 2;
  // A particle in cell c reaches nodes c + kReachLo .. c + kReachHi along each axis.
  static constexpr int kReachLo = 0, kReachHi = 1;

  static int first_node(double xi, double l) { return static_cast<int>(first_node_value(xi, l)); }
  static double first_node_value(double xi, double /*l*/) { return floor_small(xi); }
  // Valid for first <= xi <= first + 1 (the particle's cell).
  static void eval(double xi, double l, int first, double* w, double* dw) { eval_regular(xi - first, l, w, dw); }
  // Every first node make_stencil picks gives the one formula.
  static bool regular(double /*a0*/, double /*l*/) { return true; }
  // With a0 = xi - first.
  static void eval_regular(double a0, double /*l*/, double* w, double* dw) {
    w[0] = 1.0 - a0;
    w[1] = a0;
    dw[0] = -1.0;
    dw[1] = 1.0;
  }
};

// max(x, 0), exactly (x + |x| doubles x or cancels), without the branch std::max and the conditional
// operator compile to.
inline double positive_part(double x) { return 0.5 * (x + std::abs(x)); }

// uGIMP: the tent convolved with the particle's characteristic function of half-width l
// (cell units, 0 < l <= 1/2, kept at its initial size).
struct GimpShape {
  static constexpr int K = 3;
  // A particle in cell c reaches nodes c - 1 .. c + 2 along each axis: three of them, which three
  // depending on where in the cell it lies.
  static constexpr int kReachLo = -1, kReachHi = 2;

  // Value and derivative at r, by piece; inv_2l = 1 / 2l (one division per axis, not one per node).
  static void piece(double r, double l, double inv_2l, double& w, double& dw) {
    const double a = std::abs(r), s = r < 0.0 ? -1.0 : 1.0;
    if (a < l) {
      w = 1.0 - (r * r + l * l) * inv_2l;
      dw = -2.0 * r * inv_2l;
    } else if (a < 1.0 - l) {
      w = 1.0 - a;
      dw = -s;
    } else if (a < 1.0 + l) {
      const double b = 1.0 + l - a;
      w = 0.5 * b * b * inv_2l;
      dw = -s * b * inv_2l;
    } else {
      w = dw = 0.0;
    }
  }
  static double value(double r, double l) {
    double w, dw;
    piece(r, l, 0.5 / l, w, dw);
    return w;
  }
  static double derivative(double r, double l) {
    double w, dw;
    piece(r, l, 0.5 / l, w, dw);
    return dw;
  }

  // Support is |xi - node| < 1 + l; with l <= 1/2 it holds at most 3 nodes.
  static int first_node(double xi, double l) { return static_cast<int>(first_node_value(xi, l)); }
  // The same as a double (for loops that keep every value a double, so that they vectorise), for
  // |xi| < 2^52.
  static double first_node_value(double xi, double l) { return floor_small(xi - 1.0 - l) + 1.0; }
  // With the first node at distance a0 = xi - first in [l, 1 + l) (always, but where a grid without
  // ghost layers clips the stencil), each node's pieces join into one branch-free formula: the
  // first node's linear piece plus e^2 / 4l past 1 - l (its tail), the second's linear piece less
  // q^2 / 2l within l of it (its centre), the third's tail. Choosing the piece by comparisons
  // mispredicted where particles lie at random in their cells: the stencil pass ran 11 % slower.
  static void eval(double xi, double l, int first, double* w, double* dw) {
    const double a0 = xi - first;
    if (!regular(a0, l)) {  // clipped: piece by piece
      const double inv_2l = 0.5 / l;
      for (int k = 0; k < K; ++k) piece(xi - (first + k), l, inv_2l, w[k], dw[k]);
      return;
    }
    eval_regular(a0, l, w, dw);
  }
  // True where the first node lies at a0 = xi - first in [l, 1 + l): eval_regular's range.
  static bool regular(double a0, double l) { return (a0 >= l) & (a0 < 1.0 + l); }
  static void eval_regular(double a0, double l, double* w, double* dw) {
    const double inv_2l = 0.5 / l;
    const double inv_4l = 0.5 * inv_2l;
    const double e = positive_part(a0 - (1.0 - l));  // how far node 0 lies into its tail
    w[0] = 1.0 - a0 + e * e * inv_4l;
    dw[0] = -1.0 + e * inv_2l;
    const double r1 = a0 - 1.0, a1 = std::abs(r1);
    const double q = positive_part(l - a1);  // how far the particle's domain covers node 1
    w[1] = 1.0 - a1 - q * q * inv_2l;
    dw[1] = std::copysign(1.0 - 2.0 * q * inv_2l, -r1);
    const double b = positive_part(l - 1.0 + a0);  // 1 + l - (2 - a0): node 2's tail
    w[2] = b * b * inv_4l;
    dw[2] = b * inv_2l;
  }
};

}  // namespace seismpm
