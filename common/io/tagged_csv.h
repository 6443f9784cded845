#pragma once
// A CSV of tagged rows, "tag,v1,...,vk" (fibre files, activation files): blank lines and
// lines starting with '#' are skipped, and so is a first line that does not start with a
// number (a header). Every other line must hold exactly 1 + k finite numbers, the tag a
// positive integer; anything else is an InputError naming the file, the line and what
// was found.
#include <string>
#include <vector>

namespace fe2 {

struct TaggedRow {
  long long tag = 0;
  int line = 0;                ///< 1-based line in the file
  std::vector<double> values;  ///< the k numbers after the tag
};

/// `what` names the file in messages ("fibre file"), `form` spells a line
/// ("tag,fx,fy,fz,sx,sy,sz"), `note` says what the values are ("tag a positive integer").
std::vector<TaggedRow> read_tagged_csv(const std::string& file, int values, const std::string& what,
                                       const std::string& form, const std::string& note);

}  // namespace fe2
