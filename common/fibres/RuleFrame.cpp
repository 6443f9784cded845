#include "common/fibres/RuleFrame.h"

#include "common/error.h"
#include "common/fibres/laplace_p1.h"

#include <Eigen/Geometry>

#include <cmath>

namespace fe2 {

namespace {

constexpr double kDeg = M_PI / 180.0;

/// A named node set of the mesh (named faces are node sets too), or an InputError.
const std::vector<int>& named_set(const TetMesh& mesh, const std::string& key, const std::string& name) {
  const auto it = mesh.node_sets.find(name);
  if (it == mesh.node_sets.end() || it->second.empty()) {
    std::string known;
    for (const auto& [n, nodes] : mesh.node_sets) known += (known.empty() ? "" : ", ") + n;
    throw InputError(fmt::format("frame rule: '{}' = \"{}\" is not a named surface or node set of the mesh "
                                 "(it has: {}), expected one that exists and is not empty",
                                 key, name, known.empty() ? "none" : known));
  }
  return it->second;
}

Vec3 centroid(const TetMesh& mesh, const std::vector<int>& nodes) {
  Vec3 c = Vec3::Zero();
  for (int v : nodes) c += mesh.nodes[v];
  return c / static_cast<double>(nodes.size());
}

}  // namespace

Mat3 bislerp(const Mat3* Qa, const Mat3* Qb, double t) {
  if (!Qa) return *Qb;
  if (!Qb) return *Qa;
  const Eigen::Quaterniond qa(*Qa), qb(*Qb);
  Eigen::Quaterniond best = qa;
  double best_dot = -1;
  // qa·i, qa·j, qa·k turn the frame by π about its own axes: the same fibre, sheet and
  // normal lines. ±q is handled by Eigen's slerp, which takes the shorter arc.
  for (const Eigen::Quaterniond& turn : {Eigen::Quaterniond(1, 0, 0, 0), Eigen::Quaterniond(0, 1, 0, 0),
                                         Eigen::Quaterniond(0, 0, 1, 0), Eigen::Quaterniond(0, 0, 0, 1)}) {
    const Eigen::Quaterniond q = qa * turn;
    const double d = std::abs(q.dot(qb));
    if (d > best_dot) {
      best_dot = d;
      best = q;
    }
  }
  return best.slerp(t, qb).toRotationMatrix();
}

RuleFrame::RuleFrame(const TetMesh& mesh, RuleFrameOptions opt) : opt_(std::move(opt)), tets_(mesh.tets) {
  const auto& apex = named_set(mesh, "apex", opt_.apex);
  const auto& base = named_set(mesh, "base", opt_.base);
  const auto& endo = named_set(mesh, "endo", opt_.endo);
  const auto& epi = named_set(mesh, "epi", opt_.epi);
  grads_.reserve(tets_.size());
  for (int e = 0; e < mesh.num_tets(); ++e) grads_.push_back(p1_gradients(mesh, e));
  Vec3 lo = mesh.nodes.front(), hi = lo;
  for (const Vec3& x : mesh.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  length_ = (hi - lo).norm();
  const Vec3 axis = centroid(mesh, base) - centroid(mesh, apex);
  if (axis.norm() > 1e-12 * length_) long_axis_ = axis.normalized();

  psi_ = solve_laplace_p1(mesh, {{opt_.apex, apex, 0.0}, {opt_.base, base, 1.0}}, "frame rule, apico-basal ψ");
  if (!biventricular()) {
    phi_ = solve_laplace_p1(mesh, {{opt_.endo, endo, 0.0}, {opt_.epi, epi, 1.0}}, "frame rule, transmural φ");
    return;
  }
  const auto& rv = named_set(mesh, "rv_endo", opt_.rv_endo);
  phi_ = solve_laplace_p1(mesh, {{opt_.endo, endo, 0.0}, {opt_.rv_endo, rv, 0.0}, {opt_.epi, epi, 1.0}},
                          "frame rule, transmural φ_epi");
  phi_lv_ = solve_laplace_p1(mesh, {{opt_.endo, endo, 1.0}, {opt_.rv_endo, rv, 0.0}, {opt_.epi, epi, 0.0}},
                             "frame rule, φ_lv");
  phi_rv_ = solve_laplace_p1(mesh, {{opt_.endo, endo, 0.0}, {opt_.rv_endo, rv, 1.0}, {opt_.epi, epi, 0.0}},
                             "frame rule, φ_rv");
}

double RuleFrame::value(const std::vector<double>& u, int e, const Bary& l) const {
  const auto& t = tets_[e];
  return l[0] * u[t[0]] + l[1] * u[t[1]] + l[2] * u[t[2]] + l[3] * u[t[3]];
}

Vec3 RuleFrame::gradient(const std::vector<double>& u, int e) const {
  const auto& t = tets_[e];
  const auto& g = grads_[e];
  return u[t[0]] * g[0] + u[t[1]] * g[1] + u[t[2]] * g[2] + u[t[3]] * g[3];
}

double RuleFrame::transmural(int e, const Bary& l) const { return value(phi_, e, l); }

Mat3 RuleFrame::oriented(int e, const Vec3& g, double alpha, double beta) const {
  // Gradients of fields that vary by 1 across the heart are ~1/length; far less is zero.
  const double tiny = 1e-10 / length_;
  if (!(g.norm() > tiny))
    throw InputError(fmt::format("frame rule: the transmural gradient vanishes in element {} (|∇φ| = {:.3g}), "
                                 "expected the '{}' and '{}' surfaces on opposite sides of the wall",
                                 e, g.norm(), opt_.endo, opt_.epi));
  const Vec3 t = g.normalized();
  const Vec3 gpsi = gradient(psi_, e);
  Vec3 l = gpsi - gpsi.dot(t) * t;
  if (!(gpsi.norm() > tiny) || !(l.norm() > 1e-6 * gpsi.norm())) {
    l = long_axis_ - long_axis_.dot(t) * t;  // fallback 1: the mesh's long axis
    if (!(l.norm() > 1e-6)) l = t.unitOrthogonal();  // fallback 2: wall normal along the axis
  }
  l.normalize();
  const Vec3 c = l.cross(t);
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
    R = oriented(e, gradient(phi_, e), alpha, beta);
  } else {
    // Bayer's two-cavity rule (ldrb's tolerance 1e-7 for "this field is present here").
    constexpr double tol = 1e-7;
    const double lv = value(phi_lv_, e, lambda), rv = value(phi_rv_, e, lambda);
    const double d = lv + rv < tol ? 0.5 : rv / (lv + rv);
    const double alpha_s = opt_.alpha_endo * (1 - 2 * d), beta_s = opt_.beta_endo * (1 - 2 * d);
    Mat3 Qlv, Qrv, Qepi;
    const bool has_lv = lv > tol, has_rv = rv > tol, has_epi = lerp_phi > tol;
    if (has_lv) Qlv = oriented(e, -gradient(phi_lv_, e), alpha_s, beta_s);
    if (has_rv) Qrv = oriented(e, gradient(phi_rv_, e), alpha_s, beta_s);
    if (has_epi) Qepi = oriented(e, gradient(phi_, e), alpha, beta);
    if (!has_lv && !has_rv && !has_epi) Qepi = oriented(e, gradient(phi_, e), alpha, beta);
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
