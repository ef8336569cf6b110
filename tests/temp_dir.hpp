// A fresh temporary directory per test, removed at the end of the test: named after the tag, the process
// and a counter, so tests running at once (two builds' ctest, ctest -j) never share one.
//
// Example:
//   const hydrojump::testing::TempDir tmp("atomic");
//   write_file_atomically(tmp.path() / "out.txt", "text");
#pragma once

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace hydrojump::testing {

class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("hydrojump-test-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  // Kept for inspection when HYDROJUMP_KEEP_TEST_DIRS is set.
  ~TempDir() {
    if (std::getenv("HYDROJUMP_KEEP_TEST_DIRS")) return;
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace hydrojump::testing
