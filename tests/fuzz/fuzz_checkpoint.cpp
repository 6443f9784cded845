// The checkpoint reader (common/io/checkpoint_file.h) on arbitrary bytes: a checkpoint
// whose framing, sizes and unit index hold, or an InputError (truncated, corrupted, other
// version). A malicious length must not make it allocate more than the file holds.
// Each input is read twice: as it is (the checksum refuses nearly every mutation), and
// with a correct checksum appended, so that the parser behind the checksum is fuzzed too.
#include "common/hash.h"
#include "common/io/checkpoint_file.h"
#include "tests/fuzz/fuzz_support.h"

#include <cstring>
#include <vector>

using namespace fe2;

namespace {
void read_checkpoint(const uint8_t* data, size_t size) {
  const std::string& file = fuzz::as_file(data, size, ".bin");
  fuzz::expect_only<InputError>([&] {
    const CheckpointFile f(file, 1);
    uint64_t held = f.header().spec_text.size() + f.header().macro.size() + f.header().run.size();
    for (int unit : f.units()) held += f.unit_state(unit).size();
    fuzz::require(held <= size, "no section larger than the file");
    fuzz::require(f.units().size() <= size, "no more units than bytes");
  });
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  read_checkpoint(data, size);
  Fnv1a hash;
  hash.add(data, size);
  const uint64_t checksum = hash.value();
  std::vector<uint8_t> sealed(data, data + size);
  sealed.resize(size + sizeof checksum);
  std::memcpy(sealed.data() + size, &checksum, sizeof checksum);
  read_checkpoint(sealed.data(), sealed.size());
  return 0;
}
