// The checkpoint file format (common/io/checkpoint_file.h): what is written is read back
// exactly; a new checkpoint replaces the old one only once it is whole; a damaged file of
// any length is refused with an InputError, never a crash.
#include "common/io/checkpoint_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

Bytes bytes_of(std::initializer_list<int> v) {
  Bytes b;
  for (int x : v) b.push_back(static_cast<std::byte>(x));
  return b;
}

CheckpointHeader header(int steps) {
  CheckpointHeader h;
  h.protocol = 42;
  h.spec_hash = 0x1234;
  h.spec_text = R"({"title": "t"})";
  h.steps = steps;
  h.time = 0.25 * steps;
  h.ranks = 3;
  h.coordinators = 2;
  h.macro = bytes_of({1, 2, 3});
  h.run = bytes_of({9});
  return h;
}

/// Writes a checkpoint of three units, stored out of order, at `path`.
void write_three(const std::string& path, int steps) {
  CheckpointWriter w(path, header(steps), 3);
  w.add_unit(2, bytes_of({20, 21}));
  w.add_unit(0, bytes_of({}));
  w.add_unit(1, bytes_of({10, 11, 12, steps}));
  w.finish();
}

class CheckpointFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("fe2_ckpt_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path() const { return checkpoint_path(dir_.string()); }
  fs::path dir_;
};

TEST_F(CheckpointFileTest, ReadsBackWhatWasWritten) {
  write_three(path(), 4);
  const CheckpointFile f(path(), 42);
  const CheckpointHeader& h = f.header();
  EXPECT_EQ(h.format, kCheckpointFormat);
  EXPECT_EQ(h.protocol, 42);
  EXPECT_EQ(h.spec_hash, 0x1234u);
  EXPECT_EQ(h.spec_text, R"({"title": "t"})");
  EXPECT_EQ(h.steps, 4);
  EXPECT_EQ(h.time, 1.0);
  EXPECT_EQ(h.ranks, 3);
  EXPECT_EQ(h.coordinators, 2);
  EXPECT_EQ(h.macro, bytes_of({1, 2, 3}));
  EXPECT_EQ(h.run, bytes_of({9}));
  EXPECT_EQ(f.units(), (std::vector<int>{2, 0, 1}));
  EXPECT_EQ(f.unit_state(0), bytes_of({}));
  EXPECT_EQ(f.unit_state(1), bytes_of({10, 11, 12, 4}));
  EXPECT_EQ(f.unit_state(2), bytes_of({20, 21}));
  EXPECT_THROW(f.unit_state(3), Error);
}

TEST_F(CheckpointFileTest, NewOneReplacesOldOnlyWhenWhole) {
  write_three(path(), 1);
  write_three(path(), 2);
  EXPECT_EQ(CheckpointFile(path(), 42).header().steps, 2);
  EXPECT_EQ(CheckpointFile(previous_checkpoint_path(dir_.string()), 42).header().steps, 1);
  {
    // Killed half-way (no finish): the whole ones stay, and no partial file is left.
    CheckpointWriter w(path(), header(3), 3);
    w.add_unit(0, bytes_of({1}));
    EXPECT_TRUE(fs::exists(path() + ".partial"));
  }
  EXPECT_FALSE(fs::exists(path() + ".partial"));
  EXPECT_EQ(CheckpointFile(path(), 42).header().steps, 2);
  // Announcing three states and writing two is an error, not a short checkpoint.
  CheckpointWriter w(path(), header(3), 3);
  w.add_unit(0, bytes_of({1}));
  w.add_unit(1, bytes_of({1}));
  EXPECT_THROW(w.finish(), Error);
}

TEST_F(CheckpointFileTest, FolderFallsBackToPreviousAndSaysWhy) {
  write_three(path(), 1);
  write_three(path(), 2);
  {
    std::fstream f(path(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(40);
    f.put('\x7f');
  }
  std::vector<std::string> refused;
  const CheckpointFile f = open_checkpoint(dir_.string(), 42, &refused);
  EXPECT_EQ(f.header().steps, 1);
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_NE(refused[0].find("checksum mismatch"), std::string::npos) << refused[0];
  EXPECT_NE(refused[0].find("after step 1"), std::string::npos) << refused[0];
  // Both damaged: refused, naming each.
  fs::copy_file(path(), previous_checkpoint_path(dir_.string()), fs::copy_options::overwrite_existing);
  try {
    open_checkpoint(dir_.string(), 42);
    FAIL() << "a folder of damaged checkpoints was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no usable checkpoint"), std::string::npos) << e.what();
  }
}

TEST_F(CheckpointFileTest, OtherVersionsAreRefusedNamingBoth) {
  write_three(path(), 1);
  try {
    CheckpointFile(path(), 43);
    FAIL() << "another protocol version was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("protocol version 42; this fe2heart is version 43"), std::string::npos)
        << e.what();
  }
}

// Every prefix of a valid file, and every single-byte change in its framing, is refused
// with an InputError: no crash, no huge allocation, no acceptance.
TEST_F(CheckpointFileTest, EveryTruncationAndByteFlipIsRefused) {
  write_three(path(), 1);
  std::ifstream in(path(), std::ios::binary);
  const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string damaged = (dir_ / "damaged").string();
  auto refused = [&](const std::string& content) {
    std::ofstream(damaged, std::ios::binary | std::ios::trunc) << content;
    try {
      CheckpointFile f(damaged, 42);
      return false;
    } catch (const InputError&) {
      return true;
    }
  };
  for (size_t n = 0; n < whole.size(); ++n) EXPECT_TRUE(refused(whole.substr(0, n))) << "prefix of " << n;
  for (size_t k = 0; k < whole.size(); ++k) {
    std::string s = whole;
    s[k] = static_cast<char>(s[k] ^ 0x01);
    EXPECT_TRUE(refused(s)) << "byte " << k << " flipped";
  }
  EXPECT_FALSE(refused(whole));
}

}  // namespace
}  // namespace fe2
