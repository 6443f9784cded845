// A .pvd names its VTU files relative to itself, whatever the working
// directory of the writer (ParaView resolves them against the .pvd's folder).
#include "common/io/vtu_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A scratch folder that is also the working directory for the test's lifetime.
class InScratchDir {
 public:
  InScratchDir() : old_(fs::current_path()) {
    path_ = fs::temp_directory_path() / ("fe2_pvd_paths_" + std::to_string(getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_ / "a" / "b");
    fs::current_path(path_);
  }
  ~InScratchDir() {
    std::error_code ec;
    fs::current_path(old_, ec);
    fs::remove_all(path_, ec);
  }

 private:
  fs::path old_, path_;
};

TEST(PvdWriter, FilesAreRelativeToThePvdNotTheWorkingDirectory) {
  const InScratchDir cwd;
  PvdWriter pvd("a/b/displacement.pvd");
  pvd.add(0.0, "a/b/displacement_00000.vtu");
  pvd.add(0.5, "a/./b/../b/displacement_00001.vtu");  // not normalized
  pvd.add(1.0, fs::absolute("a/b/sub/displacement_00002.vtu").string());
  const std::string text = slurp("a/b/displacement.pvd");
  EXPECT_NE(text.find("timestep=\"0\" group=\"\" part=\"0\" file=\"displacement_00000.vtu\""), std::string::npos) << text;
  EXPECT_NE(text.find("timestep=\"0.5\" group=\"\" part=\"0\" file=\"displacement_00001.vtu\""), std::string::npos) << text;
  EXPECT_NE(text.find("timestep=\"1\" group=\"\" part=\"0\" file=\"sub/displacement_00002.vtu\""), std::string::npos) << text;
  EXPECT_EQ(text.find(".."), std::string::npos) << text;
}

}  // namespace
}  // namespace fe2
