// Every unpack of proto/messages.h on arbitrary bytes. The message type in the header
// picks the unpack (so seeds are real packed messages, tests/fuzz/make_proto_seeds.cpp);
// any other type goes to every unpack, which must all refuse it. A corrupt buffer must
// end in fe2::Error, never a crash or a huge allocation (lengths are bounded by the
// bytes left); an accepted message must pack to the same size and be a fixed point of
// unpack∘pack.
#include "proto/messages.h"
#include "tests/fuzz/fuzz_support.h"

using namespace fe2;
using namespace fe2::proto;

namespace {

template <class M>
void round_trip(const Bytes& in) {
  fuzz::expect_only<Error>([&] {
    const M m = M::unpack(in);
    Bytes once;
    m.pack(once);
    fuzz::require(once.size() == in.size(), "a repacked message has the received size");
    Bytes twice;
    M::unpack(once).pack(twice);
    fuzz::require(once == twice, "unpack(pack(m)) packs to the same bytes");
  });
}

// The job and result records on their own, as Batch and Pull read them.
void records(const Bytes& in) {
  fuzz::expect_only<Error>([&] {
    ByteReader r(in, "job");
    while (!r.at_end()) unpack_job(r);
  });
  fuzz::expect_only<Error>([&] {
    ByteReader r(in, "result");
    while (!r.at_end()) unpack_result(r);
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Bytes in = fuzz::bytes_of(data, size);
  const int type = size >= 4 ? std::to_integer<int>(in[2]) | std::to_integer<int>(in[3]) << 8 : 0;
  const bool any = type < 1 || type > 8;
  if (any || type == int(Type::hello)) round_trip<Hello>(in);
  if (any || type == int(Type::control)) round_trip<Control>(in);
  if (any || type == int(Type::pull)) round_trip<Pull>(in);
  if (any || type == int(Type::batch)) round_trip<Batch>(in);
  if (any || type == int(Type::stats)) round_trip<WorkerStats>(in);
  if (any || type == int(Type::state)) round_trip<UnitState>(in);
  if (any || type == int(Type::costs)) round_trip<CostReport>(in);
  if (any || type == int(Type::unit_fields)) round_trip<UnitFields>(in);
  if (any) records(in);
  return 0;
}
