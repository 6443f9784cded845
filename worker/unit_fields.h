#pragma once
// The micro fields of one unit for output (output.units; paper Fig. 11): the
// fluctuation w at every node and, per micro element, the volume mean of the first
// Piola stress Π over its Gauss points, the mean det F and the mean T_a. Read from the
// unit's last assembled state, re-assembled with that state's context, so the stress
// of a law with history or rate is the one the unit reported: call it after the step's
// converged iteration and BEFORE the step is committed (a commit makes that state the
// committed one, and re-assembling would then advance history and rates once more).
#include "proto/messages.h"
#include "worker/MicroUnit.h"

namespace fe2 {

/// `unit` and `step` label the result (the unit's global id, the output step).
proto::UnitFields micro_fields(const MicroUnit& micro, int unit, int step);

}  // namespace fe2
