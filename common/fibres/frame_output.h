#pragma once
// A frame field as VTU cell data, for ParaView (Glyph filter on "fibre").
#include "common/fibres/FrameField.h"
#include "common/io/vtu_writer.h"
#include "common/mesh/TetMesh.h"

#include <vector>

namespace fe2 {

/// Q = [f s n] at each element's centroid (λ = ¼ each, X = mean of its 4 vertices).
std::vector<Mat3> frames_at_centroids(const FrameField& field, const TetMesh& mesh);

/// Adds cell vectors "fibre" and "sheet" (one per tet) to `cells` for write_vtu.
void add_frame_cell_fields(VtuFields& cells, const std::vector<Mat3>& frames);

}  // namespace fe2
