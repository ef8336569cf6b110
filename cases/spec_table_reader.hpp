// The spec reader's internals, shared by its files (spec_reader.cpp: the study and its cases;
// spec_methods.cpp: the [sph] and [vof] tables; spec_case_kinds.cpp: the case kinds' own tables):
// the checked TOML table reader with its number ranges and the error messages that name file, line
// and key. Not part of the spec's interface (spec_reader.hpp); only files of cases/ include it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "cases/spec.hpp"
#include "cases/spec_reader.hpp"
#include "util/csv_table.hpp"
#include "util/number_text.hpp"

namespace hydrojump::cases::spec_detail {

// The largest file read as a study or a measured table: a study file is a few kB (and /dev/zero
// would be read until memory ran out).
constexpr std::uintmax_t max_input_file_bytes = 16u << 20;

// The measured surge front (measured.front_file) is a table of the front against time: '#' comment
// lines, a header naming t_s and x_front_over_L, then at least two rows with finite numbers there
// and t_s increasing. What is wrong with `file` as such a table, or "" when nothing is. At most
// 16 MiB and a regular file (a device or a pipe would be read for ever).
inline std::string front_file_problem(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return "is not a regular file";
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) return "cannot be read (" + ec.message() + ")";
  if (size > max_input_file_bytes) return "is larger than 16 MiB, not a table of the surge front";
  std::ifstream in(file, std::ios::binary);
  if (!in) return "cannot be read";
  std::vector<std::string> header;
  std::optional<std::size_t> t_column, x_column;
  std::size_t rows = 0;
  double last_t = -std::numeric_limits<double>::infinity();
  std::size_t line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line.front() == '#') continue;
    const std::vector<std::string> cells = util::split_csv_line(line);
    if (header.empty()) {
      header = cells;
      for (std::size_t k = 0; k < header.size(); ++k) {
        if (header[k] == "t_s") t_column = k;
        if (header[k] == "x_front_over_L") x_column = k;
      }
      if (!t_column || !x_column)
        return "has no header line with the columns t_s and x_front_over_L (its first line that is not a '#' "
               "comment is line " + std::to_string(line_number) + ")";
      continue;
    }
    const double t = cells.size() == header.size() ? util::csv_number(cells[*t_column]) : std::nan("");
    const double x = cells.size() == header.size() ? util::csv_number(cells[*x_column]) : std::nan("");
    if (!std::isfinite(t) || !std::isfinite(x))
      return "line " + std::to_string(line_number) + " is not a row of " + std::to_string(header.size()) +
             " cells with numbers for t_s and x_front_over_L";
    if (!(t > last_t)) return "line " + std::to_string(line_number) + ": t_s does not increase";
    last_t = t;
    ++rows;
  }
  if (header.empty()) return "has no header line with the columns t_s and x_front_over_L (it is empty or only comments)";
  if (rows < 2) return "holds " + std::to_string(rows) + " row(s) of the front; at least 2 are needed";
  return {};
}

// v to `digits` significant digits (for derived values in messages).
inline std::string rounded_text(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

// The same as a TOML float (which needs a '.' or an exponent).
inline std::string toml_number(double v) {
  std::string s = util::number_text(v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// Case ids and resolution names become directory names and bare TOML keys: 1 to 64 letters, digits,
// '_' or '-' (so never "." or "..", never a path).
constexpr const char* plain_name_rule = "use 1 to 64 letters, digits, '_' or '-'";
inline bool is_plain_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
  });
}

// An allowed interval for a number, with its unit, for messages.
struct Range {
  double low = -HUGE_VAL;
  double high = HUGE_VAL;
  bool low_open = false;   // true: value must be > low
  bool high_open = false;  // true: value must be < high
  std::string unit;

  bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (low_open ? !(v > low) : !(v >= low)) return false;
    if (high_open ? !(v < high) : !(v <= high)) return false;
    return true;
  }
  std::string describe() const {
    std::string s = "must be ";
    bool any = false;
    if (low != -HUGE_VAL) {
      s += (low_open ? "> " : ">= ") + util::number_text(low);
      any = true;
    }
    if (high != HUGE_VAL) {
      s += (any ? " and " : "") + std::string(high_open ? "< " : "<= ") + util::number_text(high);
      any = true;
    }
    if (!any) s += "a finite number";
    if (!unit.empty()) s += " (" + unit + ")";
    return s;
  }
};

