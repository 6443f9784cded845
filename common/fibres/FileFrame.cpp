#include "common/fibres/FileFrame.h"

#include "common/error.h"
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
};

std::vector<Entry> read_csv(const std::string& file) {
  std::vector<Entry> out;
  for (const TaggedRow& r :
       read_tagged_csv(file, 6, "fibre file", "tag,fx,fy,fz,sx,sy,sz", "tag a positive integer")) {
    const auto& v = r.values;
    out.push_back({r.tag, r.line, Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5])});
  }
  return out;
}

std::vector<Entry> read_gmsh(const FileFrameOptions& opt) {
  const GmshDataOn on = opt.per_node ? GmshDataOn::nodes : GmshDataOn::elements;
  const GmshVectorView f = read_gmsh_vector_view(opt.file, on, opt.fibre_view);
  const GmshVectorView s = read_gmsh_vector_view(opt.file, on, opt.sheet_view);
  std::unordered_map<long long, std::size_t> sheet_of;
  for (std::size_t i = 0; i < s.tags.size(); ++i) sheet_of.emplace(s.tags[i], i);
  const char* what = opt.per_node ? "node" : "element";
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

FileFrame::FileFrame(const TetMesh& mesh, const FileFrameOptions& opt) : per_node_(opt.per_node), file_(opt.file) {
  const char* what = per_node_ ? "node" : "element";
  const std::size_t count = per_node_ ? mesh.nodes.size() : mesh.tets.size();
  std::vector<long long> tags(count);
  if (opt.mesh_file.empty()) {
    for (std::size_t i = 0; i < count; ++i) tags[i] = static_cast<long long>(i) + 1;
  } else {
    GmshTags t = read_gmsh_tags(opt.mesh_file);
    tags = per_node_ ? std::move(t.nodes) : std::move(t.elements);
    FE2_CHECK(tags.size() == count, "mesh file '{}' gives {} {} tags for {} {}s", opt.mesh_file, tags.size(),
              what, count, what);
  }
  std::unordered_map<long long, std::size_t> index;
  for (std::size_t i = 0; i < count; ++i) index.emplace(tags[i], i);

  const std::vector<Entry> entries = opt.csv ? read_csv(opt.file) : read_gmsh(opt);
  f_.assign(count, Vec3::Zero());
  s_.assign(count, Vec3::Zero());
  std::vector<int> line_of(count, 0);
  for (const Entry& en : entries) {
    const auto where = fmt::format("fibre file '{}' line {}: {} {}", opt.file, en.line, what, en.tag);
    const auto it = index.find(en.tag);
    if (it == index.end()) {
      if (!opt.csv) continue;  // a Gmsh view may cover other elements (faces, lines) too
      throw InputError(fmt::format("{} is not a {} of the mesh ({} {}s, tags {}), expected the tag of a "
                                   "tetrahedron{}",
                                   where, what, count, what,
                                   opt.mesh_file.empty() ? "1.." + std::to_string(count) : "as in '" + opt.mesh_file + "'",
                                   per_node_ ? " node" : ""));
    }
    const std::size_t i = it->second;
    if (line_of[i] != 0)
      throw InputError(fmt::format("{} appears again (first at line {}), expected exactly one fibre and sheet per {}",
                                   where, line_of[i], what));
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
  for (std::size_t i = 0; i < count; ++i)
    if (line_of[i] == 0)
      throw InputError(fmt::format("fibre file '{}': no fibre and sheet for {} {} (and {} more), expected one "
                                   "for every {} of the mesh ({} {}s)",
                                   opt.file, what, tags[i],
                                   std::count(line_of.begin() + static_cast<long>(i) + 1, line_of.end(), 0), what,
                                   count, what));
  if (per_node_)
    for (int e = 0; e < mesh.num_tets(); ++e) element_nodes_.push_back(mesh.element_nodes(e));
}

Mat3 FileFrame::at(int e, const Bary& l, const Vec3&) const {
  Vec3 f, s;
  if (!per_node_) {
    f = f_[e];
    s = s_[e];
  } else {
    const std::vector<int>& n = element_nodes_[e];
    // Shape functions from λ: P1 λ_i; P2 λ_i(2λ_i − 1) at vertices, 4 λ_a λ_b on edges.
    double N[10];
    const bool p2 = n.size() == 10;
    for (int i = 0; i < 4; ++i) N[i] = p2 ? l[i] * (2 * l[i] - 1) : l[i];
    if (p2)
      for (int k = 0; k < 6; ++k) N[4 + k] = 4 * l[kTetEdges[k][0]] * l[kTetEdges[k][1]];
    f.setZero();
    s.setZero();
    for (std::size_t a = 0; a < n.size(); ++a) {
      const Vec3& fa = f_[n[a]];
      const Vec3& sa = s_[n[a]];
      f += N[a] * (fa.dot(f_[n[0]]) < 0 ? -fa : fa);
      s += N[a] * (sa.dot(s_[n[0]]) < 0 ? -sa : sa);
    }
  }
  Mat3 Q;
  if (!orthonormal_frame(f, s, Q))
    throw InputError(fmt::format("fibre file '{}': the interpolated fibre and sheet in element {} are zero or "
                                 "parallel (f = ({}, {}, {}), s = ({}, {}, {})), expected nodal vectors that vary "
                                 "smoothly",
                                 file_, e, f[0], f[1], f[2], s[0], s[1], s[2]));
  return Q;
}

}  // namespace fe2
