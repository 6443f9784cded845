#include "common/materials/Myocardium.h"

#include "common/materials/active_stress.h"
#include "common/materials/kelvin_voigt.h"

#include <spdlog/fmt/fmt.h>

namespace fe2 {

Myocardium::Myocardium(MaterialPtr passive, MyocardiumOptions options)
    : passive_(std::move(passive)), options_(std::move(options)) {
  passive_history_ = passive_->history_size();
  cell_history_ = options_.cell ? options_.cell->state_size() : 0;
}

std::string Myocardium::description() const {
  std::string d = passive_->description();
  if (options_.cell)
    d += fmt::format(" + active stress (n_t = {}): {}", options_.transverse_fraction, options_.cell->description());
  if (options_.viscosity > 0.0) d += fmt::format(" + viscosity eta = {} Pa s", options_.viscosity);
  return d;
}

bool Myocardium::major_symmetric() const {
  // T_a depends on λ through the cell state and λ̇; η Ė couples Z and Ż: neither is the
  // gradient of an energy.
  return passive_->major_symmetric() && !options_.cell && options_.viscosity == 0.0;
}

bool Myocardium::rate_dependent() const {
  return passive_->rate_dependent() || options_.viscosity > 0.0 ||
         (options_.cell && options_.cell->rate_dependent());
}

void Myocardium::initial_history(std::span<double> history) const {
  passive_->initial_history(history.first(passive_history_));
  if (!options_.cell) return;
  options_.cell->rest_state(history.subspan(passive_history_, cell_history_));
  history[tension_slot()] = 0.0;
}

void Myocardium::stress_and_tangent_at(const Vec9& Z, const MaterialPointContext& context,
                                       PointHistory history, Vec9& Pi, Mat9& A, Mat9& A_rate) const {
  const size_t hp = static_cast<size_t>(passive_history_), hc = static_cast<size_t>(cell_history_);
  passive_->stress_and_tangent_at(Z, context, {history.committed.first(hp), history.current.first(hp)},
                                  Pi, A, A_rate);
  if (!options_.cell && options_.viscosity == 0.0) return;
  const Mat3 F = Mat3::Identity() + as_mat3(Z), Fdot = as_mat3(context.Zdot);
  if (options_.cell) {
    const FibreStretch s = fibre_stretch(F, Fdot);
    const CellStep step{context.time, context.dt, context.activation_time, s.lambda, s.lambda_dot};
    const ActiveTension T = options_.cell->advance(step, history.committed.subspan(hp, hc),
                                                   history.current.subspan(hp, hc));
    history.current[tension_slot()] = T.Ta;
    add_active_stress(F, Fdot, T, options_.transverse_fraction, Pi, A, A_rate);
  }
  if (options_.viscosity > 0.0) add_kelvin_voigt_stress(F, Fdot, options_.viscosity, Pi, A, A_rate);
}

}  // namespace fe2
