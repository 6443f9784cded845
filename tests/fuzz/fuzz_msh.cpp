// The Gmsh MSH 4.1 reader (common/mesh/gmsh_reader.h) on arbitrary text: every entry
// point a spec reaches (macro tets, unit hexes, element/node tags, fibre and
// activation views) must end in a mesh or an InputError naming the file.
#include "common/mesh/gmsh_reader.h"
#include "tests/fuzz/fuzz_support.h"

using namespace fe2;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& file = fuzz::as_file(data, size, ".msh");
  fuzz::expect_only<InputError>([&] {
    const TetMesh m = read_gmsh_tets(file);
    fuzz::require(m.num_tets() > 0 && m.region.size() == m.tets.size(), "a read mesh has tets");
    for (const auto& t : m.tets)
      for (int n : t) fuzz::require(n >= 0 && n < static_cast<int>(m.nodes.size()), "tet nodes in range");
    const GmshTags tags = read_gmsh_tags(file);
    fuzz::require(tags.elements.size() == m.tets.size() && tags.nodes.size() == m.nodes.size(),
                  "one tag per tet and per node");
  });
  fuzz::expect_only<InputError>([&] {
    const HexMesh h = read_gmsh_hexes(file);
    for (const auto& e : h.hexes)
      for (int n : e) fuzz::require(n >= 0 && n < static_cast<int>(h.nodes.size()), "hex nodes in range");
  });
  fuzz::expect_only<InputError>([&] {
    const GmshVectorView v = read_gmsh_vector_view(file, GmshDataOn::elements, "fibre");
    fuzz::require(v.values.size() == v.tags.size(), "one vector per tag");
  });
  fuzz::expect_only<InputError>([&] {
    const GmshScalarView v = read_gmsh_scalar_view(file, GmshDataOn::nodes, "activation");
    fuzz::require(v.values.size() == v.tags.size(), "one value per tag");
  });
  return 0;
}
