#pragma once
// Boundary integrals of the fluid on a (current, moving) triangle of its boundary, in
// the node order of TetMesh::face_nodes (3 or 6 nodes), normal n outward of the fluid.
//
//   ∫ N_a n da                  a face's flux of a nodal field, Q = Σ_a (v_a − v̂_a)·∫N_a n da;
//                               and the load of a uniform pressure P: −∫ N_a (−P n) da
//   backflow (Moghadam et al. 2011, Comput Mech 48:277; Bazilevs et al. 2009):
//       + ∫ w · (−β ρ (c·n)₋ v) da,   (c·n)₋ = min(c·n, 0)
//     adds back on an open boundary the kinetic energy that inflowing velocity would
//     otherwise bring in unbounded (the instability of outlets with reversed flow);
//     zero where the flow leaves.
#include "common/tensor9.h"

#include <Eigen/Dense>

namespace fe2 {

/// ∫ N_a n da per face node (3 x m): the face's normal-weighted shape integrals.
Eigen::Matrix3Xd face_normal_integrals(int order, const Eigen::Matrix3Xd& x);

/// ∫ N_a da per face node (m): the load of a uniform traction t is t ∫N_a da.
Eigen::VectorXd face_shape_integrals(int order, const Eigen::Matrix3Xd& x);

/// The backflow term's residual (3m, node-major) and, if `K` is not null, its tangent
/// ∂R/∂v on the face's velocity nodes. `v`, `w`: velocity and mesh velocity at the nodes.
void backflow_face(int order, double density, double beta, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                   const Eigen::Matrix3Xd& w, Eigen::VectorXd& R, Eigen::MatrixXd* K);

/// The energy an open face lets through by convection: the kinetic-energy flux
/// ∫½ρ|v|²(c·n) da (c = v − v̂, positive out of the fluid) and the power the backflow
/// term (β) takes, −βρ∫(c·n)₋|v|² da ≥ 0 (its own quadrature, so the two balance it).
struct FaceEnergyFlux {
  double kinetic = 0.0, backflow = 0.0;
};
FaceEnergyFlux face_energy_flux(int order, double density, double beta, const Eigen::Matrix3Xd& x,
                                const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& w);

}  // namespace fe2
