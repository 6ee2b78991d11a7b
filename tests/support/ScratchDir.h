#pragma once
// A fresh empty folder for one test, removed when the test passes and kept (its path printed)
// when it fails, so that a failure can be looked into and passing runs leave nothing in the
// temporary directory.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>
#include <vector>

namespace tmdem::test {

// Removes the folders made during a test once it has passed. Registered with gtest's listeners
// the first time a folder is made (before the test ends, so its own end is seen).
class ScratchCleaner : public ::testing::EmptyTestEventListener {
 public:
  static ScratchCleaner& instance() {
    static ScratchCleaner* cleaner = [] {
      auto* c = new ScratchCleaner;  // owned by gtest's listener list
      ::testing::UnitTest::GetInstance()->listeners().Append(c);
      return c;
    }();
    return *cleaner;
  }
  void add(const std::filesystem::path& dir) { dirs_.push_back(dir); }
  void OnTestEnd(const ::testing::TestInfo& info) override {
    for (const auto& dir : dirs_) {
      if (info.result()->Passed()) {
        std::error_code ignored;
        std::filesystem::remove_all(dir, ignored);
      } else {
        std::cerr << "kept for the failed test: " << dir.string() << "\n";
      }
    }
    dirs_.clear();
  }

 private:
  std::vector<std::filesystem::path> dirs_;
};

// temp/<prefix><name>_<pid>, fresh and empty.
inline std::string scratch_folder(const std::string& prefix, const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (prefix + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ScratchCleaner::instance().add(dir);
  return dir.string();
}

}  // namespace tmdem::test
