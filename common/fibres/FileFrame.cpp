#include "common/fibres/FileFrame.h"

#include "common/error.h"
#include "common/fibres/frame_interpolation.h"
#include "common/io/tagged_csv.h"
#include "common/mesh/gmsh_reader.h"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace fe2 {

namespace {

/// One vector of the file with where it came from.
struct Entry {
  long long tag = 0;
  int line = 0;
  Vec3 f, s;
  double point = 0;  ///< per point: the index in the rule, as read (checked against the rule)
};

std::vector<Entry> read_csv(const std::string& file, bool per_point) {
  std::vector<Entry> out;
  const int k = per_point ? 1 : 0;  // the point index comes before the vectors
  for (const TaggedRow& r :
       read_tagged_csv(file, 6 + k, "fibre file", per_point ? "tag,point,fx,fy,fz,sx,sy,sz" : "tag,fx,fy,fz,sx,sy,sz",
                       per_point ? "tag a positive integer, point the 0-based index in the element's quadrature rule"
                                 : "tag a positive integer")) {
    const auto& v = r.values;
    out.push_back({r.tag, r.line, Vec3(v[k], v[k + 1], v[k + 2]), Vec3(v[k + 3], v[k + 4], v[k + 5]),
                   per_point ? v[0] : 0.0});
  }
  return out;
}

std::vector<Entry> read_gmsh(const FileFrameOptions& opt) {
  const GmshDataOn on = opt.per == FramePer::node ? GmshDataOn::nodes : GmshDataOn::elements;
  const GmshVectorView f = read_gmsh_vector_view(opt.file, on, opt.fibre_view);
  const GmshVectorView s = read_gmsh_vector_view(opt.file, on, opt.sheet_view);
  std::unordered_map<long long, std::size_t> sheet_of;
  for (std::size_t i = 0; i < s.tags.size(); ++i) sheet_of.emplace(s.tags[i], i);
  const char* what = opt.per == FramePer::node ? "node" : "element";
  std::vector<Entry> out;
  for (std::size_t i = 0; i < f.tags.size(); ++i) {
    const auto it = sheet_of.find(f.tags[i]);
    if (it == sheet_of.end())
      throw InputError(fmt::format("fibre file '{}' line {}: {} {} has a \"{}\" vector but no \"{}\" vector, "
                                   "expected both for every {}",
                                   opt.file, f.lines[i], what, f.tags[i], opt.fibre_view, opt.sheet_view, what));
    out.push_back({f.tags[i], f.lines[i], f.values[i], s.values[it->second]});
  }
  if (s.tags.size() > f.tags.size()) {
    std::unordered_map<long long, int> has_f;
    for (long long t : f.tags) has_f[t] = 1;
    for (std::size_t i = 0; i < s.tags.size(); ++i)
      if (!has_f.count(s.tags[i]))
        throw InputError(fmt::format("fibre file '{}' line {}: {} {} has a \"{}\" vector but no \"{}\" vector, "
                                     "expected both for every {}",
                                     opt.file, s.lines[i], what, s.tags[i], opt.sheet_view, opt.fibre_view, what));
  }
  return out;
}

}  // namespace

