// Writes one packed message of every proto/ type into DIR (the seed corpus of
// fuzz_proto): make_proto_seeds DIR. The CTest fuzz test regenerates them into the
// build folder, so a new protocol version never leaves the fuzzer at the header; the
// copies in tests/fuzz/corpus/proto/ are the committed seeds.
#include "proto/messages.h"

#include <cstdio>
#include <fstream>
#include <string>

using namespace fe2;
using namespace fe2::proto;

namespace {

JobInput job(int unit) {
  JobInput j;
  j.unit = unit;
  j.step = 2;
  j.iteration = 3;
  j.time = 0.5;
  j.dt = 0.01;
  j.apply_update = 1;
  for (int i = 0; i < 9; ++i) j.Zbar[i] = 0.01 * i, j.Zbar_dot[i] = 0.1 * i;
  j.Zbar_dot_coefficient = 100.0;
  j.activation_time = 0.02;
  return j;
}

JobOutput result(int unit, bool failed) {
  JobOutput o;
  o.unit = unit;
  for (int i = 0; i < 81; ++i) o.A_hom.data()[i] = (i % 10 == 0) ? 1e4 : 1.0;
  for (int i = 0; i < 9; ++i) o.P_tilde[i] = i, o.P_bar[i] = i + 0.5;
  o.r_norm = 1e-10;
  o.gmres_iterations = 3;
  o.kind = Refresh::refresh;
  o.cpu_seconds = 0.02;
  o.next_refresh = next_step;
  o.state_bytes = 4096;
  o.factor_evictions = 1;
  o.failed = failed;
  if (failed) o.message = "no convergence";
  return o;
}

template <class M>
void write(const std::string& dir, const char* name, const M& m) {
  Bytes b;
  m.pack(b);
  std::ofstream(dir + "/" + name + ".bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  write(dir, "hello", Hello{0x1234abcdULL, 1, 4});
  Control c;
  c.command = Command::rebalance;
  c.step = 3;
  c.iteration = 2;
  c.time = 0.3;
  c.dt = 0.1;
  c.moves = {{5, 0, 1}, {7, 1, 0}};
  write(dir, "control", c);
  Pull p;
  p.worker = 1;
  p.max_jobs = 4;
  p.results = {result(3, false), result(4, true)};
  write(dir, "pull", p);
  Batch b;
  b.jobs = {job(3), job(4)};
  write(dir, "batch", b);
  WorkerStats s;
  s.worker = 1;
  s.t_begin = 1.0;
  s.t_end = 2.0;
  s.busy_cpu = 0.7;
  write(dir, "stats", s);
  UnitState st;
  st.unit = 9;
  st.state = Bytes(40, std::byte{7});
  write(dir, "state", st);
  CostReport rep;
  rep.step = 1;
  rep.iteration = 2;
  rep.jobs = {JobCost::of(result(3, false)), JobCost::of(result(4, true))};
  write(dir, "costs", rep);
  UnitFields f;
  f.unit = 2;
  f.step = 1;
  f.w = std::vector<double>(3 * 8, 0.001);
  f.P = std::vector<double>(9, 10.0);
  f.det_F = {1.0};
  f.active_tension = {0.0};
  write(dir, "fields", f);
  return 0;
}
