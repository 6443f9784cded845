#include "coordinator/macro/FieldTable.h"

#include "common/error.h"

#include <algorithm>

namespace fe2 {

int Field::node_dof(int node, int i) const {
  FE2_CHECK(has_node(node) && i >= 0 && i < components(), "field '{}' has no component {} at node {}", name(), i,
            node);
  return offset_ + components() * index_of_node_[node] + i;
}

std::vector<int> Field::node_dofs(const std::vector<int>& nodes) const {
  std::vector<int> dofs;
  dofs.reserve(static_cast<size_t>(components()) * nodes.size());
  for (int a : nodes)
    for (int i = 0; i < components(); ++i) dofs.push_back(node_dof(a, i));
  return dofs;
}

int Field::element_dof(int e) const {
  if (e < 0 || e >= static_cast<int>(constant_of_element_.size()) || constant_of_element_[e] < 0) return -1;
  return offset_ + static_cast<int>(nodes_.size()) + constant_of_element_[e];
}

int Field::global_dof(int k) const {
  FE2_CHECK(decl_.space == FieldSpace::global && k >= 0 && k < size_, "field '{}' has no scalar {}", name(), k);
  return offset_ + k;
}

int FieldTable::add(FieldDecl decl) {
  FE2_CHECK(!numbered_, "field '{}' declared after the unknowns were numbered", decl.name);
  FE2_CHECK(!find(decl.name), "field '{}' declared twice", decl.name);
  FE2_CHECK(decl.components >= 1, "field '{}': {} components", decl.name, decl.components);
  Field f;
  f.decl_ = std::move(decl);
  f.id_ = static_cast<int>(fields_.size());
  fields_.push_back(std::move(f));
  return fields_.back().id_;
}

void FieldTable::number(const TetMesh& mesh) {
  FE2_CHECK(!numbered_, "the macro unknowns are numbered once");
  int offset = 0;
  for (Field& f : fields_) {
    const FieldDecl& d = f.decl_;
    f.offset_ = offset;
    if (d.space == FieldSpace::global) {
      f.size_ = d.count;
    } else {
      auto in_field = [&](int e) { return f.lives_on(mesh.region[e]); };
      std::vector<char> carries(mesh.num_nodes(), 0);
      std::vector<int> elements;
      for (int e = 0; e < mesh.num_tets(); ++e) {
        if (!in_field(e)) continue;
        elements.push_back(e);
        if (d.space == FieldSpace::nodal)
          for (int a : mesh.element_nodes(e)) carries[a] = 1;
        else
          for (int a : mesh.tets[e]) carries[a] = 1;
      }
      FE2_CHECK(!elements.empty(), "field '{}' has no elements (regions {})", d.name, fmt::join(d.regions, ", "));
      f.index_of_node_.assign(mesh.num_nodes(), -1);
      for (int a = 0; a < mesh.num_nodes(); ++a)
        if (carries[a]) {
          f.index_of_node_[a] = static_cast<int>(f.nodes_.size());
          f.nodes_.push_back(a);
        }
      f.size_ = d.components * static_cast<int>(f.nodes_.size());
      if (d.space == FieldSpace::vertex_element) {
        // The first element's constant would make the basis linearly dependent.
        f.constant_of_element_.assign(mesh.num_tets(), -1);
        for (size_t k = 1; k < elements.size(); ++k) f.constant_of_element_[elements[k]] = static_cast<int>(k) - 1;
        f.size_ += static_cast<int>(elements.size()) - 1;
      }
    }
    offset += f.size_;
  }
  num_dofs_ = offset;
  numbered_ = true;
}

bool Field::lives_on(int tag) const {
  if (decl_.space == FieldSpace::global) return false;
  return decl_.regions.empty() || std::find(decl_.regions.begin(), decl_.regions.end(), tag) != decl_.regions.end();
}

Eigen::VectorXd Field::at_every_node(const Eigen::VectorXd& x, int num_nodes) const {
  FE2_CHECK(decl_.space == FieldSpace::nodal, "field '{}' is not nodal", name());
  const int c = components();
  Eigen::VectorXd v = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(c) * num_nodes);
  for (int a : nodes_) v.segment(static_cast<Eigen::Index>(c) * a, c) = x.segment(node_dof(a), c);
  return v;
}

std::vector<int> FieldTable::element_weights(const TetMesh& mesh) const {
  const int vertices = 4, nodes = static_cast<int>(mesh.element_nodes(0).size());
  std::vector<int> w(static_cast<size_t>(mesh.num_tets()), 0);
  for (int e = 0; e < mesh.num_tets(); ++e) {
    int dofs = 0;
    for (const Field& f : fields_) {
      if (!f.lives_on(mesh.region[static_cast<size_t>(e)])) continue;
      const FieldSpace s = f.decl().space;
      dofs += f.components() * (s == FieldSpace::nodal ? nodes : vertices) + (s == FieldSpace::vertex_element);
    }
    w[static_cast<size_t>(e)] = std::max(1, dofs * dofs);  // METIS wants positive weights
  }
  return w;
}

const Field* FieldTable::find(const std::string& name) const {
  for (const Field& f : fields_)
    if (f.name() == name) return &f;
  return nullptr;
}

const Field& FieldTable::at(const std::string& name) const {
  if (const Field* f = find(name)) return *f;
  std::vector<std::string> names;
  for (const Field& f : fields_) names.push_back(f.name());
  throw Error(fmt::format("no macro field '{}'; the fields are: {}", name,
                          names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "))));
}

const Field& FieldTable::field_of(int dof) const {
  for (const Field& f : fields_)
    if (f.contains(dof)) return f;
  throw Error(fmt::format("DOF {} is outside every macro field ({} DOFs)", dof, num_dofs_));
}

}  // namespace fe2
