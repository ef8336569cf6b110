// Atomic writes: the target is either the old or the new content, never partial.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cases/atomic_file.hpp"

using namespace hydrojump::cases;

namespace {
std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST_CASE("Atomic writes replace whole files and leave no temporaries", "[cases][io]") {
  const auto dir = std::filesystem::temp_directory_path() / "hydrojump_test_atomic" / "sub";
  std::filesystem::remove_all(dir.parent_path());
  const auto file = dir / "out.txt";
  write_file_atomically(file, "first");
  CHECK(read(file) == "first");
  // A producer that fails leaves the old content in place.
  CHECK_THROWS_AS(write_file_atomically(file, [](std::ostream& out) {
                    out << "half";
                    throw std::runtime_error("interrupted");
                  }),
                  std::runtime_error);
  CHECK(read(file) == "first");
  write_file_atomically(file, "second");
  CHECK(read(file) == "second");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  CHECK(entries == 1);
  std::filesystem::remove_all(dir.parent_path());
}
