#include "util/csv_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace hydrojump::util {

std::vector<std::string> split_csv_line(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  std::vector<std::string> cells;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    cells.emplace_back(line.substr(begin, comma == std::string_view::npos ? std::string_view::npos : comma - begin));
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  return cells;
}

double csv_number(std::string_view cell) {
  const auto first = cell.find_first_not_of(" \t");
  if (first == std::string_view::npos) return std::nan("");
  const auto last = cell.find_last_not_of(" \t");
  const std::string text(cell.substr(first, last - first + 1));
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nan("");
  return v;
}

std::optional<std::size_t> CsvTable::column(std::string_view name) const {
  const auto at = std::find(header.begin(), header.end(), name);
  if (at == header.end()) return std::nullopt;
  return static_cast<std::size_t>(at - header.begin());
}

CsvTable read_csv_table(const std::filesystem::path& file) {
  CsvTable table;
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) return table;
  table.header = split_csv_line(line);
  while (std::getline(in, line)) {
    if (line.empty() || line == "\r") continue;
    table.rows.push_back(split_csv_line(line));
  }
  return table;
}

}  // namespace hydrojump::util
