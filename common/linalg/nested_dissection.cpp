#include "common/linalg/nested_dissection.h"

#include "common/error.h"

#include <metis.h>

#include <algorithm>
#include <numeric>

namespace fe2 {

std::vector<int> nested_dissection_positions(int n, const std::vector<int>& rows,
                                             const std::vector<int>& cols, int base) {
  FE2_CHECK(rows.size() == cols.size(), "{} rows for {} columns", rows.size(), cols.size());
  FE2_CHECK(base == 0 || base == 1, "index base {} (0 or 1)", base);
  // The symmetric adjacency (CSR) of A + Aᵀ: count, fill, then sort and drop duplicates.
  std::vector<idx_t> degree(n + 1, 0);
  for (size_t k = 0; k < rows.size(); ++k) {
    const int r = rows[k] - base, c = cols[k] - base;
    FE2_CHECK(r >= 0 && r < n && c >= 0 && c < n, "entry ({}, {}) outside a matrix of order {}",
              r, c, n);
    if (r == c) continue;
    ++degree[r + 1];
    ++degree[c + 1];
  }
  std::vector<idx_t> start(degree);
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<idx_t> neighbours(start[n]);
  std::vector<idx_t> fill(start.begin(), start.end() - 1);
  for (size_t k = 0; k < rows.size(); ++k) {
    const int r = rows[k] - base, c = cols[k] - base;
    if (r == c) continue;
    neighbours[fill[r]++] = c;
    neighbours[fill[c]++] = r;
  }
  std::vector<idx_t> xadj(n + 1, 0), adjncy;
  adjncy.reserve(neighbours.size() / 2 + 1);
  for (int i = 0; i < n; ++i) {
    auto first = neighbours.begin() + start[i], last = neighbours.begin() + start[i + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    adjncy.insert(adjncy.end(), first, last);
    xadj[i + 1] = static_cast<idx_t>(adjncy.size());
  }
  if (adjncy.empty()) adjncy.push_back(0);  // METIS reads adjncy[0] even without edges

  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = 7;  // the same order on every rank and every run
  idx_t nv = n;
  // METIS's names: A′ = A(perm, perm); iperm[i] is the row of A′ that row i of A becomes,
  // i.e. variable i's position in the pivot order.
  std::vector<idx_t> perm(n), iperm(n);
  const int rc = n == 0 ? METIS_OK
                        : METIS_NodeND(&nv, xadj.data(), adjncy.data(), nullptr, options, perm.data(),
                                       iperm.data());
  if (rc != METIS_OK)
    throw Error(fmt::format("METIS_NodeND failed with status {} on a matrix of order {} ({} "
                            "off-diagonal neighbours)",
                            rc, n, adjncy.size()));
  std::vector<int> positions(n);
  for (int i = 0; i < n; ++i) positions[i] = static_cast<int>(iperm[i]) + base;
  return positions;
}

}  // namespace fe2