FileFrame::FileFrame(const TetMesh& mesh, const FileFrameOptions& opt) : per_(opt.per), file_(opt.file) {
  const bool per_node = per_ == FramePer::node, per_point = per_ == FramePer::point;
  const char* what = per_node ? "node" : "element";
  const std::size_t count = per_node ? mesh.nodes.size() : mesh.tets.size();
  int degree = 0;
  if (per_point) {
    if (!opt.csv)
      throw InputError(fmt::format("fibre file '{}': frames per point are read from a CSV (tag,point,fx,fy,fz,sx,sy,sz), "
                                   "not from Gmsh views; expected format \"csv\"",
                                   opt.file));
    degree = opt.quadrature_degree < 0 ? default_point_degree(mesh.order()) : opt.quadrature_degree;
    rule_ = tet_rule(degree);
  }
  const std::size_t np = per_point ? rule_.size() : 1;  // entries per element (or node)
  std::vector<long long> tags(count);
  if (opt.mesh_file.empty()) {
    for (std::size_t i = 0; i < count; ++i) tags[i] = static_cast<long long>(i) + 1;
  } else {
    GmshTags t = read_gmsh_tags(opt.mesh_file);
    tags = per_node ? std::move(t.nodes) : std::move(t.elements);
    FE2_CHECK(tags.size() == count, "mesh file '{}' gives {} {} tags for {} {}s", opt.mesh_file, tags.size(),
              what, count, what);
  }
  std::unordered_map<long long, std::size_t> index;
  for (std::size_t i = 0; i < count; ++i) index.emplace(tags[i], i);
  const std::string rule_text =
      fmt::format("the quadrature rule of degree {} has {} points per element (0..{})", degree, np, np - 1);

  const std::vector<Entry> entries = opt.csv ? read_csv(opt.file, per_point) : read_gmsh(opt);
  f_.assign(count * np, Vec3::Zero());
  s_.assign(count * np, Vec3::Zero());
  std::vector<int> line_of(count * np, 0);
  for (const Entry& en : entries) {
    const auto where = per_point ? fmt::format("fibre file '{}' line {}: element {} point {}", opt.file, en.line, en.tag,
                                               en.point)
                                 : fmt::format("fibre file '{}' line {}: {} {}", opt.file, en.line, what, en.tag);
    const auto it = index.find(en.tag);
    if (it == index.end()) {
      if (!opt.csv) continue;  // a Gmsh view may cover other elements (faces, lines) too
      throw InputError(fmt::format("{} is not a {} of the mesh ({} {}s, tags {}), expected the tag of a "
                                   "tetrahedron{}",
                                   where, what, count, what,
                                   opt.mesh_file.empty() ? "1.." + std::to_string(count) : "as in '" + opt.mesh_file + "'",
                                   per_node ? " node" : ""));
    }
    if (per_point && !(en.point >= 0 && en.point < static_cast<double>(np) && en.point == std::floor(en.point)))
      throw InputError(fmt::format("{}: no such point: {}, got point {}; expected a file written for that rule "
                                   "(formulation.quadrature_degree)",
                                   where, rule_text, en.point));
    const std::size_t i = it->second * np + (per_point ? static_cast<std::size_t>(en.point) : 0);
    if (line_of[i] != 0)
      throw InputError(fmt::format("{} appears again (first at line {}), expected exactly one fibre and sheet per {}",
                                   where, line_of[i], per_point ? "point" : what));
    line_of[i] = en.line;
    for (const auto& [name, v] : {std::pair<const char*, const Vec3&>{"fibre", en.f}, {"sheet", en.s}})
      if (!(std::abs(v.norm() - 1.0) <= kFrameFileTolerance))
        throw InputError(fmt::format("{}: {} vector ({}, {}, {}) has length {:.6g}, expected a unit vector "
                                     "(length within {} of 1)",
                                     where, name, v[0], v[1], v[2], v.norm(), kFrameFileTolerance));
    if (!(std::abs(en.f.dot(en.s)) <= kFrameFileTolerance))
      throw InputError(fmt::format("{}: fibre and sheet are not orthogonal (f·s = {:.6g}), expected |f·s| <= {}",
                                   where, en.f.dot(en.s), kFrameFileTolerance));
    f_[i] = en.f;
    s_[i] = en.s;
  }
  for (std::size_t i = 0; i < count * np; ++i) {
    if (line_of[i] != 0) continue;
    const long long more = std::count(line_of.begin() + static_cast<long>(i) + 1, line_of.end(), 0);
    if (!per_point)
      throw InputError(fmt::format("fibre file '{}': no fibre and sheet for {} {} (and {} more), expected one "
                                   "for every {} of the mesh ({} {}s)",
                                   opt.file, what, tags[i], more, what, count, what));
    const std::size_t e = i / np;
    const long long given = std::count_if(line_of.begin() + static_cast<long>(e * np),
                                          line_of.begin() + static_cast<long>((e + 1) * np), [](int l) { return l != 0; });
    throw InputError(fmt::format("fibre file '{}': no fibre and sheet for element {} point {} (and {} more points "
                                 "missing); the file gives {} points for element {}, expected {}: {}",
                                 opt.file, tags[e], i % np, more, given, tags[e], np, rule_text));
  }
  if (per_node)
    for (int e = 0; e < mesh.num_tets(); ++e) element_nodes_.push_back(mesh.element_nodes(e));
  if (per_node || per_point)
    for (std::size_t i = 0; i < f_.size(); ++i) q_.emplace_back(frame(i));
}

