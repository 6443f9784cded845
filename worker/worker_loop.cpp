#include "worker/worker_loop.h"

#include "worker/PullClient.h"

#include <set>

namespace fe2 {

std::vector<int> coordinators_of(const UnitStore& store, const std::vector<int>& coordinator_of_unit) {
  std::set<int> c;
  for (int u : store.units()) c.insert(coordinator_of_unit[u]);
  return {c.begin(), c.end()};
}

void send_unit_fields(proto::Transport& transport, const UnitStore& store,
                      const std::vector<proto::Move>& requests, int step) {
  for (const proto::Move& m : requests)
    if (m.from == transport.rank()) {
      Bytes b;
      store.fields(m.unit, step).pack(b);
      transport.send(m.to, proto::Type::unit_fields, std::move(b));
    }
}

void send_unit_states(proto::Transport& transport, const std::vector<proto::Move>& requests,
                      const std::function<Bytes(int)>& copy) {
  for (const proto::Move& m : requests)
    if (m.from == transport.rank()) {
      proto::UnitState s;
      s.unit = m.unit;
      s.state = copy(m.unit);
      Bytes b;
      s.pack(b);
      transport.send(m.to, proto::Type::state, std::move(b));
    }
}

void receive_unit_states(proto::Transport& transport, const std::vector<proto::Move>& requests,
                         const std::function<void(int, const Bytes&)>& restore) {
  for (const proto::Move& m : requests)
    if (m.to == transport.rank()) {
      const proto::UnitState s = proto::UnitState::unpack(transport.recv(proto::Type::state, m.from));
      FE2_CHECK(s.unit == m.unit, "expected the checkpointed state of unit {} from rank {}, got unit {}",
                m.unit, m.from, s.unit);
      restore(s.unit, s.state);
    }
}

void run_worker_loop(proto::Transport& transport, UnitStore& store,
                     const std::vector<int>& coordinator_of_unit, int batch, int threads) {
  PullClient client(transport, store, batch, threads);
  for (;;) {
    const proto::Control c = proto::Control::unpack(
        transport.recv(proto::Type::control, 0, nullptr, proto::kIndirectPatience));
    switch (c.command) {
      case proto::Command::iterate: {
        client.begin(coordinators_of(store, coordinator_of_unit), c.step, c.iteration);
        while (!client.poll(true)) {
        }
        Bytes b;
        client.stats().pack(b);
        transport.send(0, proto::Type::stats, std::move(b));
        break;
      }
      case proto::Command::commit: store.commit(); break;
      case proto::Command::rollback: store.rollback(); break;
      case proto::Command::rebalance: {
        const auto [in, out] = migrate(transport, store, c.moves);
        client.count_migrations(in, out);
        break;
      }
      case proto::Command::fields: send_unit_fields(transport, store, c.moves, c.step); break;
      case proto::Command::checkpoint:
        send_unit_states(transport, c.moves, [&](int u) { return store.copy(u, c.with_factors != 0); });
        break;
      case proto::Command::restore:
        receive_unit_states(transport, c.moves, [&](int u, const Bytes& b) { store.restore(u, b); });
        break;
      case proto::Command::shutdown: transport.complete_sends(); return;
    }
  }
}

}  // namespace fe2
