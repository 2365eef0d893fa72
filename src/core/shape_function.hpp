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

// Tent function N(r) = 1 - |r|.
struct LinearShape {
  static constexpr int K = 2;

  static int first_node(double xi, double /*l*/) { return static_cast<int>(std::floor(xi)); }
  // Valid for first <= xi <= first + 1 (the particle's cell).
  static void eval(double xi, double /*l*/, int first, double* w, double* dw) {
    const double r = xi - first;
    w[0] = 1.0 - r;
    w[1] = r;
    dw[0] = -1.0;
    dw[1] = 1.0;
  }
};

// uGIMP: the tent convolved with the particle's characteristic function of half-width l
// (cell units, 0 < l <= 1/2, kept at its initial size).
struct GimpShape {
  static constexpr int K = 3;

  static double value(double r, double l) {
    const double a = std::abs(r);
    if (a < l) return 1.0 - (r * r + l * l) / (2.0 * l);
    if (a < 1.0 - l) return 1.0 - a;
    if (a < 1.0 + l) {
      const double b = 1.0 + l - a;
      return b * b / (4.0 * l);
    }
    return 0.0;
  }

  static double derivative(double r, double l) {
    const double a = std::abs(r);
    const double s = r < 0.0 ? -1.0 : 1.0;
    if (a < l) return -r / l;
    if (a < 1.0 - l) return -s;
    if (a < 1.0 + l) return -s * (1.0 + l - a) / (2.0 * l);
    return 0.0;
  }

  // Support is |xi - node| < 1 + l; with l <= 1/2 it holds at most 3 nodes.
  static int first_node(double xi, double l) { return static_cast<int>(std::floor(xi - 1.0 - l)) + 1; }
  static void eval(double xi, double l, int first, double* w, double* dw) {
    for (int k = 0; k < K; ++k) {
      // value() and derivative() in one pass over the pieces.
      const double r = xi - (first + k), a = std::abs(r), s = r < 0.0 ? -1.0 : 1.0;
      if (a < l) {
        w[k] = 1.0 - (r * r + l * l) / (2.0 * l);
        dw[k] = -r / l;
      } else if (a < 1.0 - l) {
        w[k] = 1.0 - a;
        dw[k] = -s;
      } else if (a < 1.0 + l) {
        const double b = 1.0 + l - a;
        w[k] = b * b / (4.0 * l);
        dw[k] = -s * b / (2.0 * l);
      } else {
        w[k] = dw[k] = 0.0;
      }
    }
  }
};

}  // namespace seismpm
