#include "common/mesh/gmsh_reader.h"

#include "common/error.h"
#include "common/spec/SpecNode.h"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <unordered_map>

namespace fe2 {

namespace {

// Keeps messages readable when the offending text is a run of binary garbage.
std::string printable(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (s.size() > 40) out += "...";
  return out;
}

// ---------------------------------------------------------------------------------
// Tokens of an MSH file, each with the line it came from so errors can point at it.
// Every read is bounds-checked: garbage input ends in an InputError, never a crash.
class MshLexer {
 public:
  MshLexer(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }

  [[noreturn]] void fail(const std::string& msg) const {
    throw InputError(fmt::format("mesh file '{}' line {}: {}", file_, line_, msg));
  }

  /// True if only whitespace remains.
  bool at_end() {
    skip_space();
    return pos_ >= text_.size();
  }

  std::string_view token(std::string_view what) {
    if (at_end()) fail(fmt::format("unexpected end of file, expected {}", what));
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return std::string_view(text_).substr(start, pos_ - start);
  }

  long long integer(std::string_view what, long long lo = INT_MIN, long long hi = INT_MAX) {
    const std::string_view tok = token(what);
    long long value = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), value);
    if (ec != std::errc() || end != tok.data() + tok.size() || value < lo || value > hi)
      fail(fmt::format("found '{}', expected {} (an integer in [{}, {}])", printable(tok), what, lo, hi));
    return value;
  }

  int small_int(std::string_view what, int lo = INT_MIN, int hi = INT_MAX) {
    return static_cast<int>(integer(what, lo, hi));
  }

