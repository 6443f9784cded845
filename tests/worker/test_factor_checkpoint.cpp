// Checkpoints that carry factors (output.checkpoint_factors, worker/cholmod_factor_io.h):
// a CHOLMOD factor written and read back solves to the same bits, refactors in place to
// the same bits, and a damaged record is refused with a message naming what is wrong.
#include "tests/worker/unit_fixtures.h"
#include "worker/cholmod_factor_io.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fe2 {
namespace {

using test::gradient;

proto::JobInput job(int step, int iteration, const Vec9& Z) {
  proto::JobInput in;
  in.step = step;
  in.iteration = iteration;
  in.apply_update = iteration > 1;
  in.Zbar = Z;
  return in;
}

template <class M>
bool same_bits(const M& a, const M& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

/// A unit's K and G after one iteration at a stretch (the test matrices).
struct Unit {
  MicroUnit unit{test::two_cell_model()};
  Unit() { unit.iterate(job(0, 1, gradient({0.05, 0.01, 0, 0, -0.02, 0, 0, 0, 0.01}))); }
  const SparseMatrix& K() const { return unit.system().K; }
  const Eigen::MatrixXd& G() const { return unit.system().G; }
};

Bytes saved(const SparseFactor& f) {
  Bytes b;
  ByteWriter w(b);
  f.save(w);
  return b;
}

std::unique_ptr<SparseFactor> loaded(const Bytes& b, const SparseMatrix& K) {
  auto f = make_sparse_factor(FactorKind::cholesky);
  ByteReader r(b, "record");
  f->load(r, K);
  EXPECT_TRUE(r.at_end());
  return f;
}

TEST(CholmodFactorRecord, RestoredFactorSolvesAndRefactorsToTheSameBits) {
  const Unit u;
  auto original = make_sparse_factor(FactorKind::cholesky);
  original->factorize(u.K());
  ASSERT_TRUE(original->savable());
  const Bytes record = saved(*original);
  // Most of the record is L's values: 8 bytes per entry of the supernodes.
  EXPECT_GT(static_cast<double>(record.size()), original->factor_bytes());
  EXPECT_LT(static_cast<double>(record.size()), 1.5 * original->factor_bytes());
  auto restored = loaded(record, u.K());
  EXPECT_TRUE(restored->ready());
  EXPECT_EQ(restored->factor_bytes(), original->factor_bytes());
  EXPECT_EQ(restored->factor_flops(), original->factor_flops());  // the cost model sees no change
  EXPECT_EQ(restored->solve_flops(), original->solve_flops());
  EXPECT_GT(restored->factor_flops(), 0.0);

  Eigen::MatrixXd X1(u.G().rows(), 9), X2(u.G().rows(), 9);
  original->solve(u.G().data(), X1.data(), 9);
  restored->solve(u.G().data(), X2.data(), 9);
  EXPECT_TRUE(same_bits(X1, X2));
  EXPECT_LT((u.K() * X2 - u.G()).norm() / u.G().norm(), 1e-12);
  // Saved again, the restored factor is the same record.
  EXPECT_TRUE(saved(*restored) == record);

  // A refresh refactors in place, on the restored analysis (Perm, supernodes, workspace
  // sizes): the same bits as the original's refactorization of the same matrix.
  SparseMatrix K2 = u.K();
  for (Eigen::Index k = 0; k < K2.nonZeros(); ++k) K2.valuePtr()[k] *= 1.0 + 1e-3 * ((k % 7) == 0);
  K2 = 0.5 * (K2 + SparseMatrix(K2.transpose()));
  original->factorize(K2);
  restored->factorize(K2);
  original->solve(u.G().data(), X1.data(), 9);
  restored->solve(u.G().data(), X2.data(), 9);
  EXPECT_TRUE(same_bits(X1, X2));
  EXPECT_TRUE(saved(*restored) == saved(*original));
}

TEST(CholmodFactorRecord, UmfpackHasNoRecord) {
  const Unit u;
  auto lu = make_sparse_factor(FactorKind::lu);
  lu->factorize(u.K());
  EXPECT_FALSE(lu->savable());
  Bytes b;
  ByteWriter w(b);
  EXPECT_THROW(lu->save(w), Error);
}

/// Offsets of the record's fields (cholmod_factor_io.h), read from the record itself.
struct Layout {
  size_t n = 0, nsuper = 0, ssize = 0, xsize = 0;
  size_t maxcsize_at = 0, perm = 0, colcount = 0, super = 0, pi = 0, px = 0, s = 0, x = 0;
  explicit Layout(const Bytes& b) {
    auto u64 = [&](size_t at) {
      uint64_t v;
      std::memcpy(&v, b.data() + at, 8);
      return static_cast<size_t>(v);
    };
    n = u64(0);
    const size_t sizes = 8 + 3 + 4;
    nsuper = u64(sizes);
    ssize = u64(sizes + 8);
    xsize = u64(sizes + 16);
    maxcsize_at = sizes + 24;
    perm = sizes + 40 + 16 + 8;  // after the five sizes, fl, lnz, and Perm's length
    colcount = perm + 4 * n + 8;
    super = colcount + 4 * n + 8;
    pi = super + 4 * (nsuper + 1) + 8;
    px = pi + 4 * (nsuper + 1) + 8;
    s = px + 4 * (nsuper + 1) + 8;
    x = s + 4 * ssize + 8;
  }
};

int32_t get_int(const Bytes& b, size_t at) {
  int32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}
void set_int(Bytes& b, size_t at, int32_t v) { std::memcpy(b.data() + at, &v, 4); }

void expect_refused(const Bytes& b, const SparseMatrix& K, const std::string& words) {
  try {
    loaded(b, K);
    ADD_FAILURE() << "a record damaged in " << words << " was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(CholmodFactorRecord, DamagedRecordsAreRefusedByName) {
  const Unit u;
  auto f = make_sparse_factor(FactorKind::cholesky);
  f->factorize(u.K());
  const Bytes good = saved(*f);
  const Layout at(good);
  ASSERT_EQ(at.n, static_cast<size_t>(u.K().rows()));
  ASSERT_EQ(at.x + 8 * at.xsize, good.size());
  ASSERT_GT(at.nsuper, 2u);
  {
    Bytes b = good;  // two pivots the same: not a permutation
    set_int(b, at.perm + 4, get_int(b, at.perm));
    expect_refused(b, u.K(), "is not a permutation");
  }
  {
    Bytes b = good;
    set_int(b, at.super + 4, 0);
    expect_refused(b, u.K(), "super is not increasing");
  }
  {
    Bytes b = good;  // the last row of the first supernode beyond n
    const int32_t end = get_int(b, at.pi + 4);
    set_int(b, at.s + 4 * (end - 1), static_cast<int32_t>(at.n));
    expect_refused(b, u.K(), "row");
  }
  {
    Bytes b = good;  // a too small update workspace would overrun on a refactorization
    uint64_t m;
    std::memcpy(&m, b.data() + at.maxcsize_at, 8);
    --m;
    std::memcpy(b.data() + at.maxcsize_at, &m, 8);
    expect_refused(b, u.K(), "maxcsize");
  }
  {
    Bytes b = good;
    const double nan = std::nan("");
    std::memcpy(b.data() + at.x + 8 * (at.xsize / 2), &nan, 8);
    expect_refused(b, u.K(), "x[");
  }
  {
    Bytes b = good;  // px no longer matches the supernode's rows × columns
    set_int(b, at.px + 8, get_int(b, at.px + 8) + 1);
    expect_refused(b, u.K(), "px[");
  }
  {
    // K with its first row and column filled: of the same size, but a refactorization
    // would assemble it outside the stored pattern.
    std::vector<Eigen::Triplet<double>> t;
    for (Eigen::Index j = 0; j < u.K().outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(u.K(), j); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
    for (int j = 1; j < u.K().rows(); ++j) t.emplace_back(0, j, 1e-3), t.emplace_back(j, 0, 1e-3);
    SparseMatrix wider(u.K().rows(), u.K().cols());
    wider.setFromTriplets(t.begin(), t.end());
    expect_refused(good, wider, "falls outside the factor's pattern");
  }
  // The pattern of another matrix: a unit of a different resolution.
  MicroUnit other(test::two_cell_model({}, {4, 4, 4}));
  other.iterate(job(0, 1, gradient({0.02, 0, 0, 0, 0, 0, 0, 0, 0})));
  expect_refused(good, other.system().K, "n = ");
  // Every truncation of the structure, and some of the values, is refused.
  for (size_t len = 0; len < good.size(); len += len < at.perm + 16 || (len > at.x - 16 && len < at.x + 64) ? 1 : 997) {
    const Bytes cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(len));
    EXPECT_THROW(loaded(cut, u.K()), Error) << "truncated to " << len << " bytes";
  }
  // Flips of any byte of the structure: refused, or (a flip the checks cannot see, e.g.
  // in ColCount) loaded; never a crash. Counted so that the test shows it refuses most.
  int refused = 0, flips = 0;
  for (size_t k = 0; k < at.x; k += std::max<size_t>(1, at.x / 1500), ++flips) {
    Bytes b = good;
    b[k] ^= std::byte{0x5a};
    try {
      loaded(b, u.K());
    } catch (const Error&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, flips * 3 / 4) << refused << " of " << flips << " flips refused";
}

// A unit checkpointed with its factor continues without refactoring, bit for bit as
// the unit that was not interrupted; checkpointed with the flag, it rebuilds first.
TEST(MicroUnitCheckpoint, WithFactorContinuesWithoutRebuild) {
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::fixed;
  opt.N_t = 100;
  const auto model = test::two_cell_model(opt);
  MicroUnit run(model);
  const Vec9 Z1 = gradient({0.05, 0.0, 0.01, 0.0, -0.01, 0.0, 0.02, 0.0, 0.0});
  run.iterate(job(0, 1, Z1));
  run.iterate(job(0, 2, Z1));
  run.commit_step();
  Bytes with, without, migrated;
  run.serialize_for_checkpoint(with, true);
  run.serialize_for_checkpoint(without, false);
  run.serialize(migrated);
  EXPECT_TRUE(without == migrated);
  EXPECT_EQ(without.size(), run.state_bytes());
  EXPECT_GT(static_cast<double>(with.size() - without.size()), run.factor_bytes());

  MicroUnit restored(model), rebuilt(model);
  restored.deserialize(with);
  rebuilt.deserialize(without);
  EXPECT_EQ(restored.factor_bytes(), run.factor_bytes());
  EXPECT_EQ(rebuilt.factor_bytes(), 0.0);
  for (int it = 1; it < 4; ++it) {
    const Vec9 Z = (1.1 + 0.05 * it) * Z1;
    const auto a = run.iterate(job(1, it, Z));
    const auto b = restored.iterate(job(1, it, Z));
    const auto c = rebuilt.iterate(job(1, it, Z));
    EXPECT_EQ(a.kind, proto::Refresh::reuse);
    EXPECT_TRUE(same_bits(a.A_hom, b.A_hom) && same_bits(a.P_tilde, b.P_tilde)) << "iteration " << it;
    EXPECT_TRUE(same_bits(a.A_hom, c.A_hom) && same_bits(a.P_tilde, c.P_tilde)) << "iteration " << it;
    EXPECT_EQ(b.factor_rebuilt, 0) << "iteration " << it;
    EXPECT_EQ(b.cpu_refresh, 0.0) << "iteration " << it;
    EXPECT_EQ(c.factor_rebuilt, it == 1 ? 1 : 0) << "iteration " << it;
  }
  EXPECT_TRUE(same_bits(run.w(), restored.w()));
  // A factor dropped by the memory budget leaves the rebuild flag, as without the key.
  run.commit_step();
  run.drop_factor();
  Bytes dropped_with, dropped_without;
  run.serialize_for_checkpoint(dropped_with, true);
  run.serialize_for_checkpoint(dropped_without, false);
  EXPECT_TRUE(dropped_with == dropped_without);
  EXPECT_EQ(dropped_with.size(), run.state_bytes());
  // A stored factor without the matrix it belongs to, or an unknown record flag, is refused.
  Bytes bad = without;
  bad.back() = std::byte{7};
  MicroUnit other(model);
  EXPECT_THROW(other.deserialize(bad), Error);
}

TEST(MicroUnitCheckpoint, LuUnitsStoreTheRebuildFlag) {
  MicroSolverOptions opt;
  opt.factorization = MicroSolverOptions::Factorization::lu;
  const auto model = test::two_cell_model(opt);
  MicroUnit unit(model);
  unit.iterate(job(0, 1, gradient({0.03, 0, 0, 0, 0, 0, 0, 0, 0})));
  unit.commit_step();
  Bytes with, without;
  unit.serialize_for_checkpoint(with, true);
  unit.serialize_for_checkpoint(without, false);
  EXPECT_TRUE(with == without);
  EXPECT_GT(unit.factor_bytes(), 0.0);
}

}  // namespace
}  // namespace fe2
