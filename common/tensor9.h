#pragma once
// 3x3 tensors as 9-vectors in column-major order (11,21,31,12,22,32,13,23,33),
// exactly as the paper orders χ_k and G_k and as Eigen::Map<Matrix3d> reads them
// (DESIGN §1). Index of component (i,J) is i + 3J.
#include <Eigen/Dense>

namespace fe2 {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;

/// Position of component (i, J) in a column-major 9-vector.
constexpr int index9(int i, int J) { return i + 3 * J; }

inline Mat3 as_mat3(const Vec9& v) { return Eigen::Map<const Mat3>(v.data()); }
inline Vec9 as_vec9(const Mat3& m) { return Eigen::Map<const Vec9>(m.data()); }

/// 9x9 operator R with vec(QᵀZQ) = R vec(Z): R = kron(Qᵀ, Qᵀ) for column-major vec.
/// The unit sees Z̄_μ = R Z̄; stresses and tangents come back as Rᵀ P_μ, Rᵀ 𝔸_μ R (DESIGN §2).
inline Mat9 frame_rotation(const Mat3& Q) {
  Mat9 R;
  const Mat3 Qt = Q.transpose();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) R.block<3, 3>(3 * a, 3 * b) = Qt(a, b) * Qt;
  return R;
}

}  // namespace fe2
