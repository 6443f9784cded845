#pragma once
// output.units: the micro fields of chosen FE² units (paper Fig. 11), one ParaView
// series per unit in <out>/units/: unit_<id>.pvd over unit_<id>_<step>.vtu, the step
// numbered as displacement_<step>.vtu. Each VTU is the unit's micro mesh in the unit's
// own frame (X along the fibre) with point data `displacement` (Z̄·X + w) and
// `fluctuation` (w), and cell data `region` (the mesh's phase index, e.g. two_cells:
// 0 ecm, 1 cell), `P` (first Piola stress, volume mean over the element's Gauss
// points), `det_F` and, when the unit's cells contract, `active_tension` (Pa).
#include "coordinator/RunSpec.h"
#include "proto/messages.h"
#include "worker/micro_cell.h"

#include "common/io/vtu_writer.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fe2 {

class UnitOutput {
 public:
  /// Creates <dir>/units when the spec chooses units (InputError if it cannot); the
  /// unit meshes are rebuilt from the spec's plans (no unit model needs to exist here).
  UnitOutput(const std::string& dir, const RunSpec& spec);
  /// Writes one VTU per unit of `fields` and adds it to the unit's PVD at `time`.
  void write(const std::vector<proto::UnitFields>& fields, double time);
  /// A restart into the same folder: each unit's PVD lists again the VTUs of the output
  /// steps behind, (step from 1, time) in order, whose files are there.
  void resume(const std::vector<std::pair<int, double>>& output_steps);
  std::string pvd_path(int unit) const;
  std::string vtu_path(int unit, int step) const;

 private:
  struct Series {
    HexMesh mesh;
    std::unique_ptr<PvdWriter> pvd;
  };
  std::string dir_;
  std::map<int, Series> units_;
};

/// The VTU fields of one unit's fields on its mesh (point data, cell data).
std::pair<VtuFields, VtuFields> unit_vtu_fields(const HexMesh& mesh, const proto::UnitFields& f);

}  // namespace fe2
