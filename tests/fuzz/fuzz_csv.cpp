// The tagged CSV reader (common/io/tagged_csv.h) of fibre files (6 values per row) and
// activation files (1 value) on arbitrary text: rows or an InputError naming the line.
#include "common/io/tagged_csv.h"
#include "tests/fuzz/fuzz_support.h"

#include <cmath>

using namespace fe2;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& file = fuzz::as_file(data, size, ".csv");
  for (int values : {1, 6})
    fuzz::expect_only<InputError>([&] {
      for (const TaggedRow& r : read_tagged_csv(file, values, "fuzz file", "tag,v...", "fuzz")) {
        fuzz::require(r.tag >= 1 && r.line >= 1, "a positive tag and line");
        fuzz::require(r.values.size() == static_cast<size_t>(values), "the row's value count");
        for (double v : r.values) fuzz::require(std::isfinite(v), "finite values");
      }
    });
  return 0;
}
