#include "worker/PeriodicDofMap.h"

#include "common/error.h"

#include <cmath>
#include <map>
#include <numeric>

namespace fe2 {

namespace {

using Key = std::array<long long, 3>;

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) { return parent[a] == a ? a : parent[a] = find(parent[a]); }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // smallest index is the root
  }
};

}  // namespace

PeriodicDofMap::PeriodicDofMap(const HexMesh& mesh, const std::string& source) {
  const int n = mesh.num_nodes();
  if (n == 0) throw InputError(fmt::format("micro mesh '{}' has no nodes", source));
  const Vec3 size = mesh.hi - mesh.lo;
  if (!(size.minCoeff() > 0.0))
    throw InputError(fmt::format("micro mesh '{}': cell size ({}, {}, {}) must be positive",
                                 source, size[0], size[1], size[2]));
  const double tol = 1e-8 * size.maxCoeff();
  auto key_of = [&](const Vec3& X) {
    Key k;
    for (int d = 0; d < 3; ++d) k[d] = std::llround((X[d] - mesh.lo[d]) / tol);
    return k;
  };
  std::map<Key, int> at;
  for (int a = 0; a < n; ++a) at.emplace(key_of(mesh.nodes[a]), a);

  UnionFind uf(n);
  const char* axis = "xyz";
  for (int a = 0; a < n; ++a) {
    const Vec3& X = mesh.nodes[a];
    for (int d = 0; d < 3; ++d) {
      const bool on_lo = std::abs(X[d] - mesh.lo[d]) <= tol;
      const bool on_hi = std::abs(X[d] - mesh.hi[d]) <= tol;
      if (!on_lo && !on_hi) continue;
      Vec3 image = X;
      image[d] = on_lo ? mesh.hi[d] : mesh.lo[d];
      auto it = at.find(key_of(image));
      if (it == at.end())
        throw InputError(fmt::format(
            "micro mesh '{}' is not periodic: node {} at ({:.6g}, {:.6g}, {:.6g}) on face "
            "{}={} has no image on the opposite face {}={}; expected matching nodes on "
            "opposite faces of the cell",
            source, a, X[0], X[1], X[2], axis[d], on_lo ? "lo" : "hi", axis[d],
            on_lo ? "hi" : "lo"));
      uf.unite(a, it->second);
    }
  }

  master_.resize(n);
  std::vector<int> index(n, -1);
  for (int a = 0; a < n; ++a) {
    master_[a] = uf.find(a);
    if (index[master_[a]] < 0) index[master_[a]] = num_masters_++;
  }
  pinned_ = master_[0];
  dof_.assign(3 * n, -1);
  // Masters in index order, pinned one skipped, three components each.
  std::vector<int> first_dof(num_masters_, -1);
  int next = 0;
  for (int a = 0; a < n; ++a) {
    const int m = master_[a];
    if (m == pinned_) continue;
    int& f = first_dof[index[m]];
    if (f < 0) f = next, next += 3;
    for (int i = 0; i < 3; ++i) dof_[3 * a + i] = f + i;
  }
  num_dofs_ = next;
}

}  // namespace fe2
