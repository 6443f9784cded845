#include "coordinator/macro/MumpsSolver.h"

#include "common/error.h"
#include "common/linalg/mumps_count.h"
#include "common/linalg/nested_dissection.h"

#include <spdlog/spdlog.h>

#include <exception>

namespace fe2 {

// MUMPS documents its controls 1-based.
#define ICNTL(k) icntl[(k)-1]
#define INFOG(k) infog[(k)-1]

MumpsSolver::MumpsSolver(MPI_Comm comm, int n, Ordering ordering)
    : comm_(comm), n_(n), requested_(ordering) {
  id_.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
  id_.par = 1;  // the host takes part in the factorization
  id_.sym = 0;  // unsymmetric
  run(-1, "initialization");
  id_.ICNTL(1) = -1;  // no error/diagnostic/global output: we report INFOG ourselves
  id_.ICNTL(2) = -1;
  id_.ICNTL(3) = -1;
  id_.ICNTL(4) = 0;
  id_.ICNTL(5) = 0;   // assembled
  id_.ICNTL(18) = 3;  // distributed assembled input
  id_.ICNTL(14) = 50; // workspace margin for pivoting (percent)
  // Null-pivot detection: an under-constrained body (rigid-body modes left free) gives
  // a singular S̄ that MUMPS would otherwise factor into a meaningless Δū, seen only
  // later as "inverted element". INFOG(28) then counts the null pivots.
  id_.ICNTL(24) = 1;
  id_.ICNTL(7) = ordering == Ordering::metis ? 1 : 7;
}

void MumpsSolver::compute_nested_dissection() {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &size);
  const int mine = static_cast<int>(irn_.size());
  std::vector<int> counts(size), offsets(size, 0);
  MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  std::vector<int> rows, cols;
  if (rank == 0) {
    long long total = 0;
    for (int r = 0; r < size; ++r) {
      offsets[r] = static_cast<int>(total);
      total += counts[r];
    }
    FE2_CHECK(total < (1LL << 31), "{} macro triplets: more than a 32-bit MPI count", total);
    rows.resize(total);
    cols.resize(total);
  }
  MPI_Gatherv(irn_.data(), mine, MPI_INT, rows.data(), counts.data(), offsets.data(), MPI_INT, 0, comm_);
  MPI_Gatherv(jcn_.data(), mine, MPI_INT, cols.data(), counts.data(), offsets.data(), MPI_INT, 0, comm_);
  perm_in_.clear();
  if (rank != 0) return;
  perm_in_ = nested_dissection_positions(n_, rows, cols, 1);
  id_.perm_in = perm_in_.data();
}

double MumpsSolver::factor_entries() const {
  return mumps_count(id_.INFOG(29));  // the factor's entries
}

MumpsSolver::~MumpsSolver() {
  // JOB = -2 is collective: while an exception unwinds, the other ranks of the group
  // may never join it (they are computing, waiting elsewhere, or already aborting), so
  // the instance is left to MPI_Abort / process exit (MFEM_ABORT's rule: abort first).
  if (std::uncaught_exceptions() > 0) return;
  id_.job = -2;
  dmumps_c(&id_);
}

void MumpsSolver::run(int job, const char* what) {
  id_.job = job;
  dmumps_c(&id_);
  if (id_.INFOG(1) < 0)
    throw NumericalError(fmt::format("MUMPS {} failed: INFOG(1) = {}, INFOG(2) = {}{}", what,
                                     id_.INFOG(1), id_.INFOG(2),
                                     id_.INFOG(1) == -10 ? " (the macro system is singular: "
                                                           "check the Dirichlet conditions)"
                                                         : ""));
}

void MumpsSolver::set_pattern(std::vector<int> rows, std::vector<int> cols) {
  FE2_CHECK(rows.size() == cols.size(), "triplet arrays differ in length");
  irn_ = std::move(rows);
  jcn_ = std::move(cols);
  for (auto& r : irn_) ++r;  // MUMPS is 1-based
  for (auto& c : jcn_) ++c;
  a_.assign(irn_.size(), 0.0);
  id_.n = n_;
  id_.nnz_loc = static_cast<MUMPS_INT8>(irn_.size());
  id_.irn_loc = irn_.data();
  id_.jcn_loc = jcn_.data();
  id_.a_loc = a_.data();
  if (requested_ == Ordering::metis) compute_nested_dissection();
  run(1, "analysis");
  analysed_ = true;
  // The ordering MUMPS actually used (INFOG(7)) can differ from the one asked for
  // (ICNTL(7) = 7: automatic) — with a saddle-point block it matters (DESIGN §6).
  static const char* const names[] = {"AMD", "METIS (user)", "AMF", "SCOTCH", "PORD", "METIS", "QAMD"};
  const int used = id_.INFOG(7);
  FE2_CHECK(requested_ != Ordering::metis || used == 1,
            "MUMPS analysed the macro system with ordering {}, not the METIS order given", used);
  ordering_ = used >= 0 && used <= 6 ? names[used] : fmt::format("code {}", used);
  spdlog::info("MUMPS analysis: {} equations, {} triplets on this rank, ordering {} (INFOG(7) = {}), "
               "unsymmetric LU with pivoting",
               n_, irn_.size(), ordering_, used);
}

void MumpsSolver::factorize_and_solve(const std::vector<double>& values, std::vector<double>& rhs) {
  factorize(values);
  solve(rhs);
}

void MumpsSolver::factorize(const std::vector<double>& values) {
  FE2_CHECK(analysed_, "set_pattern first");
  FE2_CHECK(values.size() == a_.size(), "{} values for {} triplets", values.size(), a_.size());
  a_ = values;
  id_.a_loc = a_.data();
  factored_ = false;
  run(2, "factorization");
  if (id_.INFOG(28) > 0)
    throw SingularMatrixError(fmt::format(
        "the macro matrix is singular: MUMPS found {} null pivot(s) (INFOG(28)) in {} equations. "
        "Likely cause: the Dirichlet conditions leave rigid-body motions free (each of the 3 "
        "translations and 3 rotations must be fixed, e.g. a face fixed in all components "
        "[0,1,2], not only some); otherwise a material that lost all stiffness",
        id_.INFOG(28), n_));
  factored_ = true;
}

void MumpsSolver::solve(std::vector<double>& rhs) {
  FE2_CHECK(factored_, "factorize first");
  id_.rhs = rhs.data();
  id_.nrhs = 1;
  id_.lrhs = n_;
  run(3, "solve");
}

}  // namespace fe2
