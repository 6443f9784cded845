#pragma once
// The macro Schur system S̄ Δū = ḡ (Eq. 10) solved by MUMPS with distributed
// assembled input (ICNTL(18) = 3) on the communicator it is handed: each rank passes
// its own triplets (duplicates are summed by MUMPS). The pattern is given once; the
// analysis is done once and reused while the pattern holds; every call to
// factorize_and_solve only refactors. S̄ is unsymmetric in general (follower loads).
// Every MUMPS status is checked: INFOG(1) < 0 is an error naming INFOG(1), INFOG(2).
#include <dmumps_c.h>
#include <mpi.h>

#include "common/error.h"
#include "coordinator/macro/MacroSolverOptions.h"

#include <string>
#include <vector>

namespace fe2 {

/// S̄ has null pivots (MUMPS INFOG(28) > 0). `at_committed_state`: the matrix was that
/// of the last converged state, so cutting the step back cannot cure it.
class SingularMatrixError : public NumericalError {
 public:
  explicit SingularMatrixError(const std::string& what, bool at_committed_state = false)
      : NumericalError(what), at_committed_state(at_committed_state) {}
  bool at_committed_state;
};

class MumpsSolver {
 public:
  /// metis: the order from the pattern gathered to the host, passed as the user's
  /// (ICNTL(7) = 1); mumps: ICNTL(7) = 7.
  using Ordering = MacroSolverOptions::Ordering;

  /// @note Collective on `comm` (lent; must outlive this object).
  MumpsSolver(MPI_Comm comm, int n, Ordering ordering = Ordering::metis);
  ~MumpsSolver();
  MumpsSolver(const MumpsSolver&) = delete;
  MumpsSolver& operator=(const MumpsSolver&) = delete;

  /// This rank's triplets, 0-based (row, col); fixes the pattern and runs the analysis.
  /// @note Collective.
  void set_pattern(std::vector<int> rows, std::vector<int> cols);
  /// Values in the order of the pattern's triplets; `rhs` (length n, significant on rank
  /// 0 of comm) is overwritten with the solution on rank 0. @note Collective.
  void factorize_and_solve(const std::vector<double>& values, std::vector<double>& rhs);
  /// The numeric factorization alone (throws SingularMatrixError on null pivots).
  /// @note Collective.
  void factorize(const std::vector<double>& values);
  /// A solve with the last factorization; `rhs` as in factorize_and_solve. @note Collective.
  void solve(std::vector<double>& rhs);

  int size() const { return n_; }
  /// The fill-reducing ordering the analysis used (INFOG(7)), e.g. "PORD"; "METIS (user)"
  /// for fe2heart's own nested dissection.
  const std::string& ordering() const { return ordering_; }
  /// Entries of the last numeric factor (INFOG(29)) and the operations of its elimination
  /// (RINFOG(3)), global (the same on every rank): what the ordering decides.
  double factor_entries() const;
  double factor_flops() const { return id_.rinfog[2]; }

 private:
  void run(int job, const char* what);
  /// PERM_IN from METIS on the pattern gathered to the host (empty elsewhere). @note Collective.
  void compute_nested_dissection();
  DMUMPS_STRUC_C id_{};
  MPI_Comm comm_;
  int n_;
  Ordering requested_;
  std::vector<int> irn_, jcn_, perm_in_;
  std::vector<double> a_;
  bool analysed_ = false;
  bool factored_ = false;
  std::string ordering_;
};

}  // namespace fe2
