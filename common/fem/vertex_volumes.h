#pragma once
// ∫ λ_b dV over a (possibly curved) tet of the reference mesh: the P1 pressure basis's
// integrals, V/4 each on a straight tet. A P1 field's lumped mass, a mean's weights.
#include "common/mesh/TetMesh.h"

namespace fe2 {

Eigen::Vector4d vertex_volumes(const TetMesh& mesh, int element);

}  // namespace fe2