  double real(std::string_view what) {
    const std::string_view tok = token(what);
    double value = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), value);
    if (ec != std::errc() || end != tok.data() + tok.size() || !std::isfinite(value))
      fail(fmt::format("found '{}', expected {} (a finite number)", printable(tok), what));
    return value;
  }

  /// A double-quoted string on one line (physical names may contain spaces).
  std::string quoted(std::string_view what) {
    if (at_end() || text_[pos_] != '"')
      fail(fmt::format("found '{}', expected {} in double quotes", printable(peek_rest_of_line()), what));
    const std::size_t close = text_.find_first_of("\"\n", pos_ + 1);
    if (close == std::string::npos || text_[close] != '"')
      fail(fmt::format("unterminated string, expected {} in double quotes", what));
    std::string s = text_.substr(pos_ + 1, close - pos_ - 1);
    pos_ = close + 1;
    return s;
  }

  void expect(std::string_view keyword) {
    const std::string_view tok = token(keyword);
    if (tok != keyword) fail(fmt::format("found '{}', expected {}", printable(tok), keyword));
  }

  /// Moves past the end of the current line.
  void skip_line() {
    const std::size_t nl = text_.find('\n', pos_);
    if (nl == std::string::npos) fail("unexpected end of file inside a section");
    pos_ = nl + 1;
    ++line_;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  std::string_view peek_rest_of_line() const {
    const std::size_t nl = std::min(text_.find('\n', pos_), text_.size());
    return std::string_view(text_).substr(std::min(pos_, text_.size()), nl - std::min(pos_, text_.size()));
  }

  std::string text_, file_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// ---------------------------------------------------------------------------------
// The parts of an MSH file fe2heart uses, still in the file's own numbering.

using DimTag = std::pair<int, int>;  // (dimension, tag) names an entity or a physical group

constexpr int kLine = 1, kTriangle = 2, kTet = 4, kHex = 5, kLine3 = 8, kTriangle6 = 9, kTet10 = 11,
              kPoint = 15;

int nodes_per_element(int type) {
  switch (type) {
    case kLine: return 2;
    case kTriangle: return 3;
    case kTet: return 4;
    case kHex: return 8;
    case kLine3: return 3;
    case kTriangle6: return 6;
    case kTet10: return 10;
    case kPoint: return 1;
    default: return 0;  // a type fe2heart does not read
  }
}

struct ElementBlock {
  int dim = 0, entity = 0, type = 0, nodes_per = 0;
  std::vector<long long> tags;  ///< element tags
  std::vector<int> lines;       ///< file line of each element
  std::vector<int> nodes;       ///< nodes_per per element, as positions in MshData::node_tags
};

/// One $NodeData or $ElementData section (a post-processing view at one time step).
struct DataView {
  bool on_elements = false;     ///< $ElementData (else $NodeData)
  std::string name;             ///< its first string tag
  int line = 0;                 ///< file line of the section header
  int components = 0;
  std::vector<long long> tags;  ///< node or element tag of each entry
  std::vector<int> lines;       ///< file line of each entry
  std::vector<double> values;   ///< components per entry
};

struct MshData {
  std::string file;
  std::map<DimTag, std::string> physical_names;
  std::map<DimTag, std::vector<int>> entity_physicals;  ///< entity -> its physical tags
  std::vector<long long> node_tags;                     ///< file order
  std::vector<Vec3> coords;
  std::unordered_map<long long, int> node_position;     ///< node tag -> index in node_tags
  std::vector<ElementBlock> blocks;                     ///< blocks of the element types we read
  std::set<int> element_types;                          ///< every element type in the file
  std::vector<DataView> views;                          ///< $NodeData / $ElementData sections

  std::vector<const ElementBlock*> blocks_of(int type) const {
    std::vector<const ElementBlock*> out;
    for (const auto& b : blocks)
      if (b.type == type) out.push_back(&b);
    return out;
  }
  const std::vector<int>& physicals_of(int dim, int entity) const {
    static const std::vector<int> none;
    const auto it = entity_physicals.find({dim, entity});
    return it == entity_physicals.end() ? none : it->second;
  }
  /// Names of the named physical groups an entity belongs to.
  std::vector<std::string> names_of(int dim, int entity) const {
    std::vector<std::string> names;
    for (int tag : physicals_of(dim, entity)) {
      const auto it = physical_names.find({dim, tag});
      if (it != physical_names.end()) names.push_back(it->second);
    }
    return names;
  }
};

void parse_mesh_format(MshLexer& lex) {
  const std::string version(lex.token("the MSH version"));
  if (version != "4.1") lex.fail(fmt::format("MeshFormat {}, expected 4.1 ASCII", version));
  const long long file_type = lex.integer("the file type (0 = ASCII)", LLONG_MIN, LLONG_MAX);
  if (file_type != 0)
    lex.fail(fmt::format("binary MSH file (file type {}), expected 4.1 ASCII (save with Mesh.Binary = 0)",
                         file_type));
  lex.integer("the data size", 1, 16);
  lex.expect("$EndMeshFormat");
}

void parse_physical_names(MshLexer& lex, MshData& d) {
  const long long n = lex.integer("the number of physical names", 0, INT_MAX);
  for (long long i = 0; i < n; ++i) {
    const int dim = lex.small_int("a physical group dimension", 0, 3);
    const int tag = lex.small_int("a physical tag");
    d.physical_names[{dim, tag}] = lex.quoted("a physical name");
  }
  lex.expect("$EndPhysicalNames");
}

// One entity line: tag, its bounding box (a point has just X Y Z), physical tags and,
// for curves, surfaces and volumes, the tags of its bounding entities.
void parse_entity(MshLexer& lex, MshData& d, int dim) {
  const int tag = lex.small_int("an entity tag");
  for (int i = 0; i < (dim == 0 ? 3 : 6); ++i) lex.real("an entity coordinate");
  const long long num_physicals = lex.integer("the number of physical tags", 0, INT_MAX);
  std::vector<int>& physicals = d.entity_physicals[{dim, tag}];
  for (long long i = 0; i < num_physicals; ++i) physicals.push_back(lex.small_int("a physical tag"));
  if (dim == 0) return;
  const long long num_bounding = lex.integer("the number of bounding entities", 0, INT_MAX);
  for (long long i = 0; i < num_bounding; ++i) lex.small_int("a bounding entity tag");
}

void parse_entities(MshLexer& lex, MshData& d) {
  std::array<long long, 4> counts{};
  for (auto& c : counts) c = lex.integer("the number of entities", 0, INT_MAX);
  for (int dim = 0; dim < 4; ++dim)
    for (long long i = 0; i < counts[dim]; ++i) parse_entity(lex, d, dim);
  lex.expect("$EndEntities");
}

void parse_nodes(MshLexer& lex, MshData& d) {
  const long long num_blocks = lex.integer("the number of node blocks", 0, INT_MAX);
  const long long num_nodes = lex.integer("the number of nodes", 0, INT_MAX);
  lex.integer("the minimum node tag", 0, LLONG_MAX);
  lex.integer("the maximum node tag", 0, LLONG_MAX);
  for (long long b = 0; b < num_blocks; ++b) {
    const int dim = lex.small_int("an entity dimension", 0, 3);
    lex.small_int("an entity tag");
    const int parametric = lex.small_int("the parametric flag", 0, 1);
    const long long n = lex.integer("the number of nodes in the block", 0, INT_MAX);
    const std::size_t first = d.node_tags.size();
    for (long long i = 0; i < n; ++i) {
      const long long tag = lex.integer("a node tag", 1, LLONG_MAX);
      if (!d.node_position.emplace(tag, static_cast<int>(d.node_tags.size())).second)
        lex.fail(fmt::format("node tag {} appears twice, expected unique node tags", tag));
      d.node_tags.push_back(tag);
      if (d.node_tags.size() > static_cast<std::size_t>(num_nodes))
        lex.fail(fmt::format("more nodes than the {} announced in the $Nodes header", num_nodes));
    }
    for (std::size_t i = first; i < d.node_tags.size(); ++i) {
      Vec3 x;
      for (int a = 0; a < 3; ++a) x[a] = lex.real("a node coordinate");
      for (int a = 0; a < (parametric ? dim : 0); ++a) lex.real("a parametric node coordinate");
      d.coords.push_back(x);
    }
  }
  if (d.node_tags.size() != static_cast<std::size_t>(num_nodes))
    lex.fail(fmt::format("{} nodes in the blocks, expected the {} announced in the $Nodes header",
                         d.node_tags.size(), num_nodes));
  lex.expect("$EndNodes");
}

void parse_element_block(MshLexer& lex, MshData& d, long long& count) {
  ElementBlock b;
  b.dim = lex.small_int("an entity dimension", 0, 3);
  b.entity = lex.small_int("an entity tag");
  b.type = lex.small_int("an element type", 1, INT_MAX);
  const long long n = lex.integer("the number of elements in the block", 0, INT_MAX);
  count += n;
  d.element_types.insert(b.type);
  b.nodes_per = nodes_per_element(b.type);
  if (b.nodes_per == 0) {
    // Gmsh writes one element per line, so types we do not read are skipped by line.
    lex.skip_line();
    for (long long i = 0; i < n; ++i) lex.skip_line();
    return;
  }
  for (long long i = 0; i < n; ++i) {
    b.tags.push_back(lex.integer("an element tag", 1, LLONG_MAX));
    b.lines.push_back(lex.line());
    for (int a = 0; a < b.nodes_per; ++a) {
      const long long tag = lex.integer("a node tag of the element", 1, LLONG_MAX);
      const auto it = d.node_position.find(tag);
      if (it == d.node_position.end())
        lex.fail(fmt::format("element {} uses node tag {}, expected a node listed in $Nodes", b.tags.back(), tag));
      b.nodes.push_back(it->second);
    }
  }
  d.blocks.push_back(std::move(b));
}

void parse_elements(MshLexer& lex, MshData& d) {
  const long long num_blocks = lex.integer("the number of element blocks", 0, INT_MAX);
  const long long num_elements = lex.integer("the number of elements", 0, LLONG_MAX);
  lex.integer("the minimum element tag", 0, LLONG_MAX);
  lex.integer("the maximum element tag", 0, LLONG_MAX);
  long long count = 0;
  for (long long b = 0; b < num_blocks; ++b) parse_element_block(lex, d, count);
  if (count != num_elements)
    lex.fail(fmt::format("{} elements in the blocks, expected the {} announced in the $Elements header", count,
                         num_elements));
  lex.expect("$EndElements");
}

// $NodeData/$ElementData: string tags (the first is the view name), real tags (time),
// integer tags (time step, components, entries[, partition]), then "tag v1 .. vc" lines.
void parse_data_view(MshLexer& lex, MshData& d, const std::string& section) {
  DataView v;
  v.on_elements = section == "ElementData";
  v.line = lex.line();
  const long long num_strings = lex.integer("the number of string tags", 0, 1000);
  for (long long i = 0; i < num_strings; ++i) {
    std::string t = lex.quoted("a string tag (the view name)");
    if (i == 0) v.name = std::move(t);
  }
  const long long num_reals = lex.integer("the number of real tags", 0, 1000);
  for (long long i = 0; i < num_reals; ++i) lex.real("a real tag (time)");
  const long long num_ints = lex.integer("the number of integer tags", 3, 1000);
  lex.integer("the time step");
  v.components = lex.small_int("the number of components", 1, 9);
  const long long n = lex.integer("the number of entries", 0, INT_MAX);
  for (long long i = 3; i < num_ints; ++i) lex.integer("an integer tag");
  for (long long i = 0; i < n; ++i) {
    v.tags.push_back(lex.integer(v.on_elements ? "an element tag" : "a node tag", 1, LLONG_MAX));
    v.lines.push_back(lex.line());
    for (int c = 0; c < v.components; ++c) v.values.push_back(lex.real("a data value"));
  }
  lex.expect("$End" + section);
  d.views.push_back(std::move(v));
}

void skip_section(MshLexer& lex, const std::string& name) {
  const std::string end = "$End" + name;
  while (lex.token(end) != end) {
  }
}

std::string read_file_text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(fmt::format("cannot open mesh file '{}' ({}), expected a readable Gmsh MSH 4.1 file", file,
                                 std::strerror(errno)));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

MshData parse_msh_file(const std::string& file, bool require_mesh = true) {
  MshLexer lex(read_file_text(file), file);
  MshData d;
  d.file = file;
  std::set<std::string> seen;
  while (!lex.at_end()) {
    const std::string_view tok = lex.token("a section");
    if (tok.size() < 2 || tok[0] != '$')
      lex.fail(fmt::format("found '{}', expected a section such as $Nodes", printable(tok)));
    const std::string name(tok.substr(1));
    if (seen.empty() && name != "MeshFormat")
      lex.fail(fmt::format("found ${}, expected $MeshFormat first", printable(name)));
    if (name == "MeshFormat" || name == "PhysicalNames" || name == "Entities" || name == "Nodes" ||
        name == "Elements") {
      if (!seen.insert(name).second) lex.fail(fmt::format("second ${} section, expected one", name));
    }
    if (name == "MeshFormat") {
      parse_mesh_format(lex);
    } else if (name == "PhysicalNames") {
      parse_physical_names(lex, d);
    } else if (name == "Entities") {
      parse_entities(lex, d);
    } else if (name == "Nodes") {
      parse_nodes(lex, d);
    } else if (name == "Elements") {
      if (!seen.count("Nodes")) lex.fail("$Elements before $Nodes, expected $Nodes first");
      parse_elements(lex, d);
    } else if (name == "NodeData" || name == "ElementData") {
      parse_data_view(lex, d, name);
    } else if (name == "PartitionedEntities") {
      lex.fail("partitioned mesh ($PartitionedEntities), expected an unpartitioned mesh");
    } else {
      skip_section(lex, name);  // $Comments, $Periodic, $ElementNodeData, ...: not ours to read
    }
  }
  if (require_mesh && !seen.count("Elements"))
    throw InputError(fmt::format("mesh file '{}': no $Nodes and $Elements sections, expected a Gmsh MSH 4.1 mesh",
                                 file));
  return d;
}

// ---------------------------------------------------------------------------------
// From file numbering to meshes.

std::string error_prefix(const MshData& d, const ElementBlock& b, std::size_t i) {
  return fmt::format("mesh file '{}' line {}: element {}", d.file, b.lines[i], b.tags[i]);
}

/// Compact numbering (file order) of the nodes used by `blocks`; returns for every
/// file node its new index, or -1 if unused, and appends the used coordinates to `nodes`.
std::vector<int> compact_nodes(const MshData& d, const std::vector<const ElementBlock*>& blocks,
                               std::vector<Vec3>& nodes) {
  std::vector<int> index(d.node_tags.size(), -1);
  for (const ElementBlock* b : blocks)
    for (int p : b->nodes) index[p] = 0;
  for (std::size_t p = 0; p < index.size(); ++p)
    if (index[p] == 0) {
      index[p] = static_cast<int>(nodes.size());
      nodes.push_back(d.coords[p]);
    }
  return index;
}

std::size_t count_elements(const std::vector<const ElementBlock*>& blocks) {
  std::size_t n = 0;
  for (const ElementBlock* b : blocks) n += b->tags.size();
  return n;
}

[[noreturn]] void fail_no_elements(const MshData& d, int type, const std::string& what) {
  std::string found;
  for (int t : d.element_types) found += fmt::format(" {}", t);
  throw InputError(fmt::format("mesh file '{}': no {} (Gmsh element type {}; element types in the file:{}), "
                               "expected at least one",
                               d.file, what, type, found.empty() ? " none" : found));
}

// Tets in gmsh's node order have positive volume; report an inverted one with its
// file line and tags, which is where the user can fix it.
void check_tet_orientation(const MshData& d, const TetMesh& m, const std::vector<const ElementBlock*>& blocks) {
  int e = 0;
  for (const ElementBlock* b : blocks)
    for (std::size_t i = 0; i < b->tags.size(); ++i, ++e) {
      const double v = tet_signed_volume(m, e);
      if (v > 0.0) continue;
      const int* n = &b->nodes[static_cast<std::size_t>(b->nodes_per) * i];
      throw InputError(fmt::format("{} (node tags {} {} {} {}) is inverted: signed volume {:.6g}, expected > 0",
                                   error_prefix(d, *b, i), d.node_tags[n[0]], d.node_tags[n[1]],
                                   d.node_tags[n[2]], d.node_tags[n[3]], v));
    }
}

/// Adds the elements of `type` on named physical groups of dimension `dim` to `groups`
/// (triangles for faces, points or lines for node sets), in compact node numbering.
/// Of a quadratic element only its first N (vertex) nodes are taken: edge nodes come
/// from the tets (TetMesh::edge_nodes).
template <std::size_t N>
void collect_named(const MshData& d, int type, int dim, const std::vector<int>& index,
                   std::map<std::string, std::vector<std::array<int, N>>>& groups) {
  for (const ElementBlock* b : d.blocks_of(type)) {
    if (b->dim != dim) continue;
    const std::vector<std::string> names = d.names_of(dim, b->entity);
    if (names.empty()) continue;
    for (std::size_t i = 0; i < b->tags.size(); ++i) {
      std::array<int, N> el{};
      for (std::size_t a = 0; a < N; ++a) {
        const int p = b->nodes[static_cast<std::size_t>(b->nodes_per) * i + a];
        if (index[p] < 0)
          throw InputError(fmt::format("{} of physical group '{}' uses node tag {}, which belongs to no "
                                       "tetrahedron; expected named groups to lie on the volume mesh",
                                       error_prefix(d, *b, i), names.front(), d.node_tags[p]));
        el[a] = index[p];
      }
      for (const auto& name : names) groups[name].push_back(el);
    }
  }
}

template <std::size_t N>
void add_node_sets(const std::map<std::string, std::vector<std::array<int, N>>>& groups,
                   std::map<std::string, std::vector<int>>& node_sets) {
  for (const auto& [name, elements] : groups)
    for (const auto& el : elements) node_sets[name].insert(node_sets[name].end(), el.begin(), el.end());
}

// Jacobian determinant of a trilinear hex at its centre (up to a positive factor):
// positive when the node order is right-handed.
double hex_centre_jacobian(const std::vector<Vec3>& x, const std::array<int, 8>& h) {
  const auto X = [&](int a) -> const Vec3& { return x[h[a]]; };
  const Vec3 dxi = X(1) - X(0) + X(2) - X(3) + X(5) - X(4) + X(6) - X(7);
  const Vec3 deta = X(3) - X(0) + X(2) - X(1) + X(7) - X(4) + X(6) - X(5);
  const Vec3 dzeta = X(4) - X(0) + X(5) - X(1) + X(6) - X(2) + X(7) - X(3);
  return dxi.dot(deta.cross(dzeta));
}

}  // namespace

