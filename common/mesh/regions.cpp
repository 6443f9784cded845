#include "common/mesh/regions.h"

#include "common/error.h"

#include <algorithm>

namespace fe2 {

std::vector<int> interface_nodes(const TetMesh& mesh, const std::vector<int>& a, const std::vector<int>& b) {
  auto in = [](const std::vector<int>& tags, int t) { return std::find(tags.begin(), tags.end(), t) != tags.end(); };
  std::vector<char> side(mesh.num_nodes(), 0);  // bit 1: touches a, bit 2: touches b
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const char bits = static_cast<char>((in(a, mesh.region[e]) ? 1 : 0) | (in(b, mesh.region[e]) ? 2 : 0));
    if (bits)
      for (int n : mesh.element_nodes(e)) side[n] |= bits;
  }
  std::vector<int> nodes;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (side[n] == 3) nodes.push_back(n);
  return nodes;
}

std::vector<int> interface_nodes(const TetMesh& mesh, const std::string& name) {
  const auto it = mesh.interfaces.find(name);
  if (it == mesh.interfaces.end()) {
    std::vector<std::string> known;
    for (const auto& [n, _] : mesh.interfaces) known.push_back(n);
    throw InputError(fmt::format("interface '{}': the mesh has none of that name, expected one of its "
                                 "interfaces ({})",
                                 name, known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
  }
  return mesh.surface_nodes(it->second);
}

}  // namespace fe2
