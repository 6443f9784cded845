#include "worker/MacroLawPoint.h"

#include "common/cpu_timer.h"

namespace fe2 {

proto::JobOutput MacroLawPoint::iterate(const proto::JobInput& in) {
  proto::JobOutput out;
  const double t0 = thread_cpu_seconds();
  out.unit = in.unit;
  Zbar_ = in.Zbar;
  Vec9 Pi;
  material_->stress_and_tangent(in.Zbar, Pi, out.A_hom);
  out.P_bar = Pi;
  out.P_tilde = Pi;
  out.r_norm = 0.0;
  out.r_ref = 1.0;
  out.cpu_seconds = out.cpu_assembly = thread_cpu_seconds() - t0;
  return out;
}

void MacroLawPoint::serialize(Bytes& out) const {
  ByteWriter w(out);
  w.put_string(kind());
  w.put_array(Zbar_.data(), 9);
}

size_t MacroLawPoint::state_bytes() const {
  // As serialize(): kind string (length + text), then Z̄ (length + 9 doubles).
  return sizeof(uint64_t) + kind().size() + sizeof(uint64_t) + 9 * sizeof(double);
}

void MacroLawPoint::deserialize(const Bytes& in) {
  ByteReader r(in, "macro-law point state");
  if (r.get_string() != kind()) throw Error("macro-law point state: wrong kind");
  r.get_array_into(Zbar_.data(), 9);
}

}  // namespace fe2
