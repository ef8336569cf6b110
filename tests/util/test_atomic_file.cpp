// Atomic writes: the target is either the old or the new content, never partial.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "util/atomic_file.hpp"

#include <unistd.h>
#include "util/fingerprint.hpp"
#include "tests/temp_dir.hpp"

using namespace hydrojump::util;
namespace util = hydrojump::util;

namespace {
std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST_CASE("Atomic writes replace whole files and leave no temporaries", "[cases][io]") {
  const hydrojump::testing::TempDir tmp("atomic");
  const auto dir = tmp.path() / "sub";  // not there yet: the write creates it
  const auto file = dir / "out.txt";
  util::write_file_atomically(file, "first");
  CHECK(read(file) == "first");
  // A producer that fails leaves the old content in place.
  CHECK_THROWS_AS(util::write_file_atomically(file, [](std::ostream& out) {
                    out << "half";
                    throw std::runtime_error("interrupted");
                  }),
                  std::runtime_error);
  CHECK(read(file) == "first");
  util::write_file_atomically(file, "second");
  CHECK(read(file) == "second");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  CHECK(entries == 1);
}

TEST_CASE("Temporaries of writers that no longer run are removed and a live writer's and other files are kept",
          "[cases][io]") {
  const hydrojump::testing::TempDir tmp("orphans");
  const auto dir = tmp.path();
  // A pid no process has: the kernel's pid_max is at most 2^22.
  const std::string dead = std::to_string((1 << 22) + 12345);
  const std::string live = std::to_string(::getpid());
  const std::vector<std::string> names = {".checkpoint.bin.tmp." + dead + ".0", ".run_log.csv.tmp." + dead + ".17",
                                         ".particles.pvd.tmp." + live + ".3", "checkpoint.bin", ".hydrojump.lock",
                                         ".notes.tmp.abc.1", "data.tmp.1.2", ".x.tmp." + dead};
  for (const auto& name : names)
    std::ofstream(dir / name) << "x";
  std::filesystem::create_directories(dir / "sub");
  std::ofstream(dir / "sub" / (".deep.tmp." + dead + ".0")) << "x";
  CHECK(util::remove_orphaned_temporaries(dir) == 2);
  CHECK_FALSE(std::filesystem::exists(dir / (".checkpoint.bin.tmp." + dead + ".0")));
  CHECK_FALSE(std::filesystem::exists(dir / (".run_log.csv.tmp." + dead + ".17")));
  const std::vector<std::string> kept = {".particles.pvd.tmp." + live + ".3", "checkpoint.bin", ".hydrojump.lock",
                                        ".notes.tmp.abc.1", "data.tmp.1.2", ".x.tmp." + dead,
                                        "sub/.deep.tmp." + dead + ".0"};
  for (const auto& name : kept)
    CHECK(std::filesystem::exists(dir / name));
  CHECK(util::remove_orphaned_temporaries(dir / "missing") == 0);
}

TEST_CASE("fingerprint is FNV-1a 64 (published test vectors)", "[cases][fingerprint]") {
  // Fowler/Noll/Vo reference vectors for FNV-1a, 64 bit.
  CHECK(hydrojump::util::fingerprint("") == "cbf29ce484222325");
  CHECK(hydrojump::util::fingerprint("a") == "af63dc4c8601ec8c");
  CHECK(hydrojump::util::fingerprint("foobar") == "85944171f73967e8");
}
