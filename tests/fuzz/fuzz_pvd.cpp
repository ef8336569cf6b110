// The ParaView collection reader (compare/readers.hpp, read_pvd) on arbitrary bytes: the data sets or
// a std::runtime_error naming the file.
#include <stdexcept>

#include "compare/readers.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)hydrojump::compare::read_pvd(hydrojump::fuzz::as_file(data, size, "particles.pvd"));
  } catch (const std::runtime_error&) {
  }
  return 0;
}
