// Which files make a folder "an earlier run", and what --overwrite
// removes (only fe2heart's files, never the user's).
#include "coordinator/output/RunOutput.h"

#include "common/error.h"
#include "tools/output_folder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

class Scratch {
 public:
  Scratch() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / fmt::format("fe2_{}_{}", info->name(), getpid());
    fs::remove_all(path_);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string str() const { return path_.string(); }
  void touch(const std::string& name) const {
    fs::create_directories(path_);
    std::ofstream(path_ / name) << "x\n";
  }
  bool has(const std::string& name) const { return fs::exists(path_ / name); }

 private:
  fs::path path_;
};

std::string refusal(const std::string& dir, bool overwrite) {
  try {
    cli::refuse_earlier_output(dir, "an fe2heart run", run_output_files(dir), overwrite);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RunOutput, RunFilesAreRecognizedByName) {
  for (const char* own : {"summary.json", "spec.json", "fe2heart.log", "displacement.pvd",
                          "displacement_00000.vtu", "displacement_12345.vtu", "trace_units.jsonl",
                          "trace_iterations.jsonl", "summary.json.tmp", "gantt.png", "imbalance.png",
                          "pv_curve.png", "pv_loop.png", "pv_time.png", "circulation.csv",
                          "units/unit_3.pvd", "units/unit_12_00004.vtu", "units/unit_12_00004.vtu.tmp"})
    EXPECT_TRUE(is_run_output_file(own)) << own;
  for (const char* other : {"notes.txt", "my_summary.json", "displacement_x.vtu", "mesh.vtu",
                            "spec.json.bak", "fe2heart.log.1", "heart.msh", "plot.png",
                            "unit_3.pvd", "units/unit_x.vtu", "units/notes.txt", "other/unit_3.pvd"})
    EXPECT_FALSE(is_run_output_file(other)) << other;
}

TEST(RunOutput, MissingEmptyOrForeignFolderIsAccepted) {
  const Scratch dir;
  EXPECT_EQ(refusal(dir.str(), false), "");  // does not exist
  fs::create_directories(dir.str());
  EXPECT_EQ(refusal(dir.str(), false), "");  // empty
  dir.touch("notes.txt");
  EXPECT_EQ(refusal(dir.str(), false), "");  // only the user's files
}

TEST(RunOutput, EarlierRunIsRefusedWithoutOverwriteAndNothingIsRemoved) {
  const Scratch dir;
  dir.touch("notes.txt");
  dir.touch("displacement_00099.vtu");
  const std::string msg = refusal(dir.str(), false);
  EXPECT_NE(msg.find("--out '" + dir.str() + "' already holds an fe2heart run (1 file: "
                     "displacement_00099.vtu); use --overwrite to replace it, or another --out"),
            std::string::npos)
      << msg;
  EXPECT_EQ(refusal(dir.str(), true), "");
  EXPECT_TRUE(dir.has("displacement_00099.vtu"));  // the check itself removes nothing
}

// output.units writes into units/: an earlier run's unit files count as run files there.
TEST(RunOutput, EarlierUnitFilesAreFoundInTheUnitsFolder) {
  const Scratch dir;
  fs::create_directories(dir.str() + "/units");
  dir.touch("units/notes.txt");
  EXPECT_EQ(refusal(dir.str(), false), "");
  dir.touch("units/unit_7_00003.vtu");
  EXPECT_EQ(run_output_files(dir.str()), std::vector<std::string>{"units/unit_7_00003.vtu"});
  EXPECT_NE(refusal(dir.str(), false).find("(1 file: units/unit_7_00003.vtu)"), std::string::npos);
}

TEST(RunOutput, AFileInsteadOfAFolderIsRefused) {
  const Scratch dir;
  dir.touch("summary.json");
  const std::string file = dir.str() + "/summary.json";
  EXPECT_NE(refusal(file, true).find("--out '" + file + "' exists and is not a folder"),
            std::string::npos);
}

}  // namespace
}  // namespace fe2
