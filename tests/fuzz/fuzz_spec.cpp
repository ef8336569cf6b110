// The study spec reader (cases/spec_reader.hpp) on arbitrary text: a Study or a SpecError. When it
// reads, every case's resolved case.toml (what `generate` writes) must read back: a SpecError there is
// a bug, and aborts.
#include <cstdlib>
#include <iostream>

#include "cases/spec_reader.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hydrojump::cases;
  Study study;
  try {
    study = parse_study(hydrojump::fuzz::as_text(data, size), "fuzz.toml", std::filesystem::temp_directory_path());
  } catch (const SpecError&) {
    return 0;
  }
  for (const auto& c : study.cases)
    for (const auto& [name, level] : c.resolutions) {
      const std::string resolved = resolved_case_text(study, c, name);
      try {
        (void)parse_study(resolved, "resolved.toml", std::filesystem::temp_directory_path());
      } catch (const SpecError& e) {
        std::cerr << "a resolved case does not read back: " << e.what() << "\n" << resolved << "\n";
        std::abort();
      }
    }
  return 0;
}
