#pragma once
// A fresh folder per test process and name, removed afterwards, with the result file's path.
#include <unistd.h>

#include <filesystem>
#include <string>

namespace tmdem::coupling::test {

struct ScratchResultFile {
  std::filesystem::path dir;
  std::string path;
  explicit ScratchResultFile(const std::string& name) {
    dir = std::filesystem::temp_directory_path() /
          ("tmdem-output-" + name + "-" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    path = (dir / "bed.h5").string();
  }
  ~ScratchResultFile() { std::filesystem::remove_all(dir); }
};

}  // namespace tmdem::coupling::test
