#pragma once
// The phenomenological active-stress law of Bestel, Clément & Sorine 2001 ("A
// biomechanical model of muscle contraction", MICCAI 2001, LNCS 2208:1159–1161) in the
// form of Pfaller et al. 2019 ("The importance of the pericardium for cardiac
// biomechanics", Biomech Model Mechanobiol 18:503–529):
//
//   τ̇_c = −|u(t)| τ_c + σ₀ |u(t)|₊,   u(t) = α_max f(t) + α_min (1 − f(t)),   T_a = τ_c,
//
// with f the point's normalized calcium activation (CalciumTransient) in place of
// Pfaller's prescribed box; contraction builds while u > 0 (f > −α_min/(α_max − α_min))
// and relaxes at rate |α_min| otherwise. No dependence on λ or λ̇ (as in Pfaller), so both
// sensitivities are zero. Defaults (σ₀ = 90 kPa, α_max = 5 /s, α_min = −30 /s) are the
// values svFSI ships for this law, citing Pfaller et al. 2019. State: τ_c (Pa).
#include "common/cellmodels/CalciumTransient.h"
#include "common/cellmodels/CellModel.h"

namespace fe2 {

struct BestelClementSorineParameters {
  double sigma_0 = 9.0e4;   ///< contractility σ₀ (Pa)
  double alpha_max = 5.0;   ///< activation rate α_max > 0 (1/s)
  double alpha_min = -30.0; ///< relaxation rate α_min < 0 (1/s)
};

class BestelClementSorine final : public CellModel {
 public:
  static constexpr const char* kName = "bestel_clement_sorine";

  BestelClementSorine(const BestelClementSorineParameters& p, const CalciumParameters& calcium,
                      double max_substep);

  std::string name() const override { return kName; }
  std::string description() const override;
  int state_size() const override { return 1; }
  void rest_state(std::span<double> state) const override;
  ActiveTension advance(const CellStep& step, std::span<const double> committed,
                        std::span<double> current) const override;
  bool rate_dependent() const override { return false; }

  const BestelClementSorineParameters& parameters() const { return p_; }
  const CalciumTransient& calcium() const { return calcium_; }

 private:
  BestelClementSorineParameters p_;
  CalciumTransient calcium_;
  double max_substep_;
};

}  // namespace fe2