Mat3 FileFrame::frame(std::size_t i) const {
  Mat3 Q;
  // Cannot fail: every pair was checked unit and orthogonal to 1e-3 on reading.
  FE2_CHECK(orthonormal_frame(f_[i], s_[i], Q), "fibre file '{}': frame {} is degenerate", file_, i);
  return Q;
}

Mat3 FileFrame::at(int e, const Bary& l, const Vec3&) const {
  if (per_ == FramePer::element) return frame(static_cast<std::size_t>(e));
  if (per_ == FramePer::point) {
    const std::size_t np = rule_.size(), first = static_cast<std::size_t>(e) * np;
    for (std::size_t k = 0; k < np; ++k) {
      const Vec4& b = rule_[k].bary;
      if (std::abs(l[0] - b[0]) <= kFramePointMatch && std::abs(l[1] - b[1]) <= kFramePointMatch &&
          std::abs(l[2] - b[2]) <= kFramePointMatch && std::abs(l[3] - b[3]) <= kFramePointMatch)
        return frame(first + k);
    }
    // Not a point of the rule: the element's mean frame (a rule's weights sum to 1/6).
    std::vector<double> w(np);
    for (std::size_t k = 0; k < np; ++k) w[k] = 6 * rule_[k].weight;
    return frame_mean(std::span(q_).subspan(first, np), w);
  }
  const std::vector<int>& n = element_nodes_[e];
  // Shape functions from λ: P1 λ_i; P2 λ_i(2λ_i − 1) at vertices, 4 λ_a λ_b on edges.
  // The P2 ones are used as they are, negative ones included: frame_mean applies them in
  // the tangent space at the mean (an affine combination of rotation vectors), so the
  // midside frames count and a helix angle is interpolated quadratically. The vertex
  // frames with λ alone would drop the midside data of a quadratic mesh.
  double N[10];
  const bool p2 = n.size() == 10;
  for (int i = 0; i < 4; ++i) N[i] = p2 ? l[i] * (2 * l[i] - 1) : l[i];
  if (p2)
    for (int k = 0; k < 6; ++k) N[4 + k] = 4 * l[kTetEdges[k][0]] * l[kTetEdges[k][1]];
  if (!p2) {
    const Eigen::Quaterniond q[4] = {q_[n[0]], q_[n[1]], q_[n[2]], q_[n[3]]};
    return frame_mean(q, std::span(N, 4));  // every vertex aligned to vertex 0: one edge
  }
  // P2: aligned along the edges, vertex 0 → midsides 01, 02, 03 → vertices 1, 2, 3 →
  // midsides 12, 13, 23, so each step spans half an edge: a wall one element thick
  // may turn by up to 180° (each step below 90°) and keep its handedness.
  // kTetEdges: 01, 12, 02, 03, 13, 23 are nodes 4..9.
  static constexpr int order[10] = {0, 4, 6, 7, 1, 2, 3, 5, 8, 9};
  static constexpr int align_to[10] = {0, 0, 0, 0, 1, 2, 3, 4, 4, 5};  // positions in `order`
  Eigen::Quaterniond q[10];
  double w[10];
  for (int a = 0; a < 10; ++a) {
    q[a] = q_[n[order[a]]];
    w[a] = N[order[a]];
  }
  return frame_mean(q, w, align_to);
}

}  // namespace fe2
