#pragma once
// Material frames interpolated as rotations, modulo the frame's symmetries: a frame
// [f s n] turned by π about one of its own axes — (f, −s, −n), (−f, s, −n), (−f, −s, n) —
// has the same fibre, sheet and normal lines, so it is the same material frame.
//  - bislerp: Bayer, Blake, Plank, Trayanova, "A novel rule-based algorithm for
//    assigning myocardial fiber orientation to computational heart models", Ann.
//    Biomed. Eng. 40 (2012) 2243–2254: quaternion slerp from the symmetry-equivalent of
//    Qa closest to Qb (RuleFrame's two-cavity rule);
//  - frame_mean: the weighted mean rotation of n frames (FileFrame's nodal and
//    per-point fields), bislerp's generalization to n frames: each frame is replaced by
//    its symmetry-equivalent closest to an already aligned neighbour (the first frame,
//    or along the element's edges: node → midside → node, so that a P2 element can span
//    up to 180° of helix in two steps below 90° each), then the weighted Riemannian
//    (Karcher) mean on SO(3) is found by Gauss–Newton, m ← m·exp(Σ w_a log(m⁻¹ q_a)).
//    With two frames it is bislerp; frames turning about one axis by angles θ_a give
//    the turn by Σ w_a θ_a exactly (a helix interpolated as an angle, not as vectors).
// Every result is a proper rotation (from a unit quaternion).
#include "common/tensor9.h"

#include <Eigen/Geometry>

#include <span>

namespace fe2 {

/// The symmetry-equivalent of q (q, q·i, q·j, q·k: turned by π about its own axes)
/// closest to `ref`, with the sign making q·ref ≥ 0 (q and −q are one rotation).
Eigen::Quaterniond closest_equivalent(const Eigen::Quaterniond& q, const Eigen::Quaterniond& ref);

/// Bayer's bislerp: the rotation a fraction t of the way from Qa to Qb, along the
/// quaternion arc from the symmetry-equivalent of Qa closest to Qb. A null Qa or Qb (a
/// field absent at the point) gives the other.
Mat3 bislerp(const Mat3* Qa, const Mat3* Qb, double t);

/// The weighted mean frame of the unit quaternions q (as many as w). The weights are
/// affine (Σ w = 1) and may be negative (P2 shape functions): they act on the tangent
/// space at the mean, where an affine combination is defined. The result is turned
/// (by a frame symmetry) to the equivalent closest to the frame of largest weight, so
/// at a node it is that node's frame itself, not one of its equivalents. `align_to[a]`
/// (< a) is the frame that frame a is first aligned to; empty: every frame to the first.
Mat3 frame_mean(std::span<const Eigen::Quaterniond> q, std::span<const double> w,
                std::span<const int> align_to = {});

}  // namespace fe2
