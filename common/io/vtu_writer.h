#pragma once
// ASCII VTK XML output for ParaView: UnstructuredGrid (.vtu) files of macro (tet) and
// micro (hex) meshes with point and cell data, and a .pvd collection over time.
// Every file is written to "<name>.tmp" and renamed into place, so a reader (or a run
// that is killed) never sees a half-written file.
#include "common/mesh/HexMesh.h"
#include "common/mesh/TetMesh.h"

#include <string>
#include <utility>
#include <vector>

namespace fe2 {

/// Named arrays attached to the points or the cells of a VTU file.
class VtuFields {
 public:
  struct Field {
    std::string name;
    int components = 1;
    std::vector<double> values;  ///< components values per point/cell, entity after entity
  };

  void add_scalar(const std::string& name, std::vector<double> values);
  void add_vector(const std::string& name, const std::vector<Vec3>& values);
  /// 3x3 tensors as our column-major 9-vectors (11,21,31,12,...; DESIGN §1). VTK reads
  /// 9-component arrays row-major (xx,xy,xz,yx,...), so each tensor is written
  /// transposed in memory order: component (i,J) of the file is our entry i + 3J.
  void add_tensor(const std::string& name, const std::vector<Vec9>& values);

  const std::vector<Field>& fields() const { return fields_; }

 private:
  void add(Field f);
  std::vector<Field> fields_;
};

/// Writes the tets (VTK_TETRA = 10; VTK_QUADRATIC_TETRA = 24 for a quadratic mesh) with an Int32 cell array "region" and the given
/// data; each field must have one entry per node (point_data) or per tet (cell_data).
void write_vtu(const std::string& path, const TetMesh& mesh, const VtuFields& point_data = {},
               const VtuFields& cell_data = {});

/// Writes the hexes (VTK_HEXAHEDRON = 12, same node order as HexMesh) likewise.
void write_vtu(const std::string& path, const HexMesh& mesh, const VtuFields& point_data = {},
               const VtuFields& cell_data = {});

/// A ParaView collection (.pvd) of time steps. Every add() rewrites the whole .pvd
/// (atomically), so a partial run is still openable; rewriting is O(steps) per call,
/// negligible next to the VTU files themselves.
class PvdWriter {
 public:
  /// Writes an empty collection at once, so a bad output path fails early.
  explicit PvdWriter(std::string pvd_path);

  /// Appends the step (time, vtu_path) and rewrites the .pvd. `vtu_path` is a path as
  /// the caller would open it (absolute, or relative to the working directory, like
  /// the .pvd path), not a bare name; it is stored relative to the .pvd's folder, so
  /// the series opens from anywhere and the output folder can be moved.
  void add(double time, const std::string& vtu_path);

  const std::string& path() const { return path_; }

 private:
  void write() const;
  std::string path_;
  std::vector<std::pair<double, std::string>> steps_;
};

}  // namespace fe2
