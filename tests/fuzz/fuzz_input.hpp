// What every fuzz target shares: the input as a file (the readers under test take paths), and the rule
// that a reader ends in a valid result or in its documented error, never in anything else.
//
// Each target is a libFuzzer entry point (LLVMFuzzerTestOneInput). An exception other than the
// documented one escapes and aborts the run, as a crash, a hang (-timeout) or an unbounded allocation
// (-rss_limit_mb, -malloc_limit_mb) does: libFuzzer then writes the input that did it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <unistd.h>

namespace hydrojump::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// The input written to a file of this process named `name` (replaced on every call).
inline std::filesystem::path as_file(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("hydrojump-fuzz-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / name;
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  return file;
}

}  // namespace hydrojump::fuzz