TetMesh read_gmsh_tets(const std::string& file) {
  const MshData d = parse_msh_file(file);
  const auto linear = d.blocks_of(kTet);
  const auto quadratic = d.blocks_of(kTet10);
  if (count_elements(linear) > 0 && count_elements(quadratic) > 0)
    throw InputError(fmt::format("mesh file '{}': both 4-node (type 4) and 10-node (type 11) "
                                 "tetrahedra, expected one order throughout",
                                 file));
  const bool is_quadratic = count_elements(quadratic) > 0;
  const auto tet_blocks = is_quadratic ? quadratic : linear;
  if (count_elements(tet_blocks) == 0) fail_no_elements(d, kTet, "4-node tetrahedra (or 10-node, type 11)");

  TetMesh m;
  const std::vector<int> index = compact_nodes(d, tet_blocks, m.nodes);
  // Gmsh's 10-node tet: vertices 0–3, then edges 01, 12, 20, 30, 32, 31.
  constexpr std::array<std::array<int, 2>, 6> gmsh_edges = {{{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}};
  for (const ElementBlock* b : tet_blocks) {
    const auto& physicals = d.physicals_of(3, b->entity);
    const int region = physicals.empty() ? 1 : physicals.front();
    for (std::size_t i = 0; i < b->tags.size(); ++i) {
      const int* n = &b->nodes[static_cast<std::size_t>(b->nodes_per) * i];
      m.tets.push_back({index[n[0]], index[n[1]], index[n[2]], index[n[3]]});
      m.region.push_back(region);
      if (!is_quadratic) continue;
      for (int k = 0; k < 6; ++k) {
        const auto key = std::minmax(index[n[gmsh_edges[k][0]]], index[n[gmsh_edges[k][1]]]);
        const auto [it, added] = m.edge_nodes.emplace(key, index[n[4 + k]]);
        if (!added && it->second != index[n[4 + k]])
          throw InputError(fmt::format("{}: node tag {} lies on the edge between node tags {} and {}, "
                                       "where another element has a different node; expected a "
                                       "conforming mesh",
                                       error_prefix(d, *b, i), d.node_tags[n[4 + k]],
                                       d.node_tags[n[gmsh_edges[k][0]]], d.node_tags[n[gmsh_edges[k][1]]]));
      }
    }
  }
  check_tet_orientation(d, m, tet_blocks);
  for (const auto& [dim_tag, name] : d.physical_names)
    if (dim_tag.first == 3) m.region_names[dim_tag.second] = name;

  collect_named(d, is_quadratic ? kTriangle6 : kTriangle, 2, index, m.faces);
  std::map<std::string, std::vector<std::array<int, 1>>> points;
  std::map<std::string, std::vector<std::array<int, 2>>> lines;
  std::map<std::string, std::vector<std::array<int, 3>>> lines3;
  collect_named(d, kPoint, 0, index, points);
  collect_named(d, kLine, 1, index, lines);
  collect_named(d, kLine3, 1, index, lines3);
  add_node_sets(lines3, m.node_sets);
  add_node_sets(points, m.node_sets);
  add_node_sets(lines, m.node_sets);
  for (auto& [name, ids] : m.node_sets) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  }

  orient_named_surfaces(m, file);
  validate_mesh(m, file);
  return m;
}

