#include "coordinator/failure_diagnosis.h"

#include "common/error.h"
#include "common/mesh/element_quality.h"

#include <regex>

namespace fe2 {

int inverted_element(const std::string& why) {
  static const std::regex pattern("macro element ([0-9]+) inverted");
  std::smatch m;
  if (!std::regex_search(why, m, pattern)) return -1;
  return std::stoi(m[1].str());
}

bool badly_shaped(double jacobian_ratio, double shape) { return jacobian_ratio < 0.25 || shape < 0.1; }

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
