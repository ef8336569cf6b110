// The study file a record's command names (app/record_cli.hpp): relative to where `record` runs when
// the file lies under it, so a record made in any clone names the repository's own path.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "app/record_cli.hpp"
#include "tests/temp_dir.hpp"
#include "util/atomic_file.hpp"

namespace fs = std::filesystem;
using hydrojump::app::study_command_argument;

namespace {

fs::path resolved_case(const fs::path& dir, const std::string& first_line) {
  const fs::path file = dir / "case.toml";
  hydrojump::util::write_file_atomically(file, first_line + "\n[study]\nname = \"x\"\n");
  return file;
}

}  // namespace

TEST_CASE("Record command: the study file under the working directory is named relative to it", "[study][record]") {
  const hydrojump::testing::TempDir tmp("record_cli");
  const fs::path& dir = tmp.path();
  const auto from = [&](const std::string& spec) {
    return resolved_case(dir, "# Resolved by hydrojump from " + spec + ": case \"C\" at resolution \"quick\"");
  };
  CHECK(study_command_argument(from("/work/clone/cases/ead2002.toml"), "/work/clone") == "cases/ead2002.toml");
  CHECK(study_command_argument(from("/work/clone/./cases/ead2002.toml"), "/work/clone/") == "cases/ead2002.toml");
  // Outside the working directory, or given relative: as the study was given it.
  CHECK(study_command_argument(from("/data/specs/basin.toml"), "/work/clone") == "/data/specs/basin.toml");
  CHECK(study_command_argument(from("/work/clone2/cases/a.toml"), "/work/clone") == "/work/clone2/cases/a.toml");
  CHECK(study_command_argument(from("cases/ead2002.toml"), "/work/clone") == "cases/ead2002.toml");
  CHECK(study_command_argument(from("<embedded default study>"), "/work/clone") == "default");
  // A file without the resolved header.
  CHECK(study_command_argument(resolved_case(dir, "# something else"), "/work/clone") == "SPEC");
}
