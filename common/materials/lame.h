#pragma once
// Lamé parameters of an isotropic law from Young's modulus and Poisson's ratio:
//
//   λ = E ν / ((1 + ν)(1 − 2ν)),   μ = E / (2(1 + ν)),
//
// valid for E > 0 and −1 < ν < ½ (the range where the small-strain tensor is
// positive definite).
#include "common/error.h"

#include <string_view>

namespace fe2 {

struct LameParameters {
  double lambda = 0.0;
  double mu = 0.0;
};

/// Throws InputError naming `model` when (E, ν) leave the physical range.
inline LameParameters lame_from_young_poisson(double E, double nu, std::string_view model) {
  if (!(E > 0.0))
    throw InputError(fmt::format("{}: Young's modulus E = {}, expected E > 0", model, E));
  if (!(nu > -1.0 && nu < 0.5))
    throw InputError(fmt::format("{}: Poisson's ratio nu = {}, expected -1 < nu < 0.5", model, nu));
  return {E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
}

}  // namespace fe2
