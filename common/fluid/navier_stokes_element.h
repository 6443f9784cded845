#pragma once
// One tetrahedron of incompressible Newtonian blood in ALE form (paper §II-A): on the
// current (moving) element, with the convective velocity c = v − v̂ (v̂ the mesh
// velocity) and a_χ = ∂v/∂t|_χ + (c·∇)v,
//
//   momentum   ∫ w·ρ(∂v/∂t|_χ + (c·∇)v − f) + ∫ 2μ D(v) : ∇w − ∫ p div w = 0   (+ faces)
//   mass       −∫ q div v = 0                       (the sign makes the Galerkin block
//                                                    symmetric: K_pv = K_vpᵀ)
//
// Elements (FluidElementKind):
//   taylor_hood      P2 velocity / P1 pressure on a quadratic mesh: inf–sup stable, no
//                    stabilization (Galerkin).
//   taylor_hood_supg Taylor–Hood with the SUPG and LSIC terms below (no PSPG: the pair
//                    is inf–sup stable), for convection-dominated flows (a ventricle's
//                    Re ≈ 10³ on centimetre elements) where Galerkin P2 oscillates
//   stabilized_p1p1  P1/P1 on a linear mesh with residual-based (SUPG/PSPG/LSIC) terms,
//                    the stabilization of Tezduyar (1992) and Whiting & Jansen (2001) in
//                    the notation of Bazilevs et al. (2007, CMAME 197:173), metric tensor
//                    G_ij = k² Σ_m ∂ξ_m/∂x_i ∂ξ_m/∂x_j (k the velocity degree: the nodes
//                    are h/k apart):
//       τ_M = (C_t/Δt² + c·G c + C_I ν² G:G)^(−1/2)      C_t = 4, C_I = 36, ν = μ/ρ
//       τ_C = 1/(τ_M tr G)
//       r_M = ρ(∂v/∂t|_χ + (c·∇)v − f) + ∇p − μΔv        (Δv exact on the curved P2
//                                                          element, 0 for P1: consistent)
//     SUPG  + ∫ τ_M (c·∇w)·r_M      PSPG  − ∫ (τ_M/ρ) ∇q·r_M      LSIC  + ∫ ρ τ_C div w div v
//
// Convective form (ConvectiveForm):
//   advective        ρ(c·∇)v as above.
//   skew_symmetric   + ½ρ(div v)v (Temam's term: zero for the exact, solenoidal flow).
//                    Tested with v, ρ(c·∇)v·v + ½ρ|v|² div v = ½ρ div(|v|² c) + ½ρ|v|² div v̂,
//                    and the last term is what the moving mesh adds to d/dt ∫½ρ|v|²: so the
//                    blood's kinetic energy changes by exactly the flux ½ρ|v|² c·n through its
//                    open faces, the work of the forces and the viscous dissipation, whatever
//                    div v a Taylor–Hood velocity keeps (it is zero only against P1). With
//                    the advective form the balance is off by ½∫ρ|v|² div v: an O(h) defect
//                    Δt → 0 does not remove. The strong residual r_M of the stabilization
//                    keeps the advective form (both are consistent).
//
// The tangent is consistent in v and p, the τ's dependence on c included (so Newton is
// quadratic on convective flows).
//
// Shape derivatives (K_x, the tangent with respect to the node positions x, the mesh
// velocity v̂ moving with x by the mesh scheme's ∂v̂/∂x): analytic, every term of every
// kind. Moving node b along e_j (δx_b = e_j, δv̂_b = ∂v̂/∂x e_j) changes, with
// g_b = ∇N_b and β_b = g_b·c + (∂v̂/∂x) N_b,
//   δJ = e_j ⊗ ∂N_b/∂ξ           δ(dV) = dV ∂_j N_b        δ(∇N_a) = −g_b ∂_j N_a
//   δ(∇v) = −(∂_j v) ⊗ g_b        δ((c·∇)N_a) = −β_b ∂_j N_a   δ(ρ(c·∇)v) = −ρ β_b ∂_j v
//   δG = −(g_b ⊗ G_j + G_j ⊗ g_b)  (G_j = G e_j)
//   δ(∂²N_a/∂x∂x) : I = −2 (∂²N_a/∂x∂x g_b)_j − ∂_j N_a ΔN_b      (curved P2 included)
// and τ_M, τ_C, r_M through these (the derivations are beside the code).
//
// Element unknowns, in this order: velocity node-major (3a + i over the element's n
// nodes, TetMesh::element_nodes order), then the pressure at its 4 vertices.
#include "common/tensor9.h"

#include <Eigen/Dense>

namespace fe2 {

enum class FluidElementKind { taylor_hood, taylor_hood_supg, stabilized_p1p1 };
enum class ConvectiveForm { advective, skew_symmetric };

/// The velocity's polynomial degree (and the mesh's order) of an element kind.
inline int fluid_velocity_order(FluidElementKind kind) { return kind == FluidElementKind::stabilized_p1p1 ? 1 : 2; }

struct NewtonianFluid {
  double density = 0.0;    ///< ρ
  double viscosity = 0.0;  ///< μ (dynamic)
};

/// The element's data at the new time: current geometry and the nodal fields.
struct FluidElementState {
  Eigen::Matrix3Xd x;        ///< current node positions (3 x n, n = 4 or 10)
  Eigen::Matrix3Xd v;        ///< velocity at the nodes
  Eigen::Matrix3Xd v_rate;   ///< ∂v/∂t|_χ at the nodes (the field's time scheme)
  Eigen::Matrix3Xd w;        ///< mesh velocity v̂ at the nodes
  Eigen::Vector4d p = Eigen::Vector4d::Zero();  ///< pressure at the vertices
  double dv_rate_dv = 0.0;   ///< ∂(∂v/∂t)/∂v of the scheme (0: steady)
  double dw_dx = 0.0;        ///< ∂v̂/∂x of the mesh motion's scheme (for the shape derivatives)
  double dt = 0.0;           ///< the step, for τ_M (0: steady, no C_t/Δt² term)
  Vec3 body_force = Vec3::Zero();  ///< f, per unit mass
};

/// Number of element unknowns: 3 per velocity node, 1 per vertex.
inline int fluid_element_dofs(FluidElementKind kind) { return fluid_velocity_order(kind) == 2 ? 34 : 16; }

/// The element residual R (fluid_element_dofs) and, if `K` is not null, its tangent
/// ∂R/∂(v, p); if `K_x` is not null, its shape derivatives dR/dx (fluid_element_dofs x 3n,
/// column 3b + j: node b's x_j, the mesh velocity following by s.dw_dx). Throws
/// fe2::NumericalError on an inverted or degenerate element.
void navier_stokes_element(FluidElementKind kind, ConvectiveForm convection, const NewtonianFluid& fluid,
                           const FluidElementState& s, Eigen::VectorXd& R, Eigen::MatrixXd* K,
                           Eigen::MatrixXd* K_x = nullptr);

/// τ_M and τ_C of the stabilized element at convective velocity c (see above).
struct StabilizationParameters {
  double tau_m = 0.0, tau_c = 0.0;
};
StabilizationParameters stabilization_parameters(const Mat3& G, const Vec3& c, double nu, double dt);

}  // namespace fe2
