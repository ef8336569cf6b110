// The machine's available memory and the refusal of a run that needs more (util/system_memory.hpp).
#include <catch2/catch.hpp>

#include "util/system_memory.hpp"

namespace util = hydrojump::util;

TEST_CASE("MemAvailable is read from a meminfo text", "[util][memory]") {
  CHECK(util::parse_mem_available("MemTotal:       24000000 kB\nMemFree:  100 kB\nMemAvailable:   22000000 kB\n") ==
        std::uint64_t{22000000} * 1024);
  CHECK_FALSE(util::parse_mem_available("MemTotal: 24000000 kB\n").has_value());
  CHECK_FALSE(util::parse_mem_available("MemAvailable: lots\n").has_value());
  CHECK_FALSE(util::parse_mem_available("MemAvailable: 12 MB\n").has_value());
  CHECK_FALSE(util::parse_mem_available("").has_value());
  // This machine (Linux) has one, and it is positive.
  const auto here = util::available_memory_bytes();
  REQUIRE(here.has_value());
  CHECK(*here > 0);
}

TEST_CASE("HYDROJUMP_MEMORY_LIMIT_MB caps the available memory, and a bad value is refused by name", "[util][memory]") {
  CHECK_FALSE(util::memory_limit_bytes(nullptr).has_value());
  CHECK(util::memory_limit_bytes("8000") == std::uint64_t{8'000'000'000});
  CHECK(util::memory_limit_bytes("0.5") == std::uint64_t{500'000});
  for (const char* bad : {"", "abc", "0", "-5", "nan", "inf", "12 MB", "1e13"})
    CHECK_THROWS_WITH(util::memory_limit_bytes(bad), Catch::Contains("HYDROJUMP_MEMORY_LIMIT_MB = \"" + std::string(bad) + "\"") &&
                                                         Catch::Contains("positive number of MB"));
}

TEST_CASE("a run needing more memory than is available is refused with the figures", "[util][memory]") {
  CHECK_NOTHROW(util::check_memory_need("run", 1.0e9, "basis", "way out", std::uint64_t{2'000'000'000}));
  CHECK_NOTHROW(util::check_memory_need("run", 1.0e12, "basis", "way out", std::nullopt));  // unknown: not refused
  CHECK_THROWS_AS(util::check_memory_need("run", 3.0e9, "basis", "way out", std::uint64_t{2'000'000'000}),
                  util::MemoryShortage);
  CHECK_THROWS_WITH(util::check_memory_need("hydrojump sph: case A", 2'500'000'001.0,
                                            "0.52 kB a particle x 4,800,000 particles + 25 MB", "use a coarser resolution",
                                            std::uint64_t{2'000'000'000}),
                    "hydrojump sph: case A needs about 2501 MB (0.52 kB a particle x 4,800,000 particles + 25 MB) but this "
                    "machine has 2000 MB available (MemAvailable in /proc/meminfo): use a coarser resolution");
}
