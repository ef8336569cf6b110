// The small comma-separated tables the project writes and reads back itself: the SPH run monitor's
// basin.csv (and its checkpointed rows), the comparator's eta.csv and metrics.csv. No quoting (none of
// them holds a comma inside a cell); one header line; a line ending in ',' has an empty last cell.
//
// Usage
//   | function          | returns                                                              |
//   |-------------------|----------------------------------------------------------------------|
//   | split_csv_line    | the cells of one line                                                |
//   | csv_number        | a cell as a number; NaN for "nan", an empty cell or any other text   |
//   | read_csv_table    | header and non-empty rows of a file; empty header if unreadable      |
//   | CsvTable::column  | a header name's index, or nullopt                                    |
// Example:
//   const util::CsvTable table = util::read_csv_table(run / "basin.csv");
//   if (const auto t = table.column("t_s"))
//     for (const auto& row : table.rows) if (row.size() == table.header.size()) use(util::csv_number(row[*t]));
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hydrojump::util {

std::vector<std::string> split_csv_line(std::string_view line);

// The cell's number when the whole cell (surrounding blanks aside) is one, else NaN: an empty cell is
// a missing value, not zero.
double csv_number(std::string_view cell);

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // as split; a torn last line may be shorter than header

  std::optional<std::size_t> column(std::string_view name) const;
};

CsvTable read_csv_table(const std::filesystem::path& file);

}  // namespace hydrojump::util
