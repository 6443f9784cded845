#pragma once
// Guccione's transversely isotropic exponential law for passive myocardium
// (Guccione, McCulloch & Waldman 1991), in the material frame of the unit
// (axis 1 = fibre f, 2 = sheet s, 3 = sheet-normal n), with a volumetric part U:
//
//   W = C/2 (e^Q − 1) + U(J)
//   Q = b_f E11² + b_t (E22² + E33² + 2 E23²) + b_fs (2 E12² + 2 E13²)
//
// U (volumetric.h) is the penalty κ/2 (J − 1)² by default, or absent
// (`"volumetric": "none"`) when the macro mixed formulation's pressure field enforces
// J̄ = 1: then W is exactly the first term, Guccione's incompressible law. Q uses the
// full E in both cases, as in Guccione's paper (no isochoric Ē).
//
// Writing Q = Σ_IJ b_IJ E_IJ² (all nine components; b_11 = b_f, b_22 = b_33 = b_23 =
// b_t, b_12 = b_13 = b_fs, symmetric), with a_IJ = b_IJ E_IJ (no sum):
//
//   S_Q = C e^Q a,   ℂ_Q = C e^Q (b_IJ 𝕀_IJKL + 2 a_IJ a_KL),   plus S_vol, ℂ_vol.
//
// Π and 𝔸 by push_forward (hyperelastic_push.h). Parameters in Pa (C, κ) and
// dimensionless (b). A strain so large that e^Q overflows is a NumericalError.
#include "common/materials/Material.h"
#include "common/materials/hyperelastic_push.h"
#include "common/materials/volumetric.h"

namespace fe2 {

struct GuccioneParameters {
  double C = 880.0;      ///< Pa; Guccione et al. 1991 (canine): 0.876 kPa
  double bf = 18.5;      ///< fibre exponent b_f
  double bt = 3.58;      ///< transverse exponent b_t
  double bfs = 1.63;     ///< fibre–sheet/normal shear exponent b_fs
  double kappa = 1.0e5;  ///< Pa; volumetric penalty, ~100 C: nearly incompressible
  Volumetric volumetric = Volumetric::penalty;  ///< none: κ is unused
};

class Guccione final : public Material {
 public:
  static constexpr const char* kName = "guccione";

  /// Every parameter must be > 0 (κ only with the penalty; InputError otherwise).
  explicit Guccione(const GuccioneParameters& p);

  std::string name() const override { return kName; }
  double energy(const Vec9& Z) const override;
  void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const override;
  /// C·max(b_f, b_t, b_fs) + κ: the stiffest small-strain entry, ℂ_1111 ≈ C b_f + κ
  /// at E = 0 for the usual b_f > b_t, b_fs (without κ when volumetric is none).
  double stiffness_scale() const override;

  const GuccioneParameters& parameters() const { return p_; }

 private:
  /// Q for the Voigt strain e (tensor components, order of hyperelastic_push.h).
  double get_Q(const Vec6& e) const;
  /// e^Q, checked finite.
  double get_exp_Q(double Q) const;

  GuccioneParameters p_;
  Vec6 b_;  ///< b_IJ in Voigt order: b_f, b_t, b_t, b_t, b_fs, b_fs
};

}  // namespace fe2
