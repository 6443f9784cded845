#include "common/activation/ActivationField.h"

#include "common/error.h"

#include <cmath>

namespace fe2 {

ActivationField ActivationField::uniform(double time) {
  FE2_CHECK(std::isfinite(time), "activation: uniform time {}", time);
  ActivationField f;
  f.kind_ = Kind::uniform;
  f.time_ = time;
  return f;
}

ActivationField ActivationField::per_vertex(const TetMesh& mesh, std::vector<double> node_times) {
  FE2_CHECK(node_times.size() == mesh.nodes.size(), "activation: {} node times for {} nodes", node_times.size(),
            mesh.nodes.size());
  for (const auto& tet : mesh.tets)
    for (int v : tet) FE2_CHECK(std::isfinite(node_times[v]), "activation: vertex {} has time {}", v, node_times[v]);
  ActivationField f;
  f.kind_ = Kind::per_vertex;
  f.values_ = std::move(node_times);
  f.tets_ = mesh.tets;
  return f;
}

ActivationField ActivationField::per_element(std::vector<double> element_times) {
  for (std::size_t e = 0; e < element_times.size(); ++e)
    FE2_CHECK(std::isfinite(element_times[e]), "activation: element {} has time {}", e, element_times[e]);
  ActivationField f;
  f.kind_ = Kind::per_element;
  f.values_ = std::move(element_times);
  return f;
}

double ActivationField::at(int e, const Bary& l) const {
  switch (kind_) {
    case Kind::uniform:
      return time_;
    case Kind::per_element:
      FE2_CHECK(e >= 0 && e < static_cast<int>(values_.size()), "activation: element {} of {}", e, values_.size());
      return values_[e];
    case Kind::per_vertex: {
      FE2_CHECK(e >= 0 && e < static_cast<int>(tets_.size()), "activation: element {} of {}", e, tets_.size());
      const auto& v = tets_[e];
      return l[0] * values_[v[0]] + l[1] * values_[v[1]] + l[2] * values_[v[2]] + l[3] * values_[v[3]];
    }
  }
  return time_;
}

std::vector<double> ActivationField::node_times(const TetMesh& mesh) const {
  switch (kind_) {
    case Kind::uniform:
      return std::vector<double>(mesh.nodes.size(), time_);
    case Kind::per_vertex:
      FE2_CHECK(values_.size() == mesh.nodes.size(), "activation: field of {} nodes, mesh of {}", values_.size(),
                mesh.nodes.size());
      return values_;
    case Kind::per_element: {
      FE2_CHECK(values_.size() == mesh.tets.size(), "activation: field of {} elements, mesh of {}", values_.size(),
                mesh.tets.size());
      std::vector<double> sum(mesh.nodes.size(), 0.0), count(mesh.nodes.size(), 0.0);
      for (int e = 0; e < mesh.num_tets(); ++e)
        for (int n : mesh.element_nodes(e)) sum[n] += values_[e], count[n] += 1;
      for (std::size_t n = 0; n < sum.size(); ++n) sum[n] = count[n] > 0 ? sum[n] / count[n] : std::nan("");
      return sum;
    }
  }
  return {};
}

std::vector<double> ActivationField::element_times(const TetMesh& mesh) const {
  std::vector<double> out(mesh.tets.size());
  for (int e = 0; e < mesh.num_tets(); ++e) out[e] = at(e, kCentroid);
  return out;
}

}  // namespace fe2
