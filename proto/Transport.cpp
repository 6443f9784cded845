#include "proto/Transport.h"

#include "common/error.h"

#include <chrono>
#include <climits>
#include <limits>
#include <thread>
#include <exception>

namespace fe2::proto {

void check_mpi(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw Error(fmt::format("MPI {} failed: {} (code {})", what, std::string(text, len), rc));
}

namespace {
double g_stall_timeout = std::numeric_limits<double>::infinity();

/// Polls `done()` until it is true or the liveness limit passes (then false). Spins
/// through short waits as MPI's blocking calls do (a napping rank measured 9 % more CPU
/// per unit job on farm_beam at 2 ranks: its core goes cold), and naps with growing
/// pauses only once a wait outlasts kSpinSeconds, leaving the core to computing ranks.
template <class Done>
bool poll_alive(Done done, double patience) {
  constexpr double kSpinSeconds = 0.05;
  const double limit = patience * g_stall_timeout;
  const auto t0 = std::chrono::steady_clock::now();
  auto nap = std::chrono::microseconds(10);
  for (;;) {
    if (done()) return true;
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (waited > limit) return false;
    if (waited < kSpinSeconds) continue;
    std::this_thread::sleep_for(nap);
    nap = std::min(nap * 2, std::chrono::microseconds(1000));
  }
}
}  // namespace

void set_stall_timeout(double seconds) {
  FE2_CHECK(seconds > 0, "stall timeout {} must be positive", seconds);
  g_stall_timeout = seconds;
}

double stall_timeout() { return g_stall_timeout; }

void wait_alive(MPI_Request& request, const std::string& what, double patience) {
  const bool ok = poll_alive(
      [&] {
        int flag = 0;
        check_mpi(MPI_Test(&request, &flag, MPI_STATUS_IGNORE), "Test");
        return flag != 0;
      },
      patience);
  if (!ok)
    throw StallError(fmt::format("{}: no answer for {:.0f} s (farm.stall_timeout): a rank is "
                                 "frozen, lost or slower than the limit",
                                 what, patience * g_stall_timeout));
}

Group::Group(MPI_Comm comm, bool owned) : comm_(comm), owned_(owned) {
  if (comm_ == MPI_COMM_NULL) return;
  check_mpi(MPI_Comm_set_errhandler(comm_, MPI_ERRORS_RETURN), "Comm_set_errhandler");
  check_mpi(MPI_Comm_rank(comm_, &rank_), "Comm_rank");
  check_mpi(MPI_Comm_size(comm_, &size_), "Comm_size");
}

Group::~Group() {
  // MPI_Comm_free is collective: never while an exception unwinds (see MumpsSolver).
  if (owned_ && comm_ != MPI_COMM_NULL && std::uncaught_exceptions() == 0) MPI_Comm_free(&comm_);
}

Group::Group(Group&& o) noexcept : comm_(o.comm_), owned_(o.owned_), rank_(o.rank_), size_(o.size_) {
  o.comm_ = MPI_COMM_NULL;
  o.owned_ = false;
}

Group& Group::operator=(Group&& o) noexcept {
  if (this != &o) {
    if (owned_ && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
    comm_ = o.comm_;
    owned_ = o.owned_;
    rank_ = o.rank_;
    size_ = o.size_;
    o.comm_ = MPI_COMM_NULL;
    o.owned_ = false;
  }
  return *this;
}

void Group::allreduce_sum(double* v, int n) const {
  MPI_Request q;
  check_mpi(MPI_Iallreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, comm_, &q), "Iallreduce(sum)");
  wait_alive(q, "collective Allreduce(sum)", kIndirectPatience);
}

void Group::allreduce_sum(int64_t* v, int n) const {
  MPI_Request q;
  check_mpi(MPI_Iallreduce(MPI_IN_PLACE, v, n, MPI_INT64_T, MPI_SUM, comm_, &q), "Iallreduce(sum)");
  wait_alive(q, "collective Allreduce(sum)", kIndirectPatience);
}

double Group::allreduce_max(double x) const {
  MPI_Request q;
  check_mpi(MPI_Iallreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, comm_, &q), "Iallreduce(max)");
  wait_alive(q, "collective Allreduce(max)", kIndirectPatience);
  return x;
}

int Group::allreduce_max(int x) const {
  MPI_Request q;
  check_mpi(MPI_Iallreduce(MPI_IN_PLACE, &x, 1, MPI_INT, MPI_MAX, comm_, &q), "Iallreduce(max)");
  wait_alive(q, "collective Allreduce(max)", kIndirectPatience);
  return x;
}

void Group::reduce_sum(double* v, int n, int root) const {
  MPI_Request q;
  if (rank_ == root)
    check_mpi(MPI_Ireduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, root, comm_, &q), "Ireduce(sum)");
  else
    check_mpi(MPI_Ireduce(v, nullptr, n, MPI_DOUBLE, MPI_SUM, root, comm_, &q), "Ireduce(sum)");
  wait_alive(q, "collective Reduce(sum)", kIndirectPatience);
}

void Group::bcast(double* v, int n, int root) const {
  MPI_Request q;
  check_mpi(MPI_Ibcast(v, n, MPI_DOUBLE, root, comm_, &q), "Ibcast");
  wait_alive(q, "collective Bcast", kIndirectPatience);
}

