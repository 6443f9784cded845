#include "proto/Transport.h"

#include "common/error.h"

#include <climits>

namespace fe2::proto {

void check_mpi(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw Error(fmt::format("MPI {} failed: {} (code {})", what, std::string(text, len), rc));
}

Group::Group(MPI_Comm comm, bool owned) : comm_(comm), owned_(owned) {
  if (comm_ == MPI_COMM_NULL) return;
  check_mpi(MPI_Comm_set_errhandler(comm_, MPI_ERRORS_RETURN), "Comm_set_errhandler");
  check_mpi(MPI_Comm_rank(comm_, &rank_), "Comm_rank");
  check_mpi(MPI_Comm_size(comm_, &size_), "Comm_size");
}

Group::~Group() {
  if (owned_ && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
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
  check_mpi(MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, comm_), "Allreduce(sum)");
}

double Group::allreduce_max(double x) const {
  check_mpi(MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, comm_), "Allreduce(max)");
  return x;
}

int Group::allreduce_max(int x) const {
  check_mpi(MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_INT, MPI_MAX, comm_), "Allreduce(max)");
  return x;
}

void Group::reduce_sum(double* v, int n, int root) const {
  if (rank_ == root)
    check_mpi(MPI_Reduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, root, comm_), "Reduce(sum)");
  else
    check_mpi(MPI_Reduce(v, nullptr, n, MPI_DOUBLE, MPI_SUM, root, comm_), "Reduce(sum)");
}

void Group::bcast(double* v, int n, int root) const {
  check_mpi(MPI_Bcast(v, n, MPI_DOUBLE, root, comm_), "Bcast");
}

void Group::bcast(Bytes& b, int root) const {
  long long n = static_cast<long long>(b.size());
  check_mpi(MPI_Bcast(&n, 1, MPI_LONG_LONG, root, comm_), "Bcast(size)");
  FE2_CHECK(n < INT_MAX, "broadcast of {} bytes", n);
  b.resize(static_cast<size_t>(n));
  check_mpi(MPI_Bcast(b.data(), static_cast<int>(n), MPI_BYTE, root, comm_), "Bcast(bytes)");
}

std::vector<Bytes> Group::gather(const Bytes& mine, int root) const {
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(rank_ == root ? size_ : 0), displs;
  check_mpi(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_), "Gather(size)");
  std::vector<std::byte> all;
  if (rank_ == root) {
    displs.resize(size_);
    long long total = 0;
    for (int r = 0; r < size_; ++r) displs[r] = static_cast<int>(total), total += counts[r];
    FE2_CHECK(total < INT_MAX, "gather of {} bytes", total);
    all.resize(static_cast<size_t>(total));
  }
  check_mpi(MPI_Gatherv(mine.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(),
                        MPI_BYTE, root, comm_),
            "Gatherv");
  std::vector<Bytes> out;
  if (rank_ == root)
    for (int r = 0; r < size_; ++r)
      out.emplace_back(all.begin() + displs[r], all.begin() + displs[r] + counts[r]);
  return out;
}

void Group::barrier() const { check_mpi(MPI_Barrier(comm_), "Barrier"); }

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

Bytes Transport::recv(Type type, int source, int* from) {
  MPI_Status st;
  check_mpi(MPI_Probe(source, tag_of(type), world_, &st), "Probe");
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
  for (auto& p : pending_) check_mpi(MPI_Wait(&p.request, MPI_STATUS_IGNORE), "Wait");
  pending_.clear();
}

void Transport::abort(int code) const { MPI_Abort(world_, code); std::abort(); }

}  // namespace fe2::proto
