#include "common/fluid/fluid_boundary.h"

#include "common/fem/lagrange_tet.h"

namespace fe2 {

namespace {

/// n da at a quadrature point of the current triangle (its area element times the weight).
Vec3 area_vector(const Eigen::Matrix3Xd& x, const Eigen::Matrix<double, 2, Eigen::Dynamic>& dN, double weight) {
  const Vec3 t1 = x * dN.row(0).transpose(), t2 = x * dN.row(1).transpose();
  return weight * t1.cross(t2);
}

}  // namespace

Eigen::Matrix3Xd face_normal_integrals(int order, const Eigen::Matrix3Xd& x) {
  const int m = triangle_nodes(order);
  Eigen::Matrix3Xd S = Eigen::Matrix3Xd::Zero(3, m);
  Eigen::VectorXd N;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dN;
  for (const auto& q : triangle_rule(2 * order)) {
    triangle_shape(order, q.bary, N, dN);
    S += area_vector(x, dN, q.weight) * N.transpose();
  }
  return S;
}

Eigen::VectorXd face_shape_integrals(int order, const Eigen::Matrix3Xd& x) {
  Eigen::VectorXd S = Eigen::VectorXd::Zero(triangle_nodes(order));
  Eigen::VectorXd N;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dN;
  for (const auto& q : triangle_rule(2 * order)) {  // exact on straight faces
    triangle_shape(order, q.bary, N, dN);
    S += area_vector(x, dN, q.weight).norm() * N;
  }
  return S;
}

void backflow_face(int order, double density, double beta, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                   const Eigen::Matrix3Xd& w, Eigen::VectorXd& R, Eigen::MatrixXd* K) {
  const int m = triangle_nodes(order);
  R.setZero(3 * m);
  if (K) K->setZero(3 * m, 3 * m);
  Eigen::VectorXd N;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dN;
  for (const auto& q : triangle_rule(3 * order)) {
    triangle_shape(order, q.bary, N, dN);
    const Vec3 nda = area_vector(x, dN, q.weight);
    const Vec3 vq = v * N, c = vq - w * N;
    const double cn = c.dot(nda);  // (c·n) da
    if (cn >= 0.0) continue;       // outflow: nothing
    const double k = -beta * density;
    for (int a = 0; a < m; ++a) R.segment<3>(3 * a) += k * N[a] * cn * vq;
    if (!K) continue;
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b)
        K->block<3, 3>(3 * a, 3 * b) += k * N[a] * N[b] * (cn * Mat3::Identity() + vq * nda.transpose());
  }
}

FaceEnergyFlux face_energy_flux(int order, double density, double beta, const Eigen::Matrix3Xd& x,
                                const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& w) {
  FaceEnergyFlux e;
  Eigen::VectorXd N;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dN;
  for (const auto& q : triangle_rule(3 * order)) {
    triangle_shape(order, q.bary, N, dN);
    const Vec3 vq = v * N;
    const double cn = (vq - w * N).dot(area_vector(x, dN, q.weight));  // (c·n) da
    e.kinetic += 0.5 * density * vq.squaredNorm() * cn;
    if (cn < 0.0) e.backflow -= beta * density * cn * vq.squaredNorm();
  }
  return e;
}

}  // namespace fe2