void Group::bcast(Bytes& b, int root) const {
  long long n = static_cast<long long>(b.size());
  MPI_Request q;
  check_mpi(MPI_Ibcast(&n, 1, MPI_LONG_LONG, root, comm_, &q), "Ibcast(size)");
  wait_alive(q, "collective Bcast(size)", kIndirectPatience);
  FE2_CHECK(n < INT_MAX, "broadcast of {} bytes", n);
  b.resize(static_cast<size_t>(n));
  check_mpi(MPI_Ibcast(b.data(), static_cast<int>(n), MPI_BYTE, root, comm_, &q), "Ibcast(bytes)");
  wait_alive(q, "collective Bcast(bytes)", kIndirectPatience);
}

std::vector<Bytes> Group::gather(const Bytes& mine, int root) const {
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(rank_ == root ? size_ : 0), displs;
  MPI_Request q;
  check_mpi(MPI_Igather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_, &q), "Igather(size)");
  wait_alive(q, "collective Gather(size)", kIndirectPatience);
  std::vector<std::byte> all;
  if (rank_ == root) {
    displs.resize(size_);
    long long total = 0;
    for (int r = 0; r < size_; ++r) displs[r] = static_cast<int>(total), total += counts[r];
    FE2_CHECK(total < INT_MAX, "gather of {} bytes", total);
    all.resize(static_cast<size_t>(total));
  }
  check_mpi(MPI_Igatherv(mine.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(),
                         MPI_BYTE, root, comm_, &q),
            "Igatherv");
  wait_alive(q, "collective Gatherv", kIndirectPatience);
  std::vector<Bytes> out;
  if (rank_ == root)
    for (int r = 0; r < size_; ++r)
      out.emplace_back(all.begin() + displs[r], all.begin() + displs[r] + counts[r]);
  return out;
}

void Group::barrier() const {
  MPI_Request q;
  check_mpi(MPI_Ibarrier(comm_, &q), "Ibarrier");
  wait_alive(q, "collective Barrier", kIndirectPatience);
}

Group Group::split(int color, int key) const {
  MPI_Comm out = MPI_COMM_NULL;
  check_mpi(MPI_Comm_split(comm_, color < 0 ? MPI_UNDEFINED : color, key, &out), "Comm_split");
  return Group(out, out != MPI_COMM_NULL);
}

Transport::Transport(MPI_Comm world) : world_(world) {
  check_mpi(MPI_Comm_set_errhandler(world_, MPI_ERRORS_RETURN), "Comm_set_errhandler");
  check_mpi(MPI_Comm_rank(world_, &rank_), "Comm_rank");
  check_mpi(MPI_Comm_size(world_, &size_), "Comm_size");
}

Transport::~Transport() {
  if (std::uncaught_exceptions() > 0) return;  // a peer may never receive: do not wait
  try {
    complete_sends();
  } catch (...) {
  }
}

void Transport::send(int dest, Type type, Bytes bytes) {
  FE2_CHECK(bytes.size() < INT_MAX, "message of {} bytes", bytes.size());
  pending_.push_back({MPI_REQUEST_NULL, std::move(bytes)});
  Pending& p = pending_.back();
  bytes_sent_ += static_cast<int64_t>(p.buffer.size());
  check_mpi(MPI_Isend(p.buffer.data(), static_cast<int>(p.buffer.size()), MPI_BYTE, dest,
                      tag_of(type), world_, &p.request),
            "Isend");
  reap();
}

void Transport::reap() {
  for (auto it = pending_.begin(); it != pending_.end();) {
    int done = 0;
    check_mpi(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "Test");
    it = done ? pending_.erase(it) : std::next(it);
  }
}

Bytes Transport::recv(Type type, int source, int* from, double patience) {
  MPI_Status st;
  const bool arrived = poll_alive(
      [&] {
        int flag = 0;
        check_mpi(MPI_Iprobe(source, tag_of(type), world_, &flag, &st), "Iprobe");
        return flag != 0;
      },
      patience);
  if (!arrived)
    throw StallError(fmt::format("no '{}' message from {} for {:.0f} s (farm.stall_timeout)",
                                 name_of(type),
                                 source == MPI_ANY_SOURCE ? std::string("any rank")
                                                          : fmt::format("rank {}", source),
                                 patience * g_stall_timeout));
  int n = 0;
  check_mpi(MPI_Get_count(&st, MPI_BYTE, &n), "Get_count");
  Bytes b(static_cast<size_t>(n));
  check_mpi(MPI_Recv(b.data(), n, MPI_BYTE, st.MPI_SOURCE, tag_of(type), world_, MPI_STATUS_IGNORE),
            "Recv");
  bytes_received_ += n;
  if (from) *from = st.MPI_SOURCE;
  reap();
  return b;
}

bool Transport::try_recv(Type type, Bytes& out, int* from, int source) {
  int flag = 0;
  MPI_Status st;
  check_mpi(MPI_Iprobe(source, tag_of(type), world_, &flag, &st), "Iprobe");
  if (!flag) return false;
  out = recv(type, st.MPI_SOURCE, from);
  return true;
}

void Transport::complete_sends() {
  for (auto& p : pending_) wait_alive(p.request, "completing a send", kIndirectPatience);
  pending_.clear();
}

void Transport::abort(int code) const { MPI_Abort(world_, code); std::abort(); }

}  // namespace fe2::proto
