#pragma once
// Every coordinator decides a failure alike: a numerical failure on one of them (an
// inverted element, a unit that failed, a non-finite residual) becomes the same
// NumericalError on all, so that they cut the step back together and none hangs in a
// collective the others have left.
#include "proto/Transport.h"

#include <string>

namespace fe2 {

/// Throws the same NumericalError on every coordinator if any of them failed (`why`
/// non-empty on the ones that did), with the lowest failing coordinator's reason.
/// @note Collective on `group`.
void agree_on_failure(const proto::Group& group, const std::string& why);

}  // namespace fe2
