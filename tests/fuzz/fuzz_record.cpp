// The validation record reader (compare/record.hpp, parse_record) on arbitrary text: a record or a
// RecordError naming the file and key.
#include "compare/record.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)hydrojump::compare::parse_record(std::string(hydrojump::fuzz::as_text(data, size)), "sph-quick.toml");
  } catch (const hydrojump::compare::RecordError&) {
  }
  return 0;
}
