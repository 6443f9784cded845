#pragma once
// A material frame field: the orthonormal, right-handed frame Q = [f s n] (columns:
// fibre, sheet, sheet-normal) at any point of the reference mesh. Point models read
// their anisotropy axes from it; the macro side rotates Z̄ into it.
//
// Implementations (one idea per file):
//  - AnalyticFrame: constant, or rotating about an axis with a coordinate (frame kinds
//    "constant", "rotating");
//  - FileFrame: per-element or per-node vectors from a Gmsh view or a CSV ("file");
//  - RuleFrame: the Laplace–Dirichlet rule-based method of Bayer et al. 2012 ("rule").
#include "common/tensor9.h"

#include <array>

namespace fe2 {

/// Barycentric coordinates λ0..λ3 of a point with respect to the 4 vertices of a tet
/// (TetMesh::tets order); they sum to 1.
using Bary = std::array<double, 4>;

inline constexpr Bary kCentroid = {0.25, 0.25, 0.25, 0.25};

class FrameField {
 public:
  virtual ~FrameField() = default;
  /// Q = [f s n] at the point of element e with barycentric coordinates `lambda` and
  /// reference position `X` (both given: a field uses whichever it is defined by).
  virtual Mat3 at(int e, const Bary& lambda, const Vec3& X) const = 0;
};

/// [f s n] from a fibre and a sheet that need not be orthonormal: f normalized, s made
/// orthogonal to f by Gram–Schmidt and normalized, n = f × s. Returns false (leaving Q
/// alone) if f or the orthogonal part of s is shorter than `tiny`.
inline bool orthonormal_frame(const Vec3& f, const Vec3& s, Mat3& Q, double tiny = 1e-12) {
  const double fl = f.norm();
  if (!(fl > tiny)) return false;
  const Vec3 fu = f / fl;
  const Vec3 so = s - s.dot(fu) * fu;
  const double sl = so.norm();
  if (!(sl > tiny)) return false;
  Q.col(0) = fu;
  Q.col(1) = so / sl;
  Q.col(2) = fu.cross(Q.col(1));
  return true;
}

}  // namespace fe2
