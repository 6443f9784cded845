#include "common/activation/activation_file.h"

#include "common/error.h"
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
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("cannot open activation file '{}' ({}), expected a CSV file of lines {}", file,
                                 std::strerror(errno), kCsvForm));
  std::vector<Entry> out;
  std::string line;
  bool first = true;  // the first line that is not blank or a comment may be a header
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    std::vector<double> v;
    std::vector<bool> ok;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) {
      const auto a = field.find_first_not_of(" \t"), b = field.find_last_not_of(" \t");
      double x = 0;
      const char* p = field.data() + (a == std::string::npos ? 0 : a);
      const char* q = field.data() + (a == std::string::npos ? 0 : b + 1);
      const auto [end, ec] = std::from_chars(p, q, x);
      ok.push_back(p != q && ec == std::errc() && end == q && std::isfinite(x));
      v.push_back(x);
    }
    const bool header = first && !ok.empty() && !ok[0];  // "tag,time"
    first = false;
    if (header) continue;
    const bool numbers = std::find(ok.begin(), ok.end(), false) == ok.end();
    if (!numbers || v.size() != 2 || v[0] != std::floor(v[0]) || v[0] < 1 || v[0] > 9e15)
      throw InputError(fmt::format("activation file '{}' line {}: got '{}', expected 2 comma-separated numbers {} "
                                   "(tag a positive integer, time in s)",
                                   file, n, line.substr(0, 80), kCsvForm));
    out.push_back({static_cast<long long>(v[0]), n, v[1]});
  }
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
