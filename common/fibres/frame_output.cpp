#include "common/fibres/frame_output.h"

namespace fe2 {

std::vector<Mat3> frames_at_centroids(const FrameField& field, const TetMesh& mesh) {
  std::vector<Mat3> Q(mesh.tets.size());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    Vec3 X = Vec3::Zero();
    for (int v : mesh.tets[e]) X += 0.25 * mesh.nodes[v];
    Q[e] = field.at(e, kCentroid, X);
  }
  return Q;
}

void add_frame_cell_fields(VtuFields& cells, const std::vector<Mat3>& frames) {
  std::vector<Vec3> f, s;
  f.reserve(frames.size());
  s.reserve(frames.size());
  for (const Mat3& Q : frames) {
    f.push_back(Q.col(0));
    s.push_back(Q.col(1));
  }
  cells.add_vector("fibre", f);
  cells.add_vector("sheet", s);
}

}  // namespace fe2
