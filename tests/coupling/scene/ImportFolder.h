#pragma once
// A fresh folder per test for scenes that import particle files: file() writes one there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace tmdem::coupling::test {

class ImportFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    // Suite and test name: two suites may have a test of the same name.
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("tmdem_import_" + std::to_string(::getpid()) + "_" + test->test_suite_name() + "_" +
            test->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string file(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  std::filesystem::path dir_;
};

}  // namespace tmdem::coupling::test
