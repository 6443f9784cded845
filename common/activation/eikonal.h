#pragma once
// Activation times from an eikonal equation on a tetrahedral mesh:
//   sqrt(∇tᵀ D ∇t) = 1,   t = t_s at the source vertices,
// with a conduction metric D_e = Q diag(v_f², v_s², v_n²) Qᵀ per element (Q = [f s n],
// velocities in mesh length units per second), so a front crosses a segment d of
// element e in the time ‖d‖_M = sqrt(dᵀ M_e d), M_e = D_e⁻¹.
//
// Discretization (Fu, Kirby, Whitaker 2013, "A fast iterative method for solving the
// eikonal equation on tetrahedral domains", SIAM J. Sci. Comput. 35(5):C473–C494, §3):
// P1 times at the tet vertices; a vertex x of tet e takes
//   t_x = min over λ in the opposite face of  Σ λ_i t_i + ‖x − Σ λ_i y_i‖_{M_e},
// the exact Hopf–Lax update of a linear front across the face, falling back to the
// face's edges and vertices when the minimizer leaves the face. A planar front in a
// homogeneous (anisotropic) medium is therefore reproduced exactly on any tet mesh;
// curved fronts converge at first order.
//
// Solution: a label-correcting sweep (the fixed point FIM iterates to, reached in
// heap order): a vertex whose time drops re-evaluates every vertex that shares a tet
// with it. Ties break by vertex index and adjacency is sorted, so the result is the
// same bit for bit on every run. The number of vertex re-evaluations is capped.
#include "common/mesh/TetMesh.h"
#include "common/tensor9.h"

#include <array>
#include <vector>

namespace fe2 {

struct EikonalSource {
  int vertex = 0;     ///< a vertex of the mesh's tets (TetMesh node index)
  double time = 0.0;  ///< its activation time (s); the vertex keeps it (Dirichlet)
};

struct EikonalOptions {
  /// The solve stops with an fe2::NumericalError after this many vertex pops per
  /// vertex of the mesh (a healthy solve needs a few; the cap only bounds a bug).
  int max_pops_per_vertex = 1000;
};

struct EikonalStats {
  long long pops = 0;     ///< vertices taken from the heap (each re-evaluates its tets)
  long long updates = 0;  ///< accepted decreases of a vertex time
};

/// D = Q diag(v_f², v_s², v_n²) Qᵀ for a frame Q = [f s n].
Mat3 conduction_metric(const Mat3& Q, double v_fibre, double v_sheet, double v_normal);

/// The exact local update of a point x from a simplex of k = 1, 2 or 3 points y with
/// times t: min over the simplex of Σ λ_i t_i + ‖x − Σ λ_i y_i‖_M (M = D⁻¹, symmetric
/// positive definite). Exposed for tests.
double eikonal_simplex_update(const Vec3& x, const Vec3* y, const double* t, int k, const Mat3& M);

/// Activation time of every node of `mesh` (per node: quadratic edge nodes get the
/// mean of their edge's two vertices; a node of no tet NaN). `metric`: D_e per tet
/// (symmetric positive definite). Sources on the same vertex keep the earliest time.
/// Throws InputError if a source is not a tet vertex or some vertices are not reachable
/// from any source (naming how many and one of them), NumericalError past the cap.
std::vector<double> solve_eikonal(const TetMesh& mesh, const std::vector<Mat3>& metric,
                                  const std::vector<EikonalSource>& sources, const EikonalOptions& opt = {},
                                  EikonalStats* stats = nullptr);

}  // namespace fe2
