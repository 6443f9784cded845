// Reading a spec file (read_json_file): every failure is an InputError naming the file
// and, where there is one, the key; never a crash.
#include "common/error.h"
#include "common/spec/SpecNode.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

class JsonFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("fe2_json_{}_{}",
                       ::testing::UnitTest::GetInstance()->current_test_info()->name(), getpid());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  static std::string error_of(const std::string& file) {
    try {
      read_json_file(file);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(JsonFile, NestingDeeperThanTheLimitIsRefusedWithoutCrashing) {
  const int depth = 70000;
  const std::string file = write("deep.json", std::string(depth, '[') + std::string(depth, ']'));
  const std::string msg = error_of(file);
  EXPECT_NE(msg.find("deep.json': nesting depth 65 at /0/0/0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("exceeds the limit of 64"), std::string::npos) << msg;
  // Exactly at the limit is fine.
  const std::string ok = write("ok.json", std::string(64, '[') + std::string(64, ']'));
  EXPECT_NO_THROW(read_json_file(ok));
}

TEST_F(JsonFile, DuplicateKeyIsNamedWithItsPath) {
  const std::string file =
      write("dup.json", R"({"a": {"b": [1, {"c": 1, "d": 2, "c": 3}]}, "e": 0})");
  EXPECT_EQ(error_of(file), "spec file '" + file +
                                "': duplicate key 'c' at /a/b/1/c, expected each key once per object");
  // Equal keys in different objects are not duplicates.
  EXPECT_NO_THROW(read_json_file(write("same.json", R"({"a": {"c": 1}, "b": {"c": 1}, "c": [{"c": 2}]})")));
}

TEST_F(JsonFile, OverflowingNumberNamesFileAndKey) {
  const std::string file = write("big.json", R"({"time": {"steps": 3, "t_end": 1e999}})");
  const std::string msg = error_of(file);
  EXPECT_NE(msg.find("spec file '" + file + "' at /time/t_end: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("number overflow parsing '1e999'"), std::string::npos) << msg;
}

TEST_F(JsonFile, DirectoryAndMissingFileAreNamed) {
  EXPECT_EQ(error_of(dir_.string()),
            "spec file '" + dir_.string() + "' is a directory, expected a JSON file");
  const std::string missing = (dir_ / "missing.json").string();
  EXPECT_EQ(error_of(missing), "cannot open spec file '" + missing + "' (No such file or directory)");
}

}  // namespace
}  // namespace fe2
