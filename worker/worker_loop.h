#pragma once
// The whole life of a rank that only works (DESIGN §3), in one function: wait for
// coordinator 0's control message and do what it says — run an iteration's jobs
// (pulled from the coordinators owning this rank's units, stats to rank 0 after),
// commit or roll back the step, migrate units, send units' micro fields for output,
// copy units' states into a checkpoint or take them from one, or shut down.
#include "proto/Transport.h"
#include "worker/UnitStore.h"

#include <functional>
#include <vector>

namespace fe2 {

/// `coordinator_of_unit` maps each unit to the world rank of its coordinator; `threads`
/// run the jobs (PullClient).
/// @note Returns on the shutdown message.
void run_worker_loop(proto::Transport& transport, UnitStore& store,
                     const std::vector<int>& coordinator_of_unit, int batch, int threads = 1);

/// Answers a `fields` request: for each (unit, from, to) with from = this rank, sends
/// the unit's UnitFields of output step `step` to rank `to`.
void send_unit_fields(proto::Transport& transport, const UnitStore& store,
                      const std::vector<proto::Move>& requests, int step);

/// Answers a `checkpoint` request: for each (unit, from, to) with from = this rank, sends
/// `copy(unit)` (a copy of the unit's state) to rank `to` as a State message.
void send_unit_states(proto::Transport& transport, const std::vector<proto::Move>& requests,
                      const std::function<Bytes(int unit)>& copy);

/// Answers a `restore` request: for each (unit, from, to) with to = this rank, in order,
/// receives the unit's state from rank `from` and hands it to `restore`.
void receive_unit_states(proto::Transport& transport, const std::vector<proto::Move>& requests,
                         const std::function<void(int unit, const Bytes& state)>& restore);

/// The coordinators that own at least one of the units in `store`, ascending.
std::vector<int> coordinators_of(const UnitStore& store, const std::vector<int>& coordinator_of_unit);

}  // namespace fe2
