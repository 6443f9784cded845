#pragma once
// Frames given by a formula of the reference position X (frame kinds "constant" and
// "rotating"): (f0, s0), rotated about `axis` by an angle that varies linearly with
// X·coordinate between c0 and c1 (clamped outside), a simple transmural helix rule.
#include "common/fibres/FrameField.h"

namespace fe2 {

class AnalyticFrame : public FrameField {
 public:
  Vec3 fibre = Vec3::UnitX();  ///< f0, unit
  Vec3 sheet = Vec3::UnitY();  ///< s0, unit and orthogonal to f0
  bool rotating = false;
  Vec3 axis = Vec3::UnitZ();        ///< unit rotation axis
  Vec3 coordinate = Vec3::UnitY();  ///< unit direction along which the angle varies
  double c0 = 0, c1 = 1, angle0 = 0, angle1 = 0;  ///< angles in radians

  /// Q = [f s n] at X: f = R(θ(X)) f0, s = R(θ(X)) s0, n = f × s, with
  /// θ(X) = angle0 + ξ (angle1 − angle0), ξ = clamp((X·coordinate − c0)/(c1 − c0), 0, 1).
  Mat3 at(const Vec3& X) const;
  Mat3 at(int, const Bary&, const Vec3& X) const override { return at(X); }
};

}  // namespace fe2
