#pragma once
// The whole life of a rank that only works (DESIGN §3), in one function: wait for
// coordinator 0's control message and do what it says — run an iteration's jobs
// (pulled from the coordinators owning this rank's units, stats to rank 0 after),
// commit or roll back the step, migrate units, send units' micro fields for output, or
// shut down.
#include "proto/Transport.h"
#include "worker/UnitStore.h"

#include <vector>

namespace fe2 {

/// `coordinator_of_unit` maps each unit to the world rank of its coordinator.
/// @note Returns on the shutdown message.
void run_worker_loop(proto::Transport& transport, UnitStore& store,
                     const std::vector<int>& coordinator_of_unit, int batch);

/// Answers a `fields` request: for each (unit, from, to) with from = this rank, sends
/// the unit's UnitFields of output step `step` to rank `to`.
void send_unit_fields(proto::Transport& transport, const UnitStore& store,
                      const std::vector<proto::Move>& requests, int step);

/// The coordinators that own at least one of the units in `store`, ascending.
std::vector<int> coordinators_of(const UnitStore& store, const std::vector<int>& coordinator_of_unit);

}  // namespace fe2
