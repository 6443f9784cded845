#include "common/fibres/frame_interpolation.h"

#include "common/error.h"

#include <cmath>
#include <vector>

namespace fe2 {

namespace {

using Quat = Eigen::Quaterniond;

/// The rotation vector (angle × axis, angle in [0, π]) of the unit quaternion r.
Vec3 log_rotation(const Quat& r) {
  const double s = r.vec().norm();
  if (s == 0) return Vec3::Zero();
  // atan2(s, |w|) is accurate for small and large angles; the sign picks the short way.
  return (r.w() < 0 ? -2.0 : 2.0) * std::atan2(s, std::abs(r.w())) / s * r.vec();
}

Quat exp_rotation(const Vec3& v) {
  const double a = v.norm();
  if (a == 0) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(a, v / a));
}

}  // namespace

Quat closest_equivalent(const Quat& q, const Quat& ref) {
  Quat best = q;
  double best_dot = -1;
  for (const Quat& turn : {Quat(1, 0, 0, 0), Quat(0, 1, 0, 0), Quat(0, 0, 1, 0), Quat(0, 0, 0, 1)}) {
    const Quat c = q * turn;
    const double d = std::abs(c.dot(ref));
    if (d > best_dot) {
      best_dot = d;
      best = c;
    }
  }
  if (best.dot(ref) < 0) best.coeffs() = -best.coeffs();
  return best;
}

Mat3 bislerp(const Mat3* Qa, const Mat3* Qb, double t) {
  if (!Qa) return *Qb;
  if (!Qb) return *Qa;
  const Quat qa(*Qa), qb(*Qb);
  return closest_equivalent(qa, qb).slerp(t, qb).toRotationMatrix();
}

Mat3 frame_mean(std::span<const Quat> q, std::span<const double> w, std::span<const int> align_to) {
  FE2_CHECK(!q.empty() && q.size() == w.size() && (align_to.empty() || align_to.size() == q.size()),
            "frame_mean: {} frames, {} weights and {} alignments", q.size(), w.size(), align_to.size());
  std::vector<Quat> p(q.size());
  std::size_t heaviest = 0;
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  for (std::size_t a = 0; a < q.size(); ++a) {
    const std::size_t to = align_to.empty() ? 0 : static_cast<std::size_t>(align_to[a]);
    FE2_CHECK(a == 0 || to < a, "frame_mean: frame {} aligned to frame {}, expected an earlier one", a, to);
    p[a] = a == 0 ? q[0] : closest_equivalent(q[a], p[to]);
    if (w[a] > w[heaviest]) heaviest = a;
    sum += w[a] * p[a].coeffs();
  }
  // Start from the normalized weighted sum (nlerp), which is within a small angle of the
  // mean for aligned frames; a sum that cancels starts from the heaviest frame.
  Quat m = p[heaviest];
  if (sum.norm() > 1e-6) m.coeffs() = sum.normalized();
  for (int it = 0; it < 50; ++it) {
    Vec3 v = Vec3::Zero();
    for (std::size_t a = 0; a < q.size(); ++a) v += w[a] * log_rotation(m.conjugate() * p[a]);
    m = (m * exp_rotation(v)).normalized();
    if (!(v.norm() > 1e-15)) break;
  }
  return closest_equivalent(m, q[heaviest]).toRotationMatrix();
}

}  // namespace fe2
