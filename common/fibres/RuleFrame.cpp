#include "common/fibres/RuleFrame.h"

#include "common/error.h"
#include "common/spec/SpecNode.h"
#include "common/fibres/frame_interpolation.h"
#include "common/fibres/laplace_p1.h"

#include <cmath>

namespace fe2 {

namespace {

constexpr double kDeg = M_PI / 180.0;

/// A named node set of the mesh (named faces are node sets too), or an InputError.
const std::vector<int>& named_set(const TetMesh& mesh, const std::string& key, const std::string& name) {
  const auto it = mesh.node_sets.find(name);
  if (it == mesh.node_sets.end() || it->second.empty()) {
    std::vector<std::string> known;
    for (const auto& [n, nodes] : mesh.node_sets) known.push_back(n);
    throw InputError(fmt::format("frame rule: '{}' = \"{}\" is not a named surface or node set of the mesh; "
                                 "expected {}",
                                 key, name, known_names("a non-empty one", name, known)));
  }
  return it->second;
}

Vec3 centroid(const TetMesh& mesh, const std::vector<int>& nodes) {
  Vec3 c = Vec3::Zero();
  for (int v : nodes) c += mesh.nodes[v];
  return c / static_cast<double>(nodes.size());
}

}  // namespace

RuleFrame::RuleFrame(const TetMesh& mesh, RuleFrameOptions opt) : opt_(std::move(opt)), tets_(mesh.tets) {
  const auto& base = named_set(mesh, "base", opt_.base);
  const auto& endo = named_set(mesh, "endo", opt_.endo);
  const auto& epi = named_set(mesh, "epi", opt_.epi);
  std::vector<int> apex_auto;
  if (opt_.apex.empty()) {  // Bayer's apex: the epicardial point farthest from the base
    const Vec3 b = centroid(mesh, base);
    int far = epi.front();
    for (int v : epi)
      if ((mesh.nodes[v] - b).norm() > (mesh.nodes[far] - b).norm()) far = v;
    apex_auto = {far};
  }
  const auto& apex = opt_.apex.empty() ? apex_auto : named_set(mesh, "apex", opt_.apex);
  const std::string apex_name = opt_.apex.empty() ? "the apex (farthest epi node)" : opt_.apex;
  grads_.reserve(tets_.size());
  for (int e = 0; e < mesh.num_tets(); ++e) grads_.push_back(p1_gradients(mesh, e));
  Vec3 lo = mesh.nodes.front(), hi = lo;
  for (const Vec3& x : mesh.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  length_ = (hi - lo).norm();
  const Vec3 apex_to_base = centroid(mesh, base) - centroid(mesh, apex);
  if (apex_to_base.norm() > 1e-12 * length_) long_axis_ = apex_to_base.normalized();

  psi_ = field(mesh, solve_laplace_p1(mesh, {{apex_name, apex, 0.0}, {opt_.base, base, 1.0}}, "frame rule, apico-basal ψ"));
  if (!biventricular()) {
    phi_ = field(mesh, solve_laplace_p1(mesh, {{opt_.endo, endo, 0.0}, {opt_.epi, epi, 1.0}}, "frame rule, transmural φ"));
    return;
  }
  const auto& rv = named_set(mesh, "rv_endo", opt_.rv_endo);
  phi_ = field(mesh, solve_laplace_p1(mesh, {{opt_.endo, endo, 0.0}, {opt_.rv_endo, rv, 0.0}, {opt_.epi, epi, 1.0}},
                                      "frame rule, transmural φ_epi"));
  phi_lv_ = field(mesh, solve_laplace_p1(mesh, {{opt_.endo, endo, 1.0}, {opt_.rv_endo, rv, 0.0}, {opt_.epi, epi, 0.0}},
                                         "frame rule, φ_lv"));
  phi_rv_ = field(mesh, solve_laplace_p1(mesh, {{opt_.endo, endo, 0.0}, {opt_.rv_endo, rv, 1.0}, {opt_.epi, epi, 0.0}},
                                         "frame rule, φ_rv"));
}

RuleFrame::Field RuleFrame::field(const TetMesh& mesh, std::vector<double> u) const {
  Field f;
  f.u = std::move(u);
  f.g.assign(f.u.size(), Vec3::Zero());
  std::vector<double> weight(f.u.size(), 0.0);
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const double V = std::abs(tet_signed_volume(mesh, e));
    const auto& t = tets_[e];
    const Vec3 g = f.u[t[0]] * grads_[e][0] + f.u[t[1]] * grads_[e][1] + f.u[t[2]] * grads_[e][2] + f.u[t[3]] * grads_[e][3];
    for (int v : t) {
      f.g[v] += V * g;
      weight[v] += V;
    }
  }
  for (std::size_t v = 0; v < f.g.size(); ++v)
    if (weight[v] > 0) f.g[v] /= weight[v];
  return f;
}

double RuleFrame::value(const Field& f, int e, const Bary& l) const {
  const auto& t = tets_[e];
  return l[0] * f.u[t[0]] + l[1] * f.u[t[1]] + l[2] * f.u[t[2]] + l[3] * f.u[t[3]];
}

Vec3 RuleFrame::gradient(const Field& f, int e, const Bary& l) const {
  const auto& t = tets_[e];
  const auto& g = grads_[e];
  const Vec3 ge = f.u[t[0]] * g[0] + f.u[t[1]] * g[1] + f.u[t[2]] * g[2] + f.u[t[3]] * g[3];
  if (ge.norm() > 1e-10 / length_) return ge;
  return l[0] * f.g[t[0]] + l[1] * f.g[t[1]] + l[2] * f.g[t[2]] + l[3] * f.g[t[3]];
}

double RuleFrame::transmural(int e, const Bary& l) const { return value(phi_, e, l); }

Mat3 RuleFrame::axes(int e, const Bary& l) const { return axis(e, l, gradient(phi_, e, l)); }

Mat3 RuleFrame::axis(int e, const Bary& lambda, const Vec3& g) const {
  // Gradients of fields that vary by 1 across the heart are ~1/length; far less is zero.
  const double tiny = 1e-10 / length_;
  if (!(g.norm() > tiny))
    throw InputError(fmt::format("frame rule: the transmural gradient vanishes in element {} (|∇φ| = {:.3g}), "
                                 "expected the '{}' and '{}' surfaces on opposite sides of the wall",
                                 e, g.norm(), opt_.endo, opt_.epi));
  const Vec3 t = g.normalized();
  const Vec3 gpsi = gradient(psi_, e, lambda);
  Vec3 l = gpsi - gpsi.dot(t) * t;
  if (!(gpsi.norm() > tiny) || !(l.norm() > 1e-6 * gpsi.norm())) {
    l = long_axis_ - long_axis_.dot(t) * t;  // fallback 1: the mesh's long axis
    if (!(l.norm() > 1e-6)) l = t.unitOrthogonal();  // fallback 2: wall normal along the axis
  }
  l.normalize();
  Mat3 A;
  A.col(0) = l.cross(t);
  A.col(1) = l;
  A.col(2) = t;
  return A;
}

Mat3 RuleFrame::oriented(int e, const Bary& lambda, const Vec3& g, double alpha, double beta) const {
  const Mat3 A = axis(e, lambda, g);
  const Vec3 c = A.col(0), l = A.col(1), t = A.col(2);
  const double a = alpha * kDeg, b = beta * kDeg;
  const Vec3 f = std::cos(a) * c + std::sin(a) * l;
  const Vec3 w = -std::sin(a) * c + std::cos(a) * l;
  Mat3 R;
  R.col(0) = f;
  R.col(1) = std::cos(b) * w - std::sin(b) * t;
  R.col(2) = std::sin(b) * w + std::cos(b) * t;  // the sheet
  return R;
}

Mat3 RuleFrame::at(int e, const Bary& lambda, const Vec3&) const {
  const double lerp_phi = value(phi_, e, lambda);
  const double alpha = opt_.alpha_endo + (opt_.alpha_epi - opt_.alpha_endo) * lerp_phi;
  const double beta = opt_.beta_endo + (opt_.beta_epi - opt_.beta_endo) * lerp_phi;
  Mat3 R;
  if (!biventricular()) {
    R = oriented(e, lambda, gradient(phi_, e, lambda), alpha, beta);
  } else {
    // Bayer's two-cavity rule (ldrb's tolerance 1e-7 for "this field is present here").
    constexpr double tol = 1e-7;
    const double lv = value(phi_lv_, e, lambda), rv = value(phi_rv_, e, lambda);
    const double d = lv + rv < tol ? 0.5 : rv / (lv + rv);
    const double alpha_s = opt_.alpha_endo * (1 - 2 * d), beta_s = opt_.beta_endo * (1 - 2 * d);
    Mat3 Qlv, Qrv, Qepi;
    const bool has_lv = lv > tol, has_rv = rv > tol, has_epi = lerp_phi > tol;
    if (has_lv) Qlv = oriented(e, lambda, -gradient(phi_lv_, e, lambda), alpha_s, beta_s);
    if (has_rv) Qrv = oriented(e, lambda, gradient(phi_rv_, e, lambda), alpha_s, beta_s);
    if (has_epi) Qepi = oriented(e, lambda, gradient(phi_, e, lambda), alpha, beta);
    if (!has_lv && !has_rv && !has_epi) Qepi = oriented(e, lambda, gradient(phi_, e, lambda), alpha, beta);
    const bool has_endo = has_lv || has_rv;
    const Mat3 Qendo = has_endo ? bislerp(has_lv ? &Qlv : nullptr, has_rv ? &Qrv : nullptr, d) : Mat3();
    R = bislerp(has_endo ? &Qendo : nullptr, (has_epi || !has_endo) ? &Qepi : nullptr, lerp_phi);
  }
  Mat3 Q;
  Q.col(0) = R.col(0);
  Q.col(1) = R.col(2);
  Q.col(2) = R.col(0).cross(R.col(2));
  return Q;
}

}  // namespace fe2
