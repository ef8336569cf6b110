#include "sph/cli.hpp"

#include "cases/spec_reader.hpp"

namespace hydrojump::sph {

void register_commands(CLI::App& /*app*/) {}

void write_sph_input(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                     const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  cases::write_resolved_case(study, c, resolution, dir / "case.toml");
}

}  // namespace hydrojump::sph
