#include "worker/MacroLawPoint.h"

#include "common/cpu_timer.h"

namespace fe2 {

namespace {
// 2: version field and point history. Version 1 had neither: after the kind came Z̄
// alone (length 9 + 9 doubles), which is how deserialize() recognizes it.
constexpr uint32_t kStateVersion = 2;
constexpr size_t kVersion1Tail = sizeof(uint64_t) + 9 * sizeof(double);
}  // namespace

MacroLawPoint::MacroLawPoint(MaterialPtr material)
    : material_(std::move(material)),
      history_(static_cast<size_t>(material_->history_size()), 0.0),
      history_committed_(history_) {
  material_->initial_history(history_committed_);  // e.g. a resting cell
  history_ = history_committed_;
}

proto::JobOutput MacroLawPoint::iterate(const proto::JobInput& in) {
  proto::JobOutput out;
  const double t0 = thread_cpu_seconds();
  out.unit = in.unit;
  Zbar_ = in.Zbar;
  Vec9 Pi;
  // The point is the macro integration point itself: Ż = Ż̄ as the coordinator sent it,
  // and 𝔸 = ∂Π/∂Z + c ∂Π/∂Ż with c = ∂Ż̄/∂Z̄ of the macro integrator.
  const MaterialPointContext context{in.time, in.dt, in.Zbar_dot, in.activation_time};
  Mat9 A_rate;
  material_->stress_and_tangent_at(in.Zbar, context, {history_committed_, history_}, Pi,
                                   out.A_hom, A_rate);
  if (material_->rate_dependent()) out.A_hom += in.Zbar_dot_coefficient * A_rate;
  out.P_bar = Pi;
  out.P_tilde = Pi;
  if (const int slot = material_->active_tension_slot(); slot >= 0) out.active_tension = history_[slot];
  out.r_norm = 0.0;
  out.r_ref = 1.0;
  out.cpu_seconds = out.cpu_assembly = thread_cpu_seconds() - t0;
  return out;
}

void MacroLawPoint::serialize(Bytes& out) const {
  ByteWriter w(out);
  w.put_string(kind());
  w.put(kStateVersion);
  w.put_array(Zbar_.data(), 9);
  w.put_array(history_.data(), history_.size());
  w.put_array(history_committed_.data(), history_committed_.size());
}

size_t MacroLawPoint::state_bytes() const {
  // As serialize(): kind string (length + text), version, Z̄ and two histories (length + doubles).
  const size_t len = sizeof(uint64_t), d = sizeof(double);
  return len + kind().size() + sizeof(uint32_t) + (len + 9 * d) + 2 * (len + history_.size() * d);
}

void MacroLawPoint::deserialize(const Bytes& in) {
  ByteReader r(in, "macro-law point state");
  if (r.get_string() != kind()) throw Error("macro-law point state: wrong kind");
  if (r.remaining() == kVersion1Tail)
    throw Error(fmt::format("macro-law point state: version 1, expected {} (a state written by "
                            "another build of fe2heart)",
                            kStateVersion));
  const auto version = r.get<uint32_t>();
  if (version != kStateVersion)
    throw Error(fmt::format("macro-law point state: version {}, expected {} (a state written by "
                            "another build of fe2heart)",
                            version, kStateVersion));
  r.get_array_into(Zbar_.data(), 9);
  r.get_array_into(history_.data(), history_.size());
  r.get_array_into(history_committed_.data(), history_committed_.size());
  if (!r.at_end()) throw Error("macro-law point state: trailing bytes");
}

}  // namespace fe2
