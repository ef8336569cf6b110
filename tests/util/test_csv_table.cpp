// The project's small CSV tables (util/csv_table.hpp): cells, numbers, files.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "util/csv_table.hpp"
#include "tests/temp_dir.hpp"

namespace util = hydrojump::util;
namespace fs = std::filesystem;

TEST_CASE("CSV lines split into their cells, empty ones included", "[cases][csv]") {
  using V = std::vector<std::string>;
  CHECK(util::split_csv_line("t_s,toe_x_m,q") == V{"t_s", "toe_x_m", "q"});
  CHECK(util::split_csv_line("1,,3") == V{"1", "", "3"});
  CHECK(util::split_csv_line("1,2,") == V{"1", "2", ""});  // a trailing comma: an empty last cell
  CHECK(util::split_csv_line(",") == V{"", ""});
  CHECK(util::split_csv_line("") == V{""});
  CHECK(util::split_csv_line("a,b\r") == V{"a", "b"});  // a CRLF line
}

TEST_CASE("CSV cells are numbers only when the whole cell is one, and a missing value is NaN, not zero", "[cases][csv]") {
  CHECK(util::csv_number("0.25") == 0.25);
  CHECK(util::csv_number("-1.5e-3") == -1.5e-3);
  CHECK(util::csv_number(" 2 ") == 2.0);
  CHECK(std::isnan(util::csv_number("nan")));
  CHECK(std::isnan(util::csv_number("")));
  CHECK(std::isnan(util::csv_number("  ")));
  CHECK(std::isnan(util::csv_number("1.5x")));
  CHECK(std::isnan(util::csv_number("—")));
}

TEST_CASE("CSV files read back as a header and rows, and an unreadable file as an empty table", "[cases][csv]") {
  const hydrojump::testing::TempDir tmp("csv_table");
  const fs::path& dir = tmp.path();
  const fs::path file = dir / "basin.csv";
  {
    std::ofstream out(file);
    out << "t_s,toe_x_m,q_in\n0.1,0.5,0.1\n\n0.2,nan,0.1\n0.3,0.6";  // a blank line, a torn last line
  }
  const util::CsvTable table = util::read_csv_table(file);
  REQUIRE(table.header == std::vector<std::string>{"t_s", "toe_x_m", "q_in"});
  REQUIRE(table.rows.size() == 3);
  CHECK(table.rows[2].size() == 2);
  REQUIRE(table.column("toe_x_m"));
  CHECK(*table.column("toe_x_m") == 1);
  CHECK_FALSE(table.column("toe"));
  CHECK(std::isnan(util::csv_number(table.rows[1][1])));

  const util::CsvTable none = util::read_csv_table(dir / "absent.csv");
  CHECK(none.header.empty());
  CHECK(none.rows.empty());
}
