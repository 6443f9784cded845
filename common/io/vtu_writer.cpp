#include "common/io/vtu_writer.h"

#include "common/error.h"
#include "common/io/atomic_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string_view>

namespace fe2 {

namespace {

namespace fs = std::filesystem;
using Buffer = fmt::memory_buffer;

constexpr int kVtkTetra = 10;
constexpr int kVtkHexahedron = 12;
constexpr int kVtkQuadraticTetra = 24;

std::string xml_escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

// fmt's "{}" prints the shortest text that reads back to the same double.
void write_array(Buffer& b, const VtuFields::Field& f) {
  fmt::format_to(std::back_inserter(b), "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
                 xml_escape(f.name), f.components);
  for (std::size_t i = 0; i < f.values.size(); i += f.components) {
    fmt::format_to(std::back_inserter(b), "         ");
    for (int c = 0; c < f.components; ++c) fmt::format_to(std::back_inserter(b), " {}", f.values[i + c]);
    fmt::format_to(std::back_inserter(b), "\n");
  }
  fmt::format_to(std::back_inserter(b), "        </DataArray>\n");
}

// A PointData or CellData section; `ints` is an extra integer array (cell regions).
void write_data(Buffer& b, const char* section, const VtuFields& data, std::size_t count, const std::string& path,
                const char* ints_name = nullptr, const std::vector<int>* ints = nullptr) {
  fmt::format_to(std::back_inserter(b), "      <{}>\n", section);
  for (const auto& f : data.fields()) {
    FE2_CHECK(f.values.size() == count * f.components, "{} '{}' of '{}' has {} values, expected {} x {}", section,
              f.name, path, f.values.size(), count, f.components);
    write_array(b, f);
  }
  if (ints && ints->size() == count) {
    fmt::format_to(std::back_inserter(b), "        <DataArray type=\"Int32\" Name=\"{}\" format=\"ascii\">\n", ints_name);
    for (int r : *ints) fmt::format_to(std::back_inserter(b), " {}", r);
    fmt::format_to(std::back_inserter(b), "\n        </DataArray>\n");
  }
  fmt::format_to(std::back_inserter(b), "      </{}>\n", section);
}

// One Piece of an unstructured grid whose cells all have the same type (N nodes each).
template <class Cell>
void write_unstructured(const std::string& path, const std::vector<Vec3>& nodes,
                        const std::vector<Cell>& cells, const std::vector<int>& region,
                        int vtk_type, const VtuFields& point_data, const VtuFields& cell_data) {
  const std::size_t N = cells.empty() ? 0 : cells.front().size();
  const auto out = [](Buffer& b) { return std::back_inserter(b); };
  Buffer b;
  fmt::format_to(out(b), "<?xml version=\"1.0\"?>\n"
                         "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                         "  <UnstructuredGrid>\n"
                         "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
                 nodes.size(), cells.size());
  write_data(b, "PointData", point_data, nodes.size(), path);
  write_data(b, "CellData", cell_data, cells.size(), path, "region", &region);
  fmt::format_to(out(b), "      <Points>\n"
                         "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (const Vec3& x : nodes) fmt::format_to(out(b), "          {} {} {}\n", x.x(), x.y(), x.z());
  fmt::format_to(out(b), "        </DataArray>\n      </Points>\n      <Cells>\n"
                         "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& c : cells) fmt::format_to(out(b), "          {}\n", fmt::join(c, " "));
  fmt::format_to(out(b), "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (std::size_t e = 1; e <= cells.size(); ++e) fmt::format_to(out(b), " {}", e * N);
  fmt::format_to(out(b), "\n        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (std::size_t e = 0; e < cells.size(); ++e) fmt::format_to(out(b), " {}", vtk_type);
  fmt::format_to(out(b), "\n        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  write_file_atomically(path, std::string_view(b.data(), b.size()));
}

}  // namespace

void VtuFields::add(Field f) {
  for (const auto& g : fields_) FE2_CHECK(g.name != f.name, "VTU field '{}' added twice", f.name);
  fields_.push_back(std::move(f));
}

void VtuFields::add_scalar(const std::string& name, std::vector<double> values) {
  add({name, 1, std::move(values)});
}

void VtuFields::add_vector(const std::string& name, const std::vector<Vec3>& values) {
  Field f{name, 3, {}};
  f.values.reserve(3 * values.size());
  for (const Vec3& v : values) f.values.insert(f.values.end(), v.data(), v.data() + 3);
  add(std::move(f));
}

void VtuFields::add_tensor(const std::string& name, const std::vector<Vec9>& values) {
  Field f{name, 9, {}};
  f.values.reserve(9 * values.size());
  for (const Vec9& v : values)
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) f.values.push_back(v[index9(i, J)]);  // row-major for VTK
  add(std::move(f));
}

void write_vtu(const std::string& path, const TetMesh& mesh, const VtuFields& point_data,
               const VtuFields& cell_data) {
  if (mesh.order() == 1) {
    write_unstructured(path, mesh.nodes, mesh.tets, mesh.region, kVtkTetra, point_data, cell_data);
    return;
  }
  // VTK_QUADRATIC_TETRA takes the nodes in TetMesh::element_nodes order.
  std::vector<std::vector<int>> cells(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) cells[e] = mesh.element_nodes(e);
  write_unstructured(path, mesh.nodes, cells, mesh.region, kVtkQuadraticTetra, point_data, cell_data);
}

void write_vtu(const std::string& path, const HexMesh& mesh, const VtuFields& point_data,
               const VtuFields& cell_data) {
  write_unstructured(path, mesh.nodes, mesh.hexes, mesh.region, kVtkHexahedron, point_data, cell_data);
}

PvdWriter::PvdWriter(std::string pvd_path) : path_(std::move(pvd_path)) { write(); }

void PvdWriter::add(double time, const std::string& vtu_path) {
  // Both paths as the caller opens them (relative to the working directory); ParaView
  // resolves a PVD's file attributes against the PVD's own folder.
  const fs::path dir = fs::absolute(path_).lexically_normal().parent_path();
  steps_.emplace_back(time, fs::absolute(vtu_path).lexically_normal().lexically_relative(dir).generic_string());
  write();
}

void PvdWriter::write() const {
  Buffer b;
  const auto out = std::back_inserter(b);
  fmt::format_to(out, "<?xml version=\"1.0\"?>\n"
                      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                      "  <Collection>\n");
  for (const auto& [time, file] : steps_)
    fmt::format_to(out, "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time, xml_escape(file));
  fmt::format_to(out, "  </Collection>\n</VTKFile>\n");
  write_file_atomically(path_, std::string_view(b.data(), b.size()));
}

}  // namespace fe2