inline Range positive(std::string unit, double high = HUGE_VAL) { return Range{0.0, high, true, false, std::move(unit)}; }
inline Range non_negative(std::string unit, double high = HUGE_VAL) { return Range{0.0, high, false, false, std::move(unit)}; }
inline Range between(double low, double high, std::string unit = "") { return Range{low, high, false, false, std::move(unit)}; }

inline std::string node_text(const toml::node& node) {
  std::ostringstream out;
  if (node.is_string()) {
    out << '"' << *node.value<std::string>() << '"';
  } else if (node.is_floating_point()) {
    out << util::number_text(*node.value<double>());
  } else if (node.is_integer()) {
    out << *node.value<std::int64_t>();
  } else if (node.is_boolean()) {
    out << (*node.value<bool>() ? "true" : "false");
  } else if (node.is_table()) {
    out << "(a table)";
  } else if (node.is_array()) {
    out << "(an array)";
  } else {
    out << "(a date/time)";
  }
  return out.str();
}

inline std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    default: return "a date/time";
  }
}

// Reads one TOML table, remembering which keys were used, so that unknown keys are rejected and every
// message names the file, the line, the full dotted key and the allowed values.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string file, std::string context, std::string prefix)
      : table_(table), file_(std::move(file)), context_(std::move(context)), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail_at(const toml::node* node, std::string_view key, const std::string& what) const {
    const auto& region = node ? node->source() : table_.source();
    std::string msg = file_;
    if (region.begin.line > 0) msg += ":" + std::to_string(region.begin.line);
    msg += ": " + context_ + full_key(key) + " " + what;
    throw SpecError(msg);
  }

  std::string full_key(std::string_view key) const {
    return key.empty() ? (prefix_.empty() ? std::string("(top level)") : prefix_.substr(0, prefix_.size() - 1))
                       : prefix_ + std::string(key);
  }

  bool has(std::string_view key) const { return table_.contains(key); }

  const toml::node* get(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  double number(std::string_view key, const Range& range) {
    const toml::node* node = get(key);
    if (!node) fail_at(nullptr, key, "is missing (required; " + range.describe() + ")");
    return checked_number(node, key, range);
  }

  double number_or(std::string_view key, double fallback, const Range& range) {
    const toml::node* node = get(key);
    return node ? checked_number(node, key, range) : fallback;
  }

  std::optional<double> optional_number(std::string_view key, const Range& range) {
    const toml::node* node = get(key);
    if (!node) return std::nullopt;
    return checked_number(node, key, range);
  }

  int integer_or(std::string_view key, int fallback, int low, int high) {
    const toml::node* node = get(key);
    if (!node) return fallback;
    if (!node->is_integer()) fail_at(node, key, "= " + node_text(*node) + " must be an integer from " + std::to_string(low) + " to " + std::to_string(high));
    const auto v = *node->value<std::int64_t>();
    if (v < low || v > high) fail_at(node, key, "= " + std::to_string(v) + " is out of range: must be from " + std::to_string(low) + " to " + std::to_string(high));
    return static_cast<int>(v);
  }

  std::string string(std::string_view key) {
    const toml::node* node = get(key);
    if (!node) fail_at(nullptr, key, "is missing (required string)");
    if (!node->is_string()) fail_at(node, key, "= " + node_text(*node) + " has the wrong type: expected a string, got " + type_name(*node));
    return *node->value<std::string>();
  }

  std::string string_or(std::string_view key, const std::string& fallback) {
    return has(key) ? string(key) : (get(key), fallback);
  }

  std::string choice(std::string_view key, const std::string& fallback, const std::vector<std::string_view>& allowed,
                     bool required = false) {
    if (!has(key)) {
      if (required) fail_at(nullptr, key, "is missing (required; one of " + list(allowed) + ")");
      get(key);
      return fallback;
    }
    const toml::node* node = get(key);
    if (!node->is_string()) fail_at(node, key, "= " + node_text(*node) + " has the wrong type: expected one of " + list(allowed));
    const std::string v = *node->value<std::string>();
    if (std::find(allowed.begin(), allowed.end(), v) == allowed.end()) {
      fail_at(node, key, "= \"" + v + "\" is not a known option: allowed values are " + list(allowed));
    }
    return v;
  }

  // An option of cases/options.hpp: the names of its table, parsed once into the enum.
  template <class E>
  E choice(std::string_view key, E fallback, bool required = false) {
    std::vector<std::string_view> names;
    for (const auto& option : OptionTable<E>::values) names.push_back(option.name);
    return *parse_option<E>(choice(key, std::string(option_name(fallback)), names, required));
  }

  std::vector<double> number_array(std::string_view key, const Range& range) {
    const toml::node* node = get(key);
    if (!node) return {};
    const toml::array* array = node->as_array();
    if (!array) fail_at(node, key, "= " + node_text(*node) + " has the wrong type: expected an array of numbers");
    std::vector<double> values;
    for (const auto& item : *array) values.push_back(checked_number(&item, key, range));
    return values;
  }

  std::vector<std::string> string_array(std::string_view key) {
    const toml::node* node = get(key);
    if (!node) return {};
    const toml::array* array = node->as_array();
    if (!array) fail_at(node, key, "= " + node_text(*node) + " has the wrong type: expected an array of strings");
    std::vector<std::string> values;
    for (const auto& item : *array) {
      if (!item.is_string()) fail_at(&item, key, "contains " + node_text(item) + ": expected strings only");
      values.push_back(*item.value<std::string>());
    }
    return values;
  }

  // A sub-table; nullopt if absent. Rejects a key that is present but not a table.
  std::optional<TableReader> table(std::string_view key) {
    const toml::node* node = get(key);
    if (!node) return std::nullopt;
    const toml::table* t = node->as_table();
    if (!t) fail_at(node, key, "= " + node_text(*node) + " has the wrong type: expected a table [" + full_key(key) + "]");
    return TableReader(*t, file_, context_, prefix_ + std::string(key) + ".");
  }

  TableReader required_table(std::string_view key) {
    auto t = table(key);
    if (!t) fail_at(nullptr, key, "is missing: the table [" + full_key(key) + "] is required");
    return *t;
  }

  const toml::array* array_of_tables(std::string_view key) {
    const toml::node* node = get(key);
    if (!node) return nullptr;
    const toml::array* array = node->as_array();
    if (!array || !array->is_array_of_tables()) fail_at(node, key, "has the wrong type: expected an array of tables [[" + full_key(key) + "]]");
    return array;
  }

  TableReader element(const toml::node& node, std::string_view key, std::size_t index) const {
    return TableReader(*node.as_table(), file_, context_, prefix_ + std::string(key) + "[" + std::to_string(index) + "].");
  }

  // Rejects keys that were never asked for, naming the keys that are allowed.
  void reject_unknown_keys() const {
    for (const auto& [key, node] : table_) {
      if (!used_.count(std::string(key.str()))) {
        std::string allowed;
        for (const auto& k : used_) allowed += (allowed.empty() ? "" : ", ") + k;
        fail_at(&node, key.str(), "is not a known key here" + (allowed.empty() ? std::string() : " (known keys: " + allowed + ")"));
      }
    }
  }

  const toml::table& raw() const { return table_; }
  const std::string& file() const { return file_; }

 private:
  static std::string list(const std::vector<std::string_view>& allowed) {
    std::string s;
    for (auto a : allowed) s += (s.empty() ? "\"" : ", \"") + std::string(a) + "\"";
    return s;
  }

  double checked_number(const toml::node* node, std::string_view key, const Range& range) const {
    double v = 0.0;
    if (node->is_floating_point()) {
      v = *node->value<double>();
    } else if (node->is_integer()) {
      v = static_cast<double>(*node->value<std::int64_t>());
    } else {
      fail_at(node, key, "= " + node_text(*node) + " has the wrong type: expected a number that " + range.describe().substr(8));
    }
    if (!range.contains(v)) fail_at(node, key, "= " + util::number_text(v) + " is out of range: " + range.describe());
    return v;
  }

  const toml::table& table_;
  std::string file_;
  std::string context_;
  std::string prefix_;
  std::set<std::string> used_;
};

// The tables of the methods (spec_methods.cpp) and of the case kinds (spec_case_kinds.cpp).
void read_sph(TableReader& t, SphSettings& s);
void read_vof(TableReader& t, VofSettings& v);
StillingBasinCase read_stilling_basin(TableReader& c, double g);
DamBreakCase read_dam_break(TableReader& c, const std::filesystem::path& base_dir);
StillWaterCase read_still_water(TableReader& c);
PoiseuilleCase read_poiseuille(TableReader& c);

}  // namespace hydrojump::cases::spec_detail
