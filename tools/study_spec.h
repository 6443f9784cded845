#pragma once
// A study file (`fe2heart study STUDY.json`): a base run spec, the variants to run
// from it (each a set of JSON-pointer edits), the reference to compare them with, the
// quantities compared, and how each variant is launched. See docs/study.md.
//
//   {"base": "farm_beam.json",                     // relative to the study file
//    "variants": [{"name": "fine", "set": {"/time/steps": 16}}, ...],
//    "one_at_a_time": {"/time/steps": [4, 8]},      // one variant per value
//    "reference": "finest" | "<variant name>" | {"run": "DIR of an earlier run"},
//    "quantities": ["displacement", "cavity_volumes", "/circulation/cavities/lv/EF"],
//    "np": 1, "mpirun": ["mpirun", "-n", "{np}"]}
//
// Every key is declared once, in study_spec_schema(); every problem is an InputError
// naming the study file, the key, the value and what was expected; nothing here writes
// files.
#include "common/spec/SpecNode.h"

#include <string>
#include <vector>

namespace fe2 {

struct StudyVariant {
  std::string name;  ///< also its folder: DIR/variants/<name>
  json set;          ///< {"/pointer": value, ...}: what differs from the base
  json spec;         ///< the base spec with `set` applied, file paths made absolute
};

struct StudySpec {
  std::string file;  ///< the study file, as given
  std::string title;
  std::string base;  ///< the base spec's path (resolved against the study file)
  json base_spec;
  std::vector<StudyVariant> variants;
  enum class Reference { finest, variant, run } reference = Reference::finest;
  std::string reference_variant;  ///< Reference::variant
  std::string reference_run;      ///< Reference::run: a run folder (resolved)
  std::vector<std::string> quantities;
  int np = 1;
  /// The launcher as given ("{np}" stands for the ranks); empty: not given, so
  /// `mpirun -n NP` for NP > 1 and the binary alone for NP = 1.
  std::vector<std::string> mpirun;
};

/// The quantities a study can compare by name (others are JSON pointers into summary.json).
const std::vector<std::string>& study_quantity_names();

/// Whether `j` looks like a study file (a "base" and variants) rather than a spec.
bool is_study_spec(const json& j);

/// Reads and checks a study file by study_spec_schema() and builds every variant's spec
/// (not yet validated as a run spec: cmd_study does that, naming the variant); `doc` as
/// in SpecNode.
StudySpec read_study_spec(const std::string& file, SpecDoc* doc = nullptr);

/// The schema of study files (`fe2heart spec-schema --study`, spec-doc).
const SchemaNode& study_spec_schema();

}  // namespace fe2
