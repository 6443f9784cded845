// GoogleTest main that initializes MPI (MUMPS needs it even on one process). Test
// order stays fixed (no shuffling) so every rank runs the same sequence.
#include <gtest/gtest.h>
#include <mpi.h>

int main(int argc, char** argv) {
  int provided = 0;  // as fe2heart: helper threads of a JobPool never call MPI
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  ::testing::InitGoogleTest(&argc, argv);
  const int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