HexMesh read_gmsh_hexes(const std::string& file) {
  const MshData d = parse_msh_file(file);
  const auto hex_blocks = d.blocks_of(kHex);
  if (count_elements(hex_blocks) == 0) fail_no_elements(d, kHex, "8-node hexahedra");

  // Materials are assigned by region name, so a hex volume outside every physical group
  // has no material: refuse it rather than guess.
  std::set<int> volume_tags;
  for (const ElementBlock* b : hex_blocks) {
    const auto& physicals = d.physicals_of(3, b->entity);
    if (b->tags.empty()) continue;
    if (physicals.empty())
      throw InputError(fmt::format(
          "mesh file '{}' line {}: hexahedra of volume entity {} (elements {}..{}) belong to no "
          "physical group, expected every hex volume in a physical volume named after its "
          "material (e.g. Physical Volume(\"cell\") = {{{}}};)",
          d.file, b->lines.front(), b->entity, b->tags.front(), b->tags.back(), b->entity));
    volume_tags.insert(physicals.front());
  }

  HexMesh h;
  for (int tag : volume_tags) {
    const auto it = d.physical_names.find({3, tag});
    h.region_names.push_back(it == d.physical_names.end() ? std::to_string(tag) : it->second);
  }
  const std::vector<int> index = compact_nodes(d, hex_blocks, h.nodes);
  for (const ElementBlock* b : hex_blocks) {
    if (b->tags.empty()) continue;
    const int tag = d.physicals_of(3, b->entity).front();
    const int region = static_cast<int>(std::distance(volume_tags.begin(), volume_tags.find(tag)));
    for (std::size_t i = 0; i < b->tags.size(); ++i) {
      std::array<int, 8> hex{};
      for (int a = 0; a < 8; ++a) hex[a] = index[b->nodes[8 * i + a]];
      if (!(hex_centre_jacobian(h.nodes, hex) > 0.0))
        throw InputError(fmt::format("{} is an inverted or tangled hexahedron, expected Gmsh node order "
                                     "with positive Jacobian",
                                     error_prefix(d, *b, i)));
      h.hexes.push_back(hex);
      h.region.push_back(region);
    }
  }
  h.lo = h.hi = h.nodes.front();
  for (const Vec3& x : h.nodes) {
    h.lo = h.lo.cwiseMin(x);
    h.hi = h.hi.cwiseMax(x);
  }
  return h;
}

