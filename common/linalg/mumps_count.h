#pragma once
// MUMPS stores the INFOG entries that count items (INFOG(29): entries in the factor,
// INFOG(9), INFOG(10), ...) in millions when they are negative (MUMPS 5.5 user's guide,
// §6.1): one reading for every MUMPS caller, macro and units alike.

namespace fe2 {

inline double mumps_count(int infog_entry) {
  return infog_entry < 0 ? -1e6 * infog_entry : static_cast<double>(infog_entry);
}

}  // namespace fe2
