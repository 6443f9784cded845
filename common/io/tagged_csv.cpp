#include "common/io/tagged_csv.h"

#include "common/error.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace fe2 {

std::vector<TaggedRow> read_tagged_csv(const std::string& file, int values, const std::string& what,
                                       const std::string& form, const std::string& note) {
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("cannot open {} '{}' ({}), expected a CSV file of lines {}", what, file,
                                 std::strerror(errno), form));
  std::vector<TaggedRow> out;
  std::string line;
  bool first = true;  // the first line that is not blank or a comment may be a header
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    std::vector<double> v;
    std::vector<bool> ok;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) {
      const auto a = field.find_first_not_of(" \t"), b = field.find_last_not_of(" \t");
      double x = 0;
      const char* p = field.data() + (a == std::string::npos ? 0 : a);
      const char* q = field.data() + (a == std::string::npos ? 0 : b + 1);
      const auto [end, ec] = std::from_chars(p, q, x);
      ok.push_back(p != q && ec == std::errc() && end == q && std::isfinite(x));
      v.push_back(x);
    }
    const bool header = first && !ok.empty() && !ok[0];
    first = false;
    if (header) continue;
    const bool numbers = std::find(ok.begin(), ok.end(), false) == ok.end();
    if (!numbers || v.size() != static_cast<size_t>(values) + 1 || v[0] != std::floor(v[0]) || v[0] < 1 ||
        v[0] > 9e15)
      throw InputError(fmt::format("{} '{}' line {}: got '{}', expected {} comma-separated numbers {} ({})", what,
                                   file, n, line.substr(0, 80), values + 1, form, note));
    out.push_back({static_cast<long long>(v[0]), n, std::vector<double>(v.begin() + 1, v.end())});
  }
  return out;
}

}  // namespace fe2