GmshTags read_gmsh_tags(const std::string& file) {
  const MshData d = parse_msh_file(file);
  // The same tets and node numbering as read_gmsh_tets (which refuses mixed orders).
  const auto quadratic = d.blocks_of(kTet10);
  const auto blocks = count_elements(quadratic) > 0 ? quadratic : d.blocks_of(kTet);
  if (count_elements(blocks) == 0) fail_no_elements(d, kTet, "4-node tetrahedra (or 10-node, type 11)");
  GmshTags t;
  std::vector<Vec3> nodes;
  const std::vector<int> index = compact_nodes(d, blocks, nodes);
  t.nodes.resize(nodes.size());
  for (std::size_t p = 0; p < index.size(); ++p)
    if (index[p] >= 0) t.nodes[index[p]] = d.node_tags[p];
  for (const ElementBlock* b : blocks) t.elements.insert(t.elements.end(), b->tags.begin(), b->tags.end());
  return t;
}

namespace {

/// The one view named `name` of `d` with `components` components (else InputError).
const DataView& find_view(const MshData& d, const std::string& file, GmshDataOn on, const std::string& name,
                          int components) {
  const bool elements = on == GmshDataOn::elements;
  const char* kind = components == 3 ? "a vector" : "a scalar";
  const char* section = elements ? "$ElementData" : "$NodeData";
  const DataView* found = nullptr;
  std::vector<std::string> names;
  for (const DataView& v : d.views) {
    if (v.on_elements != elements) continue;
    names.push_back(v.name);
    if (v.name != name) continue;
    if (found)
      throw InputError(fmt::format("file '{}' line {}: a second {} view \"{}\" (the first is at line {}), "
                                   "expected one (a single time step)",
                                   file, v.line, section, name, found->line));
    found = &v;
  }
  if (!found)
    throw InputError(fmt::format("file '{}': no {} view named \"{}\", expected one with {} components per {}: {}",
                                 file, section, name, components, elements ? "element" : "node",
                                 known_names("one of its views", name, names)));
  if (found->components != components)
    throw InputError(fmt::format("file '{}' line {}: {} view \"{}\" has {} components, expected {} ({})", file,
                                 found->line, section, name, found->components, components, kind));
  return *found;
}

}  // namespace

GmshVectorView read_gmsh_vector_view(const std::string& file, GmshDataOn on, const std::string& name) {
  const MshData d = parse_msh_file(file, /*require_mesh=*/false);
  const DataView* found = &find_view(d, file, on, name, 3);
  GmshVectorView out;
  out.tags = found->tags;
  out.lines = found->lines;
  for (std::size_t i = 0; i < found->tags.size(); ++i)
    out.values.emplace_back(found->values[3 * i], found->values[3 * i + 1], found->values[3 * i + 2]);
  return out;
}

GmshScalarView read_gmsh_scalar_view(const std::string& file, GmshDataOn on, const std::string& name) {
  const MshData d = parse_msh_file(file, /*require_mesh=*/false);
  const DataView& v = find_view(d, file, on, name, 1);
  return {v.tags, v.values, v.lines};
}

}  // namespace fe2
