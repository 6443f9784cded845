#include "coordinator/failure_diagnosis.h"

#include "common/error.h"
#include "common/mesh/element_quality.h"

#include <cmath>
#include <regex>

namespace fe2 {

int inverted_element(const std::string& why) {
  static const std::regex pattern("macro element ([0-9]+) inverted");
  std::smatch m;
  if (!std::regex_search(why, m, pattern)) return -1;
  return std::stoi(m[1].str());
}

bool badly_shaped(double jacobian_ratio, double shape) { return jacobian_ratio < 0.25 || shape < 0.1; }

std::string volume_diagnosis(const TetMesh& mesh, const std::vector<double>& element_J, bool p1_pressure) {
  // 5 %: far beyond what a converged mixed solution leaves (10⁻⁶ with P1+P0; a percent
  // or two with P1 at moderate strain), well before an element collapses.
  constexpr double kVolumeChange = 0.05;
  int worst = -1;
  for (size_t e = 0; e < element_J.size(); ++e)
    if (element_J[e] > 0.0 && (worst < 0 || std::abs(element_J[e] - 1.0) > std::abs(element_J[worst] - 1.0)))
      worst = static_cast<int>(e);
  if (worst < 0 || std::abs(element_J[worst] - 1.0) <= kVolumeChange) return "";
  int changed = 0;
  for (double J : element_J) changed += J > 0.0 && std::abs(J - 1.0) > kVolumeChange;
  const ElementQuality q = element_quality(mesh, worst);
  std::string text = fmt::format(
      "; at the last converged state {} element(s) have changed volume by more than {:.0f} %, most element {} "
      "(centroid ({:.3g}, {:.3g}, {:.3g})) to J = {:.3f}",
      changed, 100 * kVolumeChange, worst, q.centroid[0], q.centroid[1], q.centroid[2], element_J[worst]);
  if (p1_pressure)
    text += ": the P1 pressure holds J = 1 only on average over each vertex's patch, so an element can lose "
            "volume until it inverts, at any step size; formulation.pressure \"P1+P0\" holds every element's "
            "volume (or give the material a volumetric penalty)";
  return text;
}

std::string InversionRecord::record(const TetMesh& mesh, const std::string& why) {
  const int e = inverted_element(why);
  if (e < 0 || e >= mesh.num_tets()) {
    element_ = -1;
    count_ = 0;
    return "";
  }
  count_ = e == element_ ? count_ + 1 : 1;
  element_ = e;
  if (count_ < 2) return "";
  const ElementQuality q = element_quality(mesh, e);
  const std::string where = fmt::format("; element {} inverted in {} tries in a row: {}", e, count_, describe(q));
  if (badly_shaped(q.jacobian_ratio, q.shape))
    return where + " — a badly shaped element: the mesh is the likely cause (remesh around it, or straighten "
                   "its curved edges)";
  const ElementQuality worst = worst_element(mesh);
  return where + fmt::format(" — a well-shaped element (the mesh's worst has Jacobian ratio {:.3g}, shape {:.3g}), "
                             "so the mesh is not the cause: the load passes a point where Newton's correction "
                             "overshoots (try newton.line_search \"backtracking\" and time.adaptive) or where the "
                             "solution loses stability",
                             worst.jacobian_ratio, worst.shape);
}

}  // namespace fe2
