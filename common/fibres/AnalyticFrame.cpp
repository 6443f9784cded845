#include "common/fibres/AnalyticFrame.h"

#include <algorithm>

namespace fe2 {

Mat3 AnalyticFrame::at(const Vec3& X) const {
  Vec3 f = fibre, s = sheet;
  if (rotating) {
    const double xi = std::clamp((X.dot(coordinate) - c0) / (c1 - c0), 0.0, 1.0);
    const Eigen::AngleAxisd rot(angle0 + xi * (angle1 - angle0), axis);
    f = rot * f;
    s = rot * s;
  }
  Mat3 Q;
  Q.col(0) = f;
  Q.col(1) = s;
  Q.col(2) = f.cross(s);
  return Q;
}

}  // namespace fe2
