#pragma once
// The one place fe2heart talks MPI (besides the communicator handed to MUMPS):
// point-to-point messages (Transport) and collectives on a group of ranks (Group).
// Every MPI return code is checked (the communicators are set to MPI_ERRORS_RETURN)
// and reported with MPI's own error string.
#include "common/bytes.h"
#include "proto/messages.h"

#include <mpi.h>

#include <list>
#include <string>
#include <vector>

namespace fe2::proto {

/// Throws fe2::Error naming `what` and MPI's error text if rc is not MPI_SUCCESS.
void check_mpi(int rc, const char* what);

/// The liveness limit of this process, wall seconds (farm.stall_timeout; default: none).
/// Every wait here — a receive, a collective — gives up after it with a StallError, so
/// a frozen peer cannot hang the job.
void set_stall_timeout(double seconds);
double stall_timeout();

/// Waits that depend on another waiting rank (a worker waiting for its coordinator's
/// next command or batch, a coordinator in a collective with the others) allow this
/// multiple of the limit, so that the rank waiting on the silent one directly reports
/// first and names it.
constexpr double kIndirectPatience = 2.0;

/// Waits for `request` (nonblocking send, receive or collective) within `patience`
/// times the liveness limit; throws StallError "<what>: no answer for N s" after it.
void wait_alive(MPI_Request& request, const std::string& what, double patience = 1.0);

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
  /// Exact, so the result does not depend on how the terms are spread over ranks.
  void allreduce_sum(int64_t* v, int n) const;
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
  /// Blocks for a message of `type` from `source` (MPI_ANY_SOURCE for any), at most
  /// the liveness limit (then StallError naming the type and source).
  Bytes recv(Type type, int source, int* from = nullptr, double patience = 1.0);
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
