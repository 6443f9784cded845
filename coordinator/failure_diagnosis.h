#pragma once
// Naming the cause of a step that keeps failing by element inversion: the mesh, or not.
//
// An inverted element (det F̄ ≤ 0 at one of its points) cuts the step back. When the same
// element inverts again at the smaller step, the message a run stops with names it, its
// centroid and its quality (common/mesh/element_quality.h: the Jacobian ratio
// min/max det J of the curved element and the vertex tet's shape), and says which cause
// that points to: a badly shaped or badly curved element is the mesh's fault (remesh
// there); a well-shaped one is not, and the failure is the solution's (a limit point, a
// loss of stability of the material) or the step's (try time.adaptive, or a line search).
#include "common/mesh/TetMesh.h"

#include <string>
#include <vector>

namespace fe2 {

/// The element a failure message names as inverted ("macro element 12 inverted …", the
/// text of PointCoupling and IncompressibilityTerm), or −1.
int inverted_element(const std::string& why);

/// Elements below either bound are called badly shaped: a Jacobian ratio below 0.25 (the
/// curved map's det J varies fourfold inside the element) or a shape η below 0.1 (a sliver).
bool badly_shaped(double jacobian_ratio, double shape);

/// A failed run's committed state, element by element: the volume ratio J̄_e = ∫_e det F̄ / |e|
/// of each element (−1 off the wall) and whether the pressure is continuous P1 only (a
/// Lagrange multiplier or a perturbed one, no constant per element). With P1 the
/// constraint J = 1 holds only against the P1 test functions, so an element may gain or
/// lose volume while its vertex patch keeps its own; under a large hydrostatic pressure
/// such an element keeps shrinking until it inverts, whatever the step (the discrete
/// pressure space is the cause, P1+P0 holds each element's volume). "" or a clause
/// naming the element that lost most volume, its J̄_e and centroid, and the remedy, when
/// some element's volume changed by more than 5 %.
std::string volume_diagnosis(const TetMesh& mesh, const std::vector<double>& element_J, bool p1_pressure);

/// The failures of one output step, in order.
class InversionRecord {
 public:
  /// Notes the failure `why`; "" or, when it is an element's second or later inversion in
  /// a row, "; element 12 inverted in 3 tries in a row: element 12 (centroid …) — …".
  std::string record(const TetMesh& mesh, const std::string& why);

 private:
  int element_ = -1;
  int count_ = 0;
};

}  // namespace fe2
