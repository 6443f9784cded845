// How a grid represents a built-in cell layout (worker/micro_cell.h, cell_resolution):
// the volume fraction its elements give the cells against the layout's, and the
// resolutions that put every interface on element faces. MicroModel::plan warns when the
// two fractions differ by more than 10 %.
#include "worker/micro_cell.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

CellLayout two_cells(std::array<int, 3> resolution, double gap, double cross_section) {
  CellLayout c;
  c.kind = "two_cells";
  c.size = Vec3(1.0, 0.4, 0.4);
  c.resolution = resolution;
  c.gap = gap;
  c.cross_section = cross_section;
  return c;
}

TEST(CellResolution, TwoCellsAtTheOldDefaultBeatLoseTheGap) {
  // gap 0.1 at 6 elements along the fibre: every centroid lies inside a cell, so the
  // cells join end to end (25 % of the volume instead of (1 − 0.2) · 0.5² = 20 %).
  const CellResolution r = cell_resolution(two_cells({6, 4, 4}, 0.1, 0.5));
  EXPECT_DOUBLE_EQ(r.realised, 0.25);
  EXPECT_NEAR(r.nominal, 0.2, 1e-15);
  EXPECT_EQ(r.exact, (std::array<int, 3>{20, 4, 4}));
  // At a resolution that resolves it, the grid is the layout.
  const CellResolution fine = cell_resolution(two_cells({20, 8, 4}, 0.1, 0.5));
  EXPECT_NEAR(fine.realised, fine.nominal, 1e-15);
  // Refining from 6x4x4 to 9x6x6 changes the microstructure: a gap appears along the
  // fibre (8 of 9 columns) and 4 of 6 rows are cell across (centroids at 0.25 and 0.75
  // of the width fall inside by round-off): ≈ 40 % cells, not 25 %.
  const CellResolution nine = cell_resolution(two_cells({9, 6, 6}, 0.1, 0.5));
  EXPECT_GT(nine.realised, 0.3);
}

TEST(CellResolution, TheDefaultBeatsBundleIsResolvedAtEvenAndFourfoldCounts) {
  // gap 0 (configs/lv-beat.json): no interface along the fibre but the halves' boundary.
  for (auto res : {std::array<int, 3>{4, 4, 4}, {6, 4, 4}, {6, 8, 8}}) {
    const CellResolution r = cell_resolution(two_cells(res, 0.0, 0.5));
    EXPECT_NEAR(r.realised, 0.25, 1e-15) << res[0] << res[1] << res[2];
    EXPECT_NEAR(r.nominal, 0.25, 1e-15);
  }
  EXPECT_EQ(cell_resolution(two_cells({6, 4, 4}, 0.0, 0.5)).exact, (std::array<int, 3>{2, 4, 4}));
  // An odd count along the fibre puts a centroid on the halves' boundary: an ECM slab.
  EXPECT_LT(cell_resolution(two_cells({5, 4, 4}, 0.0, 0.5)).realised, 0.25);
}

TEST(CellResolution, LaminateAndHomogeneous) {
  CellLayout c;
  c.kind = "laminate";
  c.fraction = 0.3;
  c.axis = 1;
  c.resolution = {2, 4, 2};
  const CellResolution r = cell_resolution(c);
  EXPECT_NEAR(r.nominal, 0.7, 1e-15);
  EXPECT_DOUBLE_EQ(r.realised, 0.75);  // centroids at 1/8, 3/8, ...: one of four below 0.3
  EXPECT_EQ(r.exact, (std::array<int, 3>{1, 10, 1}));
  c.kind = "homogeneous";
  const CellResolution h = cell_resolution(c);
  EXPECT_EQ(h.realised, h.nominal);
}

}  // namespace
}  // namespace fe2
