#include "worker/point_models.h"

#include "worker/MacroLawPoint.h"
#include "worker/MicroUnit.h"

namespace fe2 {

PointModelPtr make_point_model(const PointModelSpec& spec) {
  if (spec.kind == PointModelSpec::Kind::fe2) return std::make_unique<MicroUnit>(spec.micro);
  return std::make_unique<MacroLawPoint>(spec.material);
}

}  // namespace fe2
