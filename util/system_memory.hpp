// The memory this machine can give a new run: MemAvailable of /proc/meminfo (the kernel's estimate
// of what can be allocated without swapping, page cache included), or less where the environment
// variable HYDROJUMP_MEMORY_LIMIT_MB caps it (a machine shared with other work), and the refusal of a
// run whose estimated need exceeds it.
//
//   | function                | gives                                                          |
//   |-------------------------|----------------------------------------------------------------|
//   | available_memory_bytes  | MemAvailable in bytes (capped by HYDROJUMP_MEMORY_LIMIT_MB),   |
//   |                         | or nothing where neither is known                              |
//   | memory_limit_bytes      | the cap a HYDROJUMP_MEMORY_LIMIT_MB value gives; throws        |
//   |                         | std::invalid_argument for one that is not a positive number    |
//   | parse_mem_available     | the same from the text of a meminfo file (tests)               |
//   | check_memory_need       | throws MemoryShortage naming the need, its basis and what is   |
//   |                         | available, when the need exceeds it; nothing when unknown      |
// Example:
//   util::check_memory_need("hydrojump sph: case A at dx = 0.0025 m", need_bytes,
//                           "0.52 kB a particle x 332,000 particles + 25 MB", "use a coarser resolution");
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace hydrojump::util {

class MemoryShortage : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr const char* memory_limit_variable = "HYDROJUMP_MEMORY_LIMIT_MB";

std::optional<std::uint64_t> parse_mem_available(std::string_view meminfo_text);
std::optional<std::uint64_t> memory_limit_bytes(const char* value);
std::optional<std::uint64_t> available_memory_bytes();

// Throws MemoryShortage when `need_bytes` > `available` (default: this machine's MemAvailable): the
// message names `what`, the need in MB with its `basis`, the available MB and `way_out`.
void check_memory_need(const std::string& what, double need_bytes, const std::string& basis, const std::string& way_out,
                       std::optional<std::uint64_t> available = available_memory_bytes());

}  // namespace hydrojump::util
