// The SPH checkpoint reader (sph/checkpoint.hpp) on arbitrary bytes: a checkpoint or a
// std::runtime_error naming the file (wrong magic, truncated, bad checksum, values no run writes).
#include <stdexcept>

#include "sph/checkpoint.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)hydrojump::sph::read_checkpoint(hydrojump::fuzz::as_file(data, size, "checkpoint.bin"));
  } catch (const std::runtime_error&) {
  }
  return 0;
}
