#include "coordinator/agree_on_failure.h"

#include "common/bytes.h"
#include "common/error.h"

namespace fe2 {

void agree_on_failure(const proto::Group& group, const std::string& why) {
  const int failed = group.allreduce_max(static_cast<int>(!why.empty()));
  if (!failed) return;
  const int first = -group.allreduce_max(why.empty() ? -group.size() : -group.rank());
  Bytes text;
  if (group.rank() == first) text.assign(reinterpret_cast<const std::byte*>(why.data()),
                                         reinterpret_cast<const std::byte*>(why.data()) + why.size());
  group.bcast(text, first);
  throw NumericalError(std::string(reinterpret_cast<const char*>(text.data()), text.size()));
}

}  // namespace fe2
