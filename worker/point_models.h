#pragma once
// What a scene says about the response at its points, and the factory that builds
// one PointModel per integration point from it.
#include "common/materials/Material.h"
#include "worker/MicroModel.h"
#include "worker/PointModel.h"

#include <string>

namespace fe2 {

struct PointModelSpec {
  std::string name;
  enum class Kind { fe2, macro_law } kind = Kind::fe2;
  MicroModelPtr micro;   ///< fe2: the shared unit model (null until built)
  std::shared_ptr<const MicroModelPlan> plan;  ///< fe2: what `micro` is built from, its memory
  MaterialPtr material;  ///< macro_law
};

PointModelPtr make_point_model(const PointModelSpec& spec);

}  // namespace fe2
