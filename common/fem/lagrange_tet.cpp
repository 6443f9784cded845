#include "common/fem/lagrange_tet.h"

#include "common/error.h"
#include "common/mesh/TetMesh.h"

#include <array>

namespace fe2 {

namespace {

// ∂λ_a/∂ξ for ξ = (λ1, λ2, λ3): λ0 = 1 − Σξ.
Vec3 dlambda_tet(int a) { return a == 0 ? Vec3(-1, -1, -1) : Vec3::Unit(a - 1); }
Eigen::Vector2d dlambda_tri(int a) { return a == 0 ? Eigen::Vector2d(-1, -1) : Eigen::Vector2d::Unit(a - 1); }

}  // namespace

void tet_shape(int order, const Vec4& l, Eigen::VectorXd& N, Eigen::Matrix<double, 3, Eigen::Dynamic>& dN) {
  FE2_CHECK(order == 1 || order == 2, "tet order {} (expected 1 or 2)", order);
  const int n = tet_nodes(order);
  N.resize(n);
  dN.resize(3, n);
  if (order == 1) {
    for (int a = 0; a < 4; ++a) N[a] = l[a], dN.col(a) = dlambda_tet(a);
    return;
  }
  for (int a = 0; a < 4; ++a) {
    N[a] = l[a] * (2 * l[a] - 1);
    dN.col(a) = (4 * l[a] - 1) * dlambda_tet(a);
  }
  for (int k = 0; k < 6; ++k) {
    const auto [a, b] = kTetEdges[k];
    N[4 + k] = 4 * l[a] * l[b];
    dN.col(4 + k) = 4 * (l[b] * dlambda_tet(a) + l[a] * dlambda_tet(b));
  }
}

std::vector<Mat3> tet_shape_hessians(int order) {
  FE2_CHECK(order == 1 || order == 2, "tet order {} (expected 1 or 2)", order);
  std::vector<Mat3> H(static_cast<size_t>(tet_nodes(order)), Mat3::Zero());
  if (order == 1) return H;
  for (int a = 0; a < 4; ++a) H[static_cast<size_t>(a)] = 4.0 * dlambda_tet(a) * dlambda_tet(a).transpose();
  for (int k = 0; k < 6; ++k) {
    const auto [a, b] = kTetEdges[k];
    const Mat3 ab = dlambda_tet(a) * dlambda_tet(b).transpose();
    H[static_cast<size_t>(4 + k)] = 4.0 * (ab + ab.transpose());
  }
  return H;
}

std::vector<Mat3> tet_shape_physical_hessians(int order, const Eigen::Matrix3Xd& x, const Mat3& Jinv,
                                              const Eigen::Matrix3Xd& gN) {
  const Eigen::Index n = x.cols();
  std::vector<Mat3> P(static_cast<size_t>(n), Mat3::Zero());
  if (order == 1) return P;
  static const std::vector<Mat3> H = tet_shape_hessians(2);
  std::array<Mat3, 3> Hx;  // ∂²x_k/∂ξ∂ξ
  for (int k = 0; k < 3; ++k) {
    Hx[k].setZero();
    for (Eigen::Index c = 0; c < n; ++c) Hx[k] += x(k, c) * H[static_cast<size_t>(c)];
  }
  for (Eigen::Index a = 0; a < n; ++a) {
    Mat3 h = H[static_cast<size_t>(a)];
    for (int k = 0; k < 3; ++k) h -= gN(k, a) * Hx[k];
    P[static_cast<size_t>(a)] = Jinv.transpose() * h * Jinv;
  }
  return P;
}

Eigen::VectorXd tet_shape_laplacians(int order, const Eigen::Matrix3Xd& x, const Mat3& Jinv,
                                     const Eigen::Matrix3Xd& gN) {
  const std::vector<Mat3> P = tet_shape_physical_hessians(order, x, Jinv, gN);
  Eigen::VectorXd lap(x.cols());
  for (Eigen::Index a = 0; a < x.cols(); ++a) lap[a] = P[static_cast<size_t>(a)].trace();
  return lap;
}

void triangle_shape(int order, const Vec3& l, Eigen::VectorXd& N, Eigen::Matrix<double, 2, Eigen::Dynamic>& dN) {
  FE2_CHECK(order == 1 || order == 2, "triangle order {} (expected 1 or 2)", order);
  const int n = triangle_nodes(order);
  N.resize(n);
  dN.resize(2, n);
  if (order == 1) {
    for (int a = 0; a < 3; ++a) N[a] = l[a], dN.col(a) = dlambda_tri(a);
    return;
  }
  for (int a = 0; a < 3; ++a) {
    N[a] = l[a] * (2 * l[a] - 1);
    dN.col(a) = (4 * l[a] - 1) * dlambda_tri(a);
  }
  for (int k = 0; k < 3; ++k) {  // edges 01, 12, 20
    const int a = k, b = (k + 1) % 3;
    N[3 + k] = 4 * l[a] * l[b];
    dN.col(3 + k) = 4 * (l[b] * dlambda_tri(a) + l[a] * dlambda_tri(b));
  }
}

}  // namespace fe2
