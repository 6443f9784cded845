#include "common/activation/activation_file.h"

#include "common/error.h"
#include "common/io/tagged_csv.h"
#include "common/mesh/gmsh_reader.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace fe2 {

namespace {

struct Entry {
  long long tag = 0;
  int line = 0;
  double time = 0;
};

const char* const kCsvForm = "tag,time";

std::vector<Entry> read_csv(const std::string& file) {
  std::vector<Entry> out;
  for (const TaggedRow& r : read_tagged_csv(file, 1, "activation file", kCsvForm, "tag a positive integer, time in s"))
    out.push_back({r.tag, r.line, r.values[0]});
  return out;
}

std::vector<Entry> read_gmsh(const ActivationFileOptions& opt) {
  const GmshScalarView view = read_gmsh_scalar_view(opt.file, GmshDataOn::elements, opt.view);
  std::vector<Entry> out;
  for (std::size_t i = 0; i < view.tags.size(); ++i) out.push_back({view.tags[i], view.lines[i], view.values[i]});
  return out;
}

}  // namespace

std::vector<double> read_activation_file(const TetMesh& mesh, const ActivationFileOptions& opt) {
  const std::size_t count = mesh.tets.size();
  std::vector<long long> tags(count);
  if (opt.mesh_file.empty()) {
    for (std::size_t i = 0; i < count; ++i) tags[i] = static_cast<long long>(i) + 1;
  } else {
    tags = read_gmsh_tags(opt.mesh_file).elements;
    FE2_CHECK(tags.size() == count, "mesh file '{}' gives {} element tags for {} elements", opt.mesh_file,
              tags.size(), count);
  }
  std::unordered_map<long long, std::size_t> index;
  for (std::size_t i = 0; i < count; ++i) index.emplace(tags[i], i);

  const std::vector<Entry> entries = opt.csv ? read_csv(opt.file) : read_gmsh(opt);
  std::vector<double> times(count, 0.0);
  std::vector<int> line_of(count, 0);
  for (const Entry& en : entries) {
    const auto where = fmt::format("activation file '{}' line {}: element {}", opt.file, en.line, en.tag);
    const auto it = index.find(en.tag);
    if (it == index.end()) {
      if (!opt.csv) continue;  // a Gmsh view may cover other elements (faces, lines) too
      throw InputError(fmt::format("{} is not an element of the mesh ({} elements, tags {}), expected the tag of a "
                                   "tetrahedron",
                                   where, count,
                                   opt.mesh_file.empty() ? "1.." + std::to_string(count)
                                                         : "as in '" + opt.mesh_file + "'"));
    }
    const std::size_t i = it->second;
    if (line_of[i] != 0)
      throw InputError(fmt::format("{} appears again (first at line {}), expected exactly one time per element", where,
                                   line_of[i]));
    if (!(std::isfinite(en.time) && en.time >= 0))
      throw InputError(fmt::format("{}: time {}, expected a finite activation time >= 0 (s)", where, en.time));
    line_of[i] = en.line;
    times[i] = en.time;
  }
  for (std::size_t i = 0; i < count; ++i)
    if (line_of[i] == 0)
      throw InputError(fmt::format("activation file '{}': no time for element {} (and {} more), expected one for "
                                   "every element of the mesh ({} elements)",
                                   opt.file, tags[i],
                                   std::count(line_of.begin() + static_cast<long>(i) + 1, line_of.end(), 0), count));
  return times;
}

}  // namespace fe2
