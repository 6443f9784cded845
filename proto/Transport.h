#pragma once
// The one place fe2heart talks MPI (besides the communicator handed to MUMPS):
// point-to-point messages (Transport) and collectives on a group of ranks (Group).
// Every MPI return code is checked (the communicators are set to MPI_ERRORS_RETURN)
// and reported with MPI's own error string.
#include "common/bytes.h"
#include "proto/messages.h"

#include <mpi.h>

#include <list>
#include <vector>

namespace fe2::proto {

/// Throws fe2::Error naming `what` and MPI's error text if rc is not MPI_SUCCESS.
void check_mpi(int rc, const char* what);

/// Collectives on one communicator (not owned unless created by split()).
/// Every function here is @note Collective on the group.
class Group {
 public:
  explicit Group(MPI_Comm comm = MPI_COMM_NULL, bool owned = false);
  ~Group();
  Group(Group&& o) noexcept;
  Group& operator=(Group&& o) noexcept;
  Group(const Group&) = delete;
  Group& operator=(const Group&) = delete;

  bool valid() const { return comm_ != MPI_COMM_NULL; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  MPI_Comm raw() const { return comm_; }

  void allreduce_sum(double* v, int n) const;
  double allreduce_max(double x) const;
  int allreduce_max(int x) const;
  void reduce_sum(double* v, int n, int root) const;
  void bcast(double* v, int n, int root) const;
  void bcast(Bytes& b, int root) const;
  /// All ranks' byte strings on `root` (empty elsewhere).
  std::vector<Bytes> gather(const Bytes& mine, int root) const;
  void barrier() const;
  /// Ranks with the same color form a new group; color < 0 gets an invalid group.
  Group split(int color, int key) const;

 private:
  MPI_Comm comm_;
  bool owned_;
  int rank_ = -1, size_ = 0;
};

/// Point-to-point messages on the world communicator. Sends never block (each keeps
/// its buffer until MPI is done with it), so ranks that both coordinate and work can
/// message themselves and each other without deadlock.
class Transport {
 public:
  explicit Transport(MPI_Comm world);
  ~Transport();
  int rank() const { return rank_; }
  int size() const { return size_; }

  void send(int dest, Type type, Bytes bytes);
  /// Blocks for a message of `type` from `source` (MPI_ANY_SOURCE for any).
  Bytes recv(Type type, int source, int* from = nullptr);
  /// Receives a waiting message of `type`, if there is one; never blocks.
  bool try_recv(Type type, Bytes& out, int* from = nullptr, int source = MPI_ANY_SOURCE);
  /// Waits for every outstanding send.
  void complete_sends();
  /// Ends every rank of the job (a fatal error on one rank must not leave others hanging).
  [[noreturn]] void abort(int code) const;

  int64_t bytes_sent() const { return bytes_sent_; }
  int64_t bytes_received() const { return bytes_received_; }

 private:
  void reap();
  struct Pending {
    MPI_Request request;
    Bytes buffer;
  };
  MPI_Comm world_;
  int rank_ = 0, size_ = 1;
  std::list<Pending> pending_;
  int64_t bytes_sent_ = 0, bytes_received_ = 0;
};

}  // namespace fe2::proto
