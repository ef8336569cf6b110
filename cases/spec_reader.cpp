#include "cases/spec_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <toml++/toml.h>

#include "util/atomic_file.hpp"
#include "cases/case_rules.hpp"
#include "util/csv_table.hpp"
#include "util/fingerprint.hpp"
#include "cases/geometry.hpp"
#include "cases/hydraulics.hpp"
#include "util/number_text.hpp"
#include "cases/output_times.hpp"

namespace hydrojump::cases {
namespace {

// The largest file read as a study or a measured table: a study file is a few kB (and /dev/zero
// would be read until memory ran out).
constexpr std::uintmax_t max_input_file_bytes = 16u << 20;

// The measured surge front (measured.front_file) is a table of the front against time: '#' comment
// lines, a header naming t_s and x_front_over_L, then at least two rows with finite numbers there
// and t_s increasing. What is wrong with `file` as such a table, or "" when nothing is. At most
// 16 MiB and a regular file (a device or a pipe would be read for ever).
std::string front_file_problem(const std::filesystem::path& file) {
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
std::string rounded_text(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

// The same as a TOML float (which needs a '.' or an exponent).
std::string toml_number(double v) {
  std::string s = util::number_text(v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// Case ids and resolution names become directory names and bare TOML keys: 1 to 64 letters, digits,
// '_' or '-' (so never "." or "..", never a path).
constexpr const char* plain_name_rule = "use 1 to 64 letters, digits, '_' or '-'";
bool is_plain_name(const std::string& name) {
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

Range positive(std::string unit, double high = HUGE_VAL) { return Range{0.0, high, true, false, std::move(unit)}; }
Range non_negative(std::string unit, double high = HUGE_VAL) { return Range{0.0, high, false, false, std::move(unit)}; }
Range between(double low, double high, std::string unit = "") { return Range{low, high, false, false, std::move(unit)}; }

std::string node_text(const toml::node& node) {
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

std::string type_name(const toml::node& node) {
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

  std::string choice(std::string_view key, const std::string& fallback,
                     std::initializer_list<std::string_view> allowed, bool required = false) {
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
  static std::string list(std::initializer_list<std::string_view> allowed) {
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

void read_sph(TableReader& t, SphSettings& s) {
  s.kernel = t.choice("kernel", s.kernel, {"wendland_c2", "cubic_spline"});
  s.viscosity = t.choice("viscosity", s.viscosity, {"artificial", "laminar_sps"});
  s.artificial_viscosity_alpha = t.number_or("artificial_viscosity_alpha", s.artificial_viscosity_alpha, between(0.0, 1.0));
  // nu or alpha: both in one table is an error; alpha given here overrides a nu inherited from [sph].
  if (t.has("artificial_viscosity_nu_m2_s") && t.has("artificial_viscosity_alpha"))
    t.fail_at(t.raw().get("artificial_viscosity_nu_m2_s"), "artificial_viscosity_nu_m2_s",
              "and artificial_viscosity_alpha are both given: set one (nu fixes alpha = 8 nu / (h c0) at each resolution)");
  if (t.has("artificial_viscosity_alpha")) s.artificial_viscosity_nu_m2_s = 0.0;
  s.artificial_viscosity_nu_m2_s = t.number_or("artificial_viscosity_nu_m2_s", s.artificial_viscosity_nu_m2_s,
                                                non_negative("m^2/s, 0: use artificial_viscosity_alpha", 1.0));
  if (t.has("artificial_viscosity_nu_m2_s") && s.viscosity != "artificial")
    t.fail_at(t.raw().get("artificial_viscosity_nu_m2_s"), "artificial_viscosity_nu_m2_s",
              std::string("is only used with viscosity = \"artificial\" (here \"") + s.viscosity + "\")");
  // A case that switches to another viscosity model does not use the nu it inherits from [sph].
  if (s.viscosity != "artificial") s.artificial_viscosity_nu_m2_s = 0.0;
  s.artificial_viscosity_wall_factor = t.number_or("artificial_viscosity_wall_factor", s.artificial_viscosity_wall_factor, between(0.0, 1.0));
  s.sps_smagorinsky_constant = t.number_or("sps_smagorinsky_constant", s.sps_smagorinsky_constant, between(0.0, 1.0));
  s.sps_blin_constant = t.number_or("sps_blin_constant", s.sps_blin_constant, between(0.0, 1.0));
  // The mixing length is given in metres or by the rule l = c_l y2* (cases/case_rules.hpp): a table that
  // gives one drops the other it inherits; one that sets C_s alone means Smagorinsky's length.
  constexpr const char* kRule = "sps_mixing_length_per_sequent_depth";
  if (t.has("sps_mixing_length_m") && t.has(kRule))
    t.fail_at(t.raw().get(kRule), kRule, "and sps_mixing_length_m are both given: set one (the rule gives l = c_l y2* per case)");
  if (t.has("sps_smagorinsky_constant") && !t.has("sps_mixing_length_m") && !t.has(kRule)) {
    s.sps_mixing_length_m = 0.0;
    s.sps_mixing_length_per_sequent_depth = 0.0;
  }
  if (t.has("sps_mixing_length_m")) s.sps_mixing_length_per_sequent_depth = 0.0;
  if (t.has(kRule)) s.sps_mixing_length_m = 0.0;
  s.sps_mixing_length_m = t.number_or("sps_mixing_length_m", s.sps_mixing_length_m,
                                      non_negative("m, 0: the Smagorinsky length sps_smagorinsky_constant dx", 1.0));
  s.sps_mixing_length_per_sequent_depth = t.number_or(kRule, s.sps_mixing_length_per_sequent_depth,
                                                      between(0.0, 1.0, "l / y2*, 0: no rule"));
  s.sps_wall_distance = t.choice("sps_wall_distance", s.sps_wall_distance, {"kernel_support", "whole_domain"});
  s.boundary = t.choice("boundary", s.boundary, {"dbc", "mdbc"});
  s.viscous_wall_condition = t.choice("viscous_wall_condition", s.viscous_wall_condition, {"no_slip", "free_slip", "wall_function"});
  // A case that switches to another viscosity model does not use the wall condition it inherits.
  if (s.viscosity != "laminar_sps") s.viscous_wall_condition = "no_slip";
  s.density_diffusion = t.choice("density_diffusion", s.density_diffusion, {"none", "molteni", "fourtakas"});
  s.density_diffusion_coefficient = t.number_or("density_diffusion_coefficient", s.density_diffusion_coefficient, between(0.0, 1.0));
  s.sound_speed_coefficient = t.number_or("sound_speed_coefficient", s.sound_speed_coefficient, Range{1.0, 1000.0, false, false, "c0 / sqrt(g H_max)"});
  s.sound_speed_m_s = t.number_or("sound_speed_m_s", s.sound_speed_m_s, non_negative("m/s", 1e5));
  s.sound_speed_min_flow_ratio = t.number_or("sound_speed_min_flow_ratio", s.sound_speed_min_flow_ratio, Range{0.0, 1000.0, true, false, "c0 / expected max flow speed"});
  s.cfl_number = t.number_or("cfl_number", s.cfl_number, Range{0.01, 1.0, false, false, ""});
  s.coef_h = t.number_or("coef_h", s.coef_h, Range{0.5, 3.0, false, false, "h = coef_h sqrt(2) dx"});
  s.time_integrator = t.choice("time_integrator", s.time_integrator, {"symplectic", "verlet"});
  s.verlet_euler_interval = t.integer_or("verlet_euler_interval", s.verlet_euler_interval, 1, 1000);
  s.boundary_layers = t.integer_or("boundary_layers", s.boundary_layers, 0, 20);
  s.open_boundary_layers = t.integer_or("open_boundary_layers", s.open_boundary_layers, 0, 50);
  s.inflow_condition = t.choice("inflow_condition", s.inflow_condition, {"buffer", "piston"});
  s.sluice_opening_m = t.number_or("sluice_opening_m", s.sluice_opening_m, non_negative("m, 0: y1 / 0.611", 100.0));
  s.reservoir_length_m = t.number_or("reservoir_length_m", s.reservoir_length_m, non_negative("m, 0: from the run's length", 1000.0));
  s.piston_level_gain_per_s = t.number_or("piston_level_gain_per_s", s.piston_level_gain_per_s,
                                          non_negative("1/s, 0: the piston keeps the speed q/H_r", 1000.0));
  for (const char* key : {"sluice_opening_m", "reservoir_length_m", "piston_level_gain_per_s"})
    if (s.inflow_condition != "piston" && t.raw().get(key))
      t.fail_at(t.raw().get(key), key, std::string("is only used with inflow_condition = \"piston\" (here \"") + s.inflow_condition + "\")");
  s.outflow_condition = t.choice("outflow_condition", s.outflow_condition, {"hydrostatic_level", "absorbing", "tailgate"});
  s.tailgate_height_m = t.number_or("tailgate_height_m", s.tailgate_height_m, non_negative("m, 0: from the tailwater depth", 100.0));
  if (s.outflow_condition != "tailgate" && t.raw().get("tailgate_height_m"))
    t.fail_at(t.raw().get("tailgate_height_m"), "tailgate_height_m",
              "is only used with outflow_condition = \"tailgate\" (here \"" + s.outflow_condition + "\")");
  s.outflow_level_reference = t.choice("outflow_level_reference", s.outflow_level_reference, {"outlet", "downstream_section"});
  if (s.outflow_condition == "tailgate" && s.outflow_level_reference != "outlet")
    t.fail_at(t.raw().get("outflow_level_reference") ? t.raw().get("outflow_level_reference") : t.raw().get("outflow_condition"),
              "outflow_level_reference", "= \"" + s.outflow_level_reference +
              "\" needs an outflow buffer: a tailgate sets its level by its crest (use outflow_condition = \"absorbing\" or \"hydrostatic_level\")");
  s.outflow_level_time_s = t.number_or("outflow_level_time_s", s.outflow_level_time_s, Range{0.0, 100.0, true, false, "s, integral time of the level control"});
  if (s.outflow_level_reference != "downstream_section" && t.raw().get("outflow_level_time_s"))
    t.fail_at(t.raw().get("outflow_level_time_s"), "outflow_level_time_s",
              "is only used with outflow_level_reference = \"downstream_section\" (here \"" + s.outflow_level_reference + "\")");
  if (s.open_boundary_layers > 0) {
    // The buffers must cover the kernel support 2h = 2 sqrt(2) coef_h dx of the fluid next to them.
    const int needed = static_cast<int>(std::ceil(2.0 * std::sqrt(2.0) * s.coef_h - 1e-9)) + 1;
    if (s.open_boundary_layers < needed)
      t.fail_at(t.raw().get("open_boundary_layers"), "open_boundary_layers",
                "= " + std::to_string(s.open_boundary_layers) + " makes the inflow/outflow buffers thinner than the kernel support 2h = " +
                    util::number_text(2.0 * std::sqrt(2.0) * s.coef_h) + " dx (coef_h = " + util::number_text(s.coef_h) +
                    "): use 0 (automatic) or at least " + std::to_string(needed));
  }
  s.particle_shifting = t.choice("particle_shifting", s.particle_shifting, {"none", "fickian"});
  s.particle_shifting_coefficient = t.number_or("particle_shifting_coefficient", s.particle_shifting_coefficient,
                                                Range{0.0, 10.0, true, false, "A in delta r = -A h |v| dt grad C"});
  s.particle_shifting_surface_threshold = t.number_or("particle_shifting_surface_threshold", s.particle_shifting_surface_threshold,
                                                      Range{0.0, 1.9, false, false, "div r (2 in the bulk of a 2D fluid; at 1.98 or more every particle would count as at the surface)"});
  s.particle_shifting_correction = t.choice("particle_shifting_correction", s.particle_shifting_correction, {"none", "taylor", "taylor_volume"});
  s.max_density_variation = t.number_or("max_density_variation", s.max_density_variation, Range{0.0, 0.5, true, false, "|rho/rho0 - 1|"});
  s.checkpoint_interval_wall_s = t.number_or("checkpoint_interval_wall_s", s.checkpoint_interval_wall_s, positive("s", 1e6));
  // A parameter of a model this table's settings do not use is an error (it would be silently ignored).
  // Inherited ones are not: a case that switches model drops the [sph] parameters of the old one.
  const auto only_with = [&](const char* key, bool used, const std::string& requirement) {
    if (!used && t.has(key)) t.fail_at(t.raw().get(key), key, "is only used with " + requirement);
  };
  const std::string here_viscosity = " (here \"" + s.viscosity + "\")";
  only_with("artificial_viscosity_alpha", s.viscosity == "artificial", "viscosity = \"artificial\"" + here_viscosity);
  only_with("artificial_viscosity_wall_factor", s.viscosity == "artificial", "viscosity = \"artificial\"" + here_viscosity);
  only_with("sps_smagorinsky_constant", s.viscosity == "laminar_sps", "viscosity = \"laminar_sps\"" + here_viscosity);
  only_with("sps_blin_constant", s.viscosity == "laminar_sps", "viscosity = \"laminar_sps\"" + here_viscosity);
  only_with("sps_mixing_length_m", s.viscosity == "laminar_sps", "viscosity = \"laminar_sps\"" + here_viscosity);
  only_with(kRule, s.viscosity == "laminar_sps", "viscosity = \"laminar_sps\"" + here_viscosity);
  only_with("viscous_wall_condition", s.viscosity == "laminar_sps", "viscosity = \"laminar_sps\"" + here_viscosity);
  if (s.viscous_wall_condition != "no_slip" && s.boundary != "mdbc")
    t.fail_at(t.raw().get(t.has("viscous_wall_condition") ? "viscous_wall_condition" : "boundary"), "viscous_wall_condition",
              "= \"" + s.viscous_wall_condition + "\" needs boundary = \"mdbc\" (the slip velocity is mirrored at mDBC's ghost nodes; here \"" +
                  s.boundary + "\")");
  const bool mixing_length = s.sps_mixing_length_m > 0.0 || s.sps_mixing_length_per_sequent_depth > 0.0;
  only_with("sps_wall_distance", s.viscosity == "laminar_sps" && mixing_length,
            "viscosity = \"laminar_sps\" and a mixing length, sps_mixing_length_m or " + std::string(kRule) +
                " > 0 (here \"" + s.viscosity + "\", " + util::number_text(s.sps_mixing_length_m) + " m)");
  // A case without a mixing length does not use the distance rule it inherits, nor the length rule.
  if (s.viscosity != "laminar_sps" || !mixing_length) s.sps_wall_distance = "kernel_support";
  if (s.viscosity != "laminar_sps") s.sps_mixing_length_per_sequent_depth = 0.0;
  for (const char* key : {"sps_mixing_length_m", kRule})
    if (t.has(key) && t.has("sps_smagorinsky_constant") && mixing_length)
      t.fail_at(t.raw().get(key), key, "and sps_smagorinsky_constant are both given: the mixing length replaces C_s dx, set one");
  only_with("density_diffusion_coefficient", s.density_diffusion != "none",
            "density_diffusion = \"molteni\" or \"fourtakas\" (here \"none\")");
  for (const char* key : {"particle_shifting_coefficient", "particle_shifting_surface_threshold", "particle_shifting_correction"})
    only_with(key, s.particle_shifting == "fickian", "particle_shifting = \"fickian\" (here \"" + s.particle_shifting + "\")");
  if (s.particle_shifting != "none" && s.time_integrator != "symplectic")
    t.fail_at(t.raw().get(t.has("particle_shifting") ? "particle_shifting" : "time_integrator"), "particle_shifting",
              "= \"" + s.particle_shifting + "\" needs time_integrator = \"symplectic\" (here \"" + s.time_integrator + "\")");
  only_with("verlet_euler_interval", s.time_integrator == "verlet",
            "time_integrator = \"verlet\" (here \"" + s.time_integrator + "\")");
  for (const char* key : {"sound_speed_coefficient", "sound_speed_min_flow_ratio"})
    only_with(key, s.sound_speed_m_s == 0.0,
              "sound_speed_m_s = 0 (here " + util::number_text(s.sound_speed_m_s) + " m/s gives c0 directly)");
  t.reject_unknown_keys();
}

void read_vof(TableReader& t, VofSettings& v) {
  v.turbulence_model = t.choice("turbulence_model", v.turbulence_model, {"laminar", "kOmegaSST", "kEpsilon", "RNGkEpsilon"});
  v.turbulence_stabilization = t.choice("turbulence_stabilization", v.turbulence_stabilization, {"none", "nut_limiter", "nut_limiter_and_buoyancy"});
  // The v1912 fvOption corrects k and nut = Cmu k^2/epsilon: it needs an epsilon-based model. The check
  // runs on the merged settings, so a case's [case.vof] that changes either key is checked too.
  if (v.turbulence_stabilization != "none" && v.turbulence_model != "kEpsilon" && v.turbulence_model != "RNGkEpsilon") {
    // One of the two keys is in this table: the study's [vof] passed this check before a case overrode it.
    const std::string key = t.has("turbulence_stabilization") ? "turbulence_stabilization" : "turbulence_model";
    const std::string value = key == "turbulence_stabilization" ? v.turbulence_stabilization : v.turbulence_model;
    t.fail_at(t.raw().get(key), key,
              "= \"" + value + "\" cannot be used: turbulence_stabilization = \"" + v.turbulence_stabilization +
                  "\" needs an epsilon-based turbulence_model (allowed: \"kEpsilon\", \"RNGkEpsilon\"), but turbulence_model is \"" +
                  v.turbulence_model + "\"");
  }
  v.max_courant = t.number_or("max_courant", v.max_courant, Range{0.01, 5.0, false, false, ""});
  v.max_alpha_courant = t.number_or("max_alpha_courant", v.max_alpha_courant, Range{0.01, 5.0, false, false, ""});
  v.max_time_step_s = t.number_or("max_time_step_s", v.max_time_step_s, Range{1e-6, 1.0, false, false, "s"});
  v.mesh_strategy = t.choice("mesh_strategy", v.mesh_strategy, {"cartesian_cut", "body_fitted"});
  v.surface_refinement_band_m = t.number_or("surface_refinement_band_m", v.surface_refinement_band_m, non_negative("m", 100.0));
  // The tailwater control is the case's protocol, read by both solvers ([case.tailwater] control).
  for (const char* key : {"tailwater_control", "volume_hold_time_s", "toe_hold_time_s"})
    if (t.has(key))
      t.fail_at(t.raw().get(key), key,
                "is no [vof] setting: the tailwater control is the case's protocol, read by both solvers: "
                "[case.tailwater] control = \"hold_toe\" (the default) or \"fixed_depth\", with its "
                "volume_hold_time_s and toe_hold_time_s");
  v.tailwater_control_interval_s = t.number_or("tailwater_control_interval_s", v.tailwater_control_interval_s, positive("s", 100.0));
  t.reject_unknown_keys();
}

void read_resolution(TableReader& t, Resolution& r, bool require_all) {
  const Range length = positive("m", 10.0);
  if (require_all) {
    r.particle_spacing_m = t.number("particle_spacing_m", length);
    r.vof_cell_size_bed_m = t.number("vof_cell_size_bed_m", length);
    r.vof_cell_size_bulk_m = t.number("vof_cell_size_bulk_m", length);
  } else {
    r.particle_spacing_m = t.number_or("particle_spacing_m", r.particle_spacing_m, length);
    r.vof_cell_size_bed_m = t.number_or("vof_cell_size_bed_m", r.vof_cell_size_bed_m, length);
    r.vof_cell_size_bulk_m = t.number_or("vof_cell_size_bulk_m", r.vof_cell_size_bulk_m, length);
  }
  if (r.vof_cell_size_bulk_m < r.vof_cell_size_bed_m) {
    t.fail_at(t.raw().get("vof_cell_size_bulk_m"), "vof_cell_size_bulk_m",
              "= " + util::number_text(r.vof_cell_size_bulk_m) + " is out of range: must be >= vof_cell_size_bed_m (" + util::number_text(r.vof_cell_size_bed_m) + " m)");
  }
  t.reject_unknown_keys();
}

// The study's [resolution] rule key: the inflow depth its levels are given for (resolution_rule below).
constexpr const char* resolution_rule_key = "for_inflow_depth_m";

void read_resolutions(TableReader& parent, std::map<std::string, Resolution>& out, bool require_all) {
  auto t = parent.table("resolution");
  if (!t) return;
  for (const auto& [name, node] : t->raw()) {
    const std::string key(name.str());
    if (key == resolution_rule_key) {  // the study's rule (read by the study), not a level
      if (!require_all)
        t->fail_at(&node, key, "is a rule of the study's [resolution] table: a case's own levels are given as they are");
      (void)t->number(key, positive("m", 10.0));
      continue;
    }
    if (!is_plain_name(key)) {
      t->fail_at(&node, key, std::string("is not usable as a resolution name (it names directories and TOML tables): ") + plain_name_rule);
    }
    auto level = t->table(key);
    Resolution r = out.count(key) ? out.at(key) : Resolution{};
    if (!require_all && !out.count(key)) {
      t->fail_at(&node, key, "is not a resolution defined at the study level (define [resolution." + key + "] first)");
    }
    r.name = key;
    read_resolution(*level, r, require_all);
    out[key] = r;
  }
  t->reject_unknown_keys();
}

void read_run(TableReader& t, RunSettings& run) {
  run.end_time_s = t.number("end_time_s", positive("s", max_end_time_s));
  run.output_interval_s = t.number_or("output_interval_s", run.output_interval_s, positive("s", max_end_time_s));
  if (run.output_interval_s > run.end_time_s) {
    t.fail_at(t.raw().get("output_interval_s"), "output_interval_s", "= " + util::number_text(run.output_interval_s) + " is out of range: must be <= run.end_time_s (" + util::number_text(run.end_time_s) + " s)");
  }
  // Every output is a file per method: at most max_outputs_per_run of them.
  if (run.end_time_s / run.output_interval_s > max_outputs_per_run) {
    t.fail_at(t.raw().get("output_interval_s"), "output_interval_s",
              "= " + util::number_text(run.output_interval_s) + " is out of range: must be >= run.end_time_s / " + util::number_text(max_outputs_per_run) + " (" +
                  util::number_text(run.end_time_s / max_outputs_per_run) + " s; at most " + util::number_text(max_outputs_per_run) + " outputs a run)");
  }
  run.average_start_s = t.number_or("average_start_s", 0.5 * run.end_time_s, Range{0.0, run.end_time_s, false, true, "s, within the run and before its end"});
  run.average_end_s = t.number_or("average_end_s", run.end_time_s, Range{run.average_start_s, run.end_time_s, true, false, "s, after average_start_s and within the run"});
  // A time mean (and a standard deviation, a trend) needs two outputs at least.
  if (const long n = outputs_in_window(run.average_start_s, run.average_end_s, run.output_interval_s); n < 2) {
    // Named by the key the file gives (the window's, else the output interval or the end time).
    std::string key = "end_time_s";
    for (const char* k : {"output_interval_s", "average_start_s", "average_end_s"})
      if (t.raw().get(k)) key = k;
    const double value = key == "average_end_s"       ? run.average_end_s
                          : key == "average_start_s"   ? run.average_start_s
                          : key == "output_interval_s" ? run.output_interval_s
                                                       : run.end_time_s;
    t.fail_at(t.raw().get(key), key,
              "= " + util::number_text(value) + " leaves the averaging window [" +
                  util::number_text(run.average_start_s) + ", " + util::number_text(run.average_end_s) + "] s with " +
                  util::number_text(static_cast<double>(n)) + " output time(s) (one every output_interval_s = " +
                  util::number_text(run.output_interval_s) + " s): it must hold at least 2");
  }
  t.reject_unknown_keys();
}

// The study's [run]: the run-length rule of its stilling basins (cases/case_rules.hpp).
RunRule read_run_rule(TableReader& t) {
  RunRule r;
  r.output_interval_s = t.number_or("output_interval_s", r.output_interval_s, positive("s", 100.0));
  r.start_up_sloshing_periods = t.number_or("start_up_sloshing_periods", r.start_up_sloshing_periods,
                                            Range{0.5, 100.0, false, false, "sloshing periods 2 L / sqrt(g y2*)"});
  r.window_sloshing_periods = t.number_or("window_sloshing_periods", r.window_sloshing_periods,
                                          Range{0.0, 100.0, true, false, "sloshing periods 2 L / sqrt(g y2*)"});
  t.reject_unknown_keys();
  return r;
}

MeasuredValues read_measured(TableReader& t) {
  MeasuredValues m;
  m.sequent_depth_m = t.optional_number("sequent_depth_m", positive("m", 100.0));
  m.jump_length_m = t.optional_number("jump_length_m", positive("m", 1000.0));
  m.roller_length_m = t.optional_number("roller_length_m", positive("m", 1000.0));
  m.eta_percent = t.optional_number("eta_percent", between(0.0, 100.0, "%"));
  m.eta_smooth_percent = t.optional_number("eta_smooth_percent", between(0.0, 100.0, "%"));
  m.published_sph_eta_percent = t.optional_number("published_sph_eta_percent", between(0.0, 100.0, "%"));
  m.source = t.string_or("source", "");
  m.note = t.string_or("note", "");
  t.reject_unknown_keys();
  return m;
}

// Fails if `stated` differs from `derived` by more than 2 %.
void check_stated(TableReader& t, std::string_view key, std::optional<double> stated, double derived,
                  const std::string& derivation) {
  if (stated && std::abs(*stated - derived) > 0.02 * std::abs(derived)) {
    t.fail_at(t.raw().get(key), key, "= " + util::number_text(*stated) + " disagrees with the value derived from " + derivation + ", " + util::number_text(derived) + ", by " + util::number_text(std::round(1000.0 * std::abs(*stated / derived - 1.0)) / 10.0) + " % (allowed: 2 %)");
  }
}

StillingBasinCase read_stilling_basin(TableReader& c, double g) {
  StillingBasinCase b;
  auto inflow = c.required_table("inflow");
  b.inflow_depth_m = inflow.number("depth_m", positive("m", 10.0));
  b.inflow_velocity_m_s = inflow.number("velocity_m_s", positive("m/s", 100.0));
  b.stated_discharge_m2_s = inflow.optional_number("discharge_m2_s", positive("m^2/s"));
  b.stated_froude = inflow.optional_number("froude", positive(""));
  const auto hyd0 = jump_hydraulics(b.inflow_depth_m, b.inflow_velocity_m_s, b.inflow_depth_m, g);
  check_stated(inflow, "discharge_m2_s", b.stated_discharge_m2_s, hyd0.discharge_m2_s, "depth_m * velocity_m_s");
  check_stated(inflow, "froude", b.stated_froude, hyd0.froude1, "velocity_m_s / sqrt(g depth_m)");
  if (!(hyd0.froude1 > 1.0)) {
    inflow.fail_at(inflow.raw().get("velocity_m_s"), "velocity_m_s", "= " + util::number_text(b.inflow_velocity_m_s) + " gives Fr1 = " + util::number_text(hyd0.froude1) + ": a hydraulic jump needs supercritical inflow, Fr1 > 1, i.e. velocity_m_s > " + util::number_text(std::sqrt(g * b.inflow_depth_m)) + " m/s");
  }
  inflow.reject_unknown_keys();

  auto tail = c.required_table("tailwater");
  b.tailwater_rule = tail.choice("rule", "given", {"given", "belanger"});
  if (b.tailwater_rule == "belanger" && tail.has("depth_m")) {
    tail.fail_at(tail.raw().get("rule"), "rule", "= \"belanger\" sets the depth, and tailwater.depth_m is given too: give one of them");
  }
  if (b.tailwater_rule == "belanger") {
    b.tailwater_depth_m = hyd0.belanger_y2_m;
  } else {
    b.tailwater_depth_m = tail.number("depth_m", Range{b.inflow_depth_m, 100.0, true, false, "m, above the inflow depth y1"});
  }
  b.control.mode = tail.choice("control", b.control.mode, {"hold_toe", "fixed_depth"});
  b.control.volume_hold_time_s = tail.number_or("volume_hold_time_s", b.control.volume_hold_time_s, positive("s", 1000.0));
  b.control.toe_hold_time_s = tail.number_or("toe_hold_time_s", b.control.toe_hold_time_s, positive("s", 1000.0));
  for (const char* key : {"volume_hold_time_s", "toe_hold_time_s"})
    if (!b.control.holds_toe() && tail.has(key))
      tail.fail_at(tail.raw().get(key), key, "is only used with control = \"hold_toe\" (here \"" + b.control.mode + "\")");
  tail.reject_unknown_keys();

  auto domain = c.required_table("domain");
  b.upstream_length_m = domain.number("upstream_length_m", Range{0.0, 1000.0, true, false, "m"});
  b.basin_length_m = domain.number("basin_length_m", positive("m", 1000.0));
  b.downstream_length_m = domain.number("downstream_length_m", non_negative("m", 1000.0));
  b.air_height_m = domain.number("air_height_m", positive("m", 100.0));
  b.initial_toe_x_m = domain.optional_number("initial_toe_x_m", Range{0.0, b.upstream_length_m + b.basin_length_m, true, true, "m, inside the domain upstream of the basin end"});
  domain.reject_unknown_keys();

  auto bed = c.required_table("bed");
  b.bed.profile = bed.choice("profile", "", {"smooth", "sinusoidal"}, true);
  if (b.bed.profile == "sinusoidal") {
    b.bed.wavelength_m = bed.number("wavelength_m", positive("m", 100.0));
    b.bed.height_m = bed.number("height_m", positive("m", 100.0));
    const double basin_start = b.upstream_length_m, basin_end = basin_start + b.basin_length_m;
    const double s = b.bed.wavelength_m;
    b.bed.reach_start_m = bed.number_or("reach_start_m", basin_start, between(0.0, basin_end, "m, within the domain upstream of the basin end"));
    const double whole = std::floor((basin_end - b.bed.reach_start_m) / s + 1e-9);
    if (whole < 1.0) {
      bed.fail_at(bed.raw().get("wavelength_m"), "wavelength_m", "= " + util::number_text(s) + " is out of range: the basin from reach_start_m to its end (" + util::number_text(basin_end - b.bed.reach_start_m) + " m) must hold at least one wavelength");
    }
    b.bed.reach_end_m = bed.number_or("reach_end_m", b.bed.reach_start_m + whole * s, Range{b.bed.reach_start_m, basin_end + 1e-9, true, false, "m, after reach_start_m and not past the basin end"});
    const double n = (b.bed.reach_end_m - b.bed.reach_start_m) / s;
    if (std::abs(n - std::round(n)) > 1e-6 * std::max(1.0, n)) {
      bed.fail_at(bed.raw().get("reach_end_m"), "reach_end_m", "= " + util::number_text(b.bed.reach_end_m) + " is out of range: the corrugated reach must be a whole number of wavelengths so it ends on a crest; nearest allowed values are " + util::number_text(b.bed.reach_start_m + std::floor(n) * s) + " and " + util::number_text(b.bed.reach_start_m + std::ceil(n) * s) + " m");
    }
  } else {
    for (const char* key : {"wavelength_m", "height_m", "reach_start_m", "reach_end_m"}) {
      if (bed.has(key)) bed.fail_at(bed.raw().get(key), key, "is only used with profile = \"sinusoidal\" (this bed is \"smooth\")");
    }
  }
  bed.reject_unknown_keys();

  if (auto m = c.table("measured")) b.measured = read_measured(*m);
  return b;
}

DamBreakCase read_dam_break(TableReader& c, const std::filesystem::path& base_dir) {
  DamBreakCase d;
  auto column = c.required_table("column");
  d.column_width_m = column.number("width_m", positive("m", 1000.0));
  d.column_height_m = column.number("height_m", positive("m", 1000.0));
  column.reject_unknown_keys();
  auto tank = c.required_table("tank");
  d.tank_length_m = tank.number("length_m", Range{d.column_width_m, 1000.0, true, false, "m, longer than the column"});
  d.tank_height_m = tank.number("height_m", Range{d.column_height_m, 1000.0, false, false, "m, at least the column height"});
  tank.reject_unknown_keys();
  if (auto gate = c.table("gate")) {
    d.gate = gate->choice("type", "instant", {"instant", "lifted"});
    if (d.gate == "lifted") d.gate_lift_speed_m_s = gate->number("lift_speed_m_s", positive("m/s", 1000.0));
    gate->reject_unknown_keys();
  }
  if (auto gauges = c.table("gauges")) {
    d.gauges_x_m = gauges->number_array("x_m", Range{0.0, d.tank_length_m, true, true, "m, inside the tank"});
    gauges->reject_unknown_keys();
  }
  if (auto measured = c.table("measured")) {
    if (measured->has("front_file")) {
      const std::string file = measured->string("front_file");
      std::filesystem::path p(file);
      if (p.is_relative()) p = base_dir / p;
      std::error_code ec;
      if (!std::filesystem::exists(p, ec)) {
        measured->fail_at(measured->raw().get("front_file"), "front_file", "= \"" + file + "\": no such file (looked for '" + p.string() + "')");
      } else if (std::filesystem::is_directory(p, ec)) {
        measured->fail_at(measured->raw().get("front_file"), "front_file", "= \"" + file + "\": '" + p.string() + "' is a directory, not a CSV file");
      } else if (const std::string problem = front_file_problem(p); !problem.empty()) {
        measured->fail_at(measured->raw().get("front_file"), "front_file", "= \"" + file + "\": '" + p.string() + "' " + problem);
      }
      d.measured_front_file = std::filesystem::absolute(p).lexically_normal();
    }
    measured->reject_unknown_keys();
  }
  return d;
}

StillWaterCase read_still_water(TableReader& c) {
  StillWaterCase s;
  auto tank = c.required_table("tank");
  s.tank_length_m = tank.number("length_m", positive("m", 1000.0));
  s.tank_height_m = tank.number("height_m", positive("m", 1000.0));
  tank.reject_unknown_keys();
  auto water = c.required_table("water");
  s.water_depth_m = water.number("depth_m", Range{0.0, s.tank_height_m, true, false, "m, up to the tank height"});
  water.reject_unknown_keys();
  return s;
}

PoiseuilleCase read_poiseuille(TableReader& c) {
  PoiseuilleCase p;
  auto channel = c.required_table("channel");
  p.channel_width_m = channel.number("width_m", positive("m", 100.0));
  p.channel_length_m = channel.number("length_m", positive("m", 1000.0));
  p.body_force_m_s2 = channel.number("body_force_m_s2", positive("m/s^2", 1000.0));
  channel.reject_unknown_keys();
  return p;
}

// `basin_start`: a stilling basin's start (the expected toe), which the upstream section must lie
// upstream of (E1 and the toe search start there) and the downstream section downstream of (y2, E2);
// NaN for other kinds.
std::vector<Section> read_sections(TableReader& c, const toml::array& array, double x_min, double x_max,
                                   double basin_start) {
  std::vector<Section> sections;
  std::set<std::string> names;
  std::size_t index = 0;
  for (const auto& node : array) {
    auto t = c.element(node, "sections", index++);
    Section s;
    s.name = t.string("name");
    // Names become OpenFOAM set names and file names.
    if (!is_plain_name(s.name))
      t.fail_at(t.raw().get("name"), "name", "= \"" + s.name + "\" is not usable as a section name (it names OpenFOAM sets and files): " +
                                                 plain_name_rule);
    if (!names.insert(s.name).second) t.fail_at(t.raw().get("name"), "name", "= \"" + s.name + "\" is used by two sections: names must be unique");
    s.x_m = t.number("x_m", Range{x_min, x_max, false, false, "m, inside the domain"});
    s.role = t.choice("role", "interior", {"upstream", "toe", "interior", "downstream", "gauge"});
    if (std::isfinite(basin_start) && s.role == "upstream" && !(s.x_m < basin_start))
      t.fail_at(t.raw().get("x_m"), "x_m", "= " + util::number_text(s.x_m) + " is out of range for the upstream section \"" + s.name +
                                               "\": must be < " + util::number_text(basin_start) +
                                               " m, the basin start (E1 and the toe search are taken upstream of the jump)");
    if (std::isfinite(basin_start) && s.role == "downstream" && !(s.x_m > basin_start))
      t.fail_at(t.raw().get("x_m"), "x_m", "= " + util::number_text(s.x_m) + " is out of range for the downstream section \"" + s.name +
                                               "\": must be > " + util::number_text(basin_start) +
                                               " m, the basin start (y2 and E2 are taken behind the jump)");
    // E1 and the toe search start at the one upstream section, y2 and E2 come from the one downstream
    // section: a second one of either would be ignored, and a downstream section upstream of the
    // upstream one would turn eta and the jump length inside out.
    for (const Section& earlier : sections) {
      if ((s.role == "upstream" || s.role == "downstream") && earlier.role == s.role)
        t.fail_at(t.raw().get("role"), "role", "= \"" + s.role + "\" is also the role of section \"" + earlier.name +
                                                   "\": at most one section may have it");
      const Section* up = s.role == "upstream" ? &s : (earlier.role == "upstream" ? &earlier : nullptr);
      const Section* down = s.role == "downstream" ? &s : (earlier.role == "downstream" ? &earlier : nullptr);
      if (up && down && up != down && down->x_m <= up->x_m)
        t.fail_at(t.raw().get("x_m"), "x_m", "= " + util::number_text(s.x_m) + " puts the downstream section \"" + down->name +
                                                 "\" (x_m = " + util::number_text(down->x_m) + ") at or upstream of the upstream section \"" +
                                                 up->name + "\" (x_m = " + util::number_text(up->x_m) + "): it must lie downstream");
    }
    t.reject_unknown_keys();
    sections.push_back(s);
  }
  return sections;
}

// How far the inflow buffer's whole rows may miss the inflow depth (relative).
constexpr double kInflowRowsTolerance = 0.02;

// The most fluid particles a 2D case may start with (memory, and weeks of run time on a workstation).
constexpr double max_fluid_particles = 5.0e6;

// Resolution-dependent checks of one case at one resolution level.
void check_resolution(const Case& c, const Resolution& r, double gravity_m_s2, const std::string& file,
                      SpecPurpose purpose = SpecPurpose::run) {
  const auto fail = [&](const std::string& what) {
    throw SpecError(file + ": case \"" + c.id + "\" at resolution \"" + r.name + "\": " + what);
  };
  const double dx = r.particle_spacing_m;
  // The water a run starts with, per metre of width (m^2), for the particle-count bound below.
  double water_area_m2 = 0.0;
  if (const auto* b = c.stilling_basin()) {
    water_area_m2 = (b->upstream_length_m + b->basin_length_m + b->downstream_length_m) *
                    std::max({b->inflow_depth_m, b->tailwater_depth_m, b->bed.height_m});
    if (c.sph.inflow_condition == "piston") {
      // The reservoir (cases/geometry.hpp, add_piston_reservoir): water at most at the energy head
      // E1 = y1 + U1^2/(2g), over reservoir_length_m or the piston's travel plus 2 H_r.
      const double head = b->inflow_depth_m + b->inflow_velocity_m_s * b->inflow_velocity_m_s / (2.0 * gravity_m_s2);
      const double length = c.sph.reservoir_length_m > 0.0
                                ? c.sph.reservoir_length_m
                                : b->inflow_depth_m * b->inflow_velocity_m_s / head * c.run.end_time_s + 2.0 * head;
      water_area_m2 += length * head;
    }
  } else if (const auto* d = c.dam_break()) {
    water_area_m2 = d->column_width_m * d->column_height_m;
  } else if (const auto* s = c.still_water()) {
    water_area_m2 = s->tank_length_m * s->water_depth_m;
  } else if (const auto* p = c.poiseuille()) {
    water_area_m2 = p->channel_length_m * p->channel_width_m;
  }
  // Fluid particles ~ area / dx^2; each takes ~0.3 kB with its neighbour lists and checkpoint copy.
  if (water_area_m2 / (dx * dx) > max_fluid_particles) {
    const double count = std::min(water_area_m2 / (dx * dx), 1e18);  // dx = 1e-200 would square to 0
    fail("resolution." + r.name + ".particle_spacing_m = " + util::number_text(dx) + " gives about " + std::to_string(std::llround(count)) +
         " fluid particles: must be at most " + std::to_string(std::llround(max_fluid_particles)) + ", i.e. particle_spacing_m >= " +
         util::number_text(std::sqrt(water_area_m2 / max_fluid_particles)) + " m");
  }
  if (const auto* b = c.stilling_basin()) {
    if (b->bed.profile == "sinusoidal" && b->bed.wavelength_m < 4.0 * dx - 1e-12) {
      fail("resolution." + r.name + ".particle_spacing_m = " + util::number_text(dx) + " resolves bed.wavelength_m = " + util::number_text(b->bed.wavelength_m) + " with " + util::number_text(b->bed.wavelength_m / dx) + " spacings: must be at least 4, i.e. particle_spacing_m <= " + util::number_text(b->bed.wavelength_m / 4.0) + " m");
    }
    if (b->inflow_depth_m < 5.0 * dx - 1e-12) {
      fail("resolution." + r.name + ".particle_spacing_m = " + util::number_text(dx) + " puts " + util::number_text(b->inflow_depth_m / dx) + " particles across inflow.depth_m = " + util::number_text(b->inflow_depth_m) + ": must be at least 5, i.e. particle_spacing_m <= " + util::number_text(b->inflow_depth_m / 5.0) + " m");
    }
    // The inflow buffer (sph/open_boundaries.hpp) is N = inflow_buffer_rows(y1, dx) whole rows deep and
    // carries the spec's q, so its jet enters N dx deep at q/(N dx): Fr1 = (q^2/(g (N dx)^3))^(1/2) is off
    // by (y1/(N dx))^(3/2) - 1. The rows must match y1 within 2 % (Fr1 within 3 %; E1 within ~3 %).
    const double rows = inflow_buffer_rows(b->inflow_depth_m, dx);
    const double jet_depth = rows * dx;
    if (purpose == SpecPurpose::run && c.sph.inflow_condition == "buffer" &&
        std::abs(jet_depth / b->inflow_depth_m - 1.0) > kInflowRowsTolerance + 1e-12) {
      const double q = unit_discharge(b->inflow_depth_m, b->inflow_velocity_m_s);
      const double fr_spec = froude_number(b->inflow_depth_m, b->inflow_velocity_m_s, gravity_m_s2);
      const double fr_jet = froude_number(jet_depth, q / jet_depth, gravity_m_s2);
      fail("resolution." + r.name + ".particle_spacing_m = " + util::number_text(dx) + " makes the inflow buffer " +
           util::number_text(rows) + " particle rows (" + util::number_text(jet_depth) + " m) deep for inflow.depth_m = " +
           util::number_text(b->inflow_depth_m) + ": the jet would enter with Fr1 = " + rounded_text(fr_jet, 4) + " instead of " +
           rounded_text(fr_spec, 4) + "; the rows must match the inflow depth within 2 %, i.e. particle_spacing_m = inflow.depth_m / N, e.g. " +
           rounded_text(b->inflow_depth_m / rows, 6) + " (N = " + util::number_text(rows) + ") or " +
           rounded_text(b->inflow_depth_m / (rows + 1.0), 6) + " (N = " + util::number_text(rows + 1.0) + ") m");
    }
  } else if (const auto* d = c.dam_break()) {
    if (d->column_width_m < 4.0 * dx) fail("particle_spacing_m = " + util::number_text(dx) + " puts fewer than 4 particles across column.width_m");
  } else if (const auto* s = c.still_water()) {
    if (s->water_depth_m < 4.0 * dx) fail("particle_spacing_m = " + util::number_text(dx) + " puts fewer than 4 particles across water.depth_m");
  } else if (const auto* p = c.poiseuille()) {
    if (p->channel_width_m < 8.0 * dx) fail("particle_spacing_m = " + util::number_text(dx) + " puts fewer than 8 particles across channel.width_m");
    // The periodic length must hold at least 3 kernel supports 2h, h = coef_h sqrt(2) dx.
    const double support = 2.0 * c.sph.coef_h * std::sqrt(2.0) * dx;
    if (p->channel_length_m < 3.0 * support - 1e-12) {
      fail("channel.length_m = " + util::number_text(p->channel_length_m) + " is out of range: the periodic channel must be at least 3 kernel supports long at particle_spacing_m = " + util::number_text(dx) + ", i.e. >= " + util::number_text(3.0 * support) + " m");
    }
  }
}

// [case.tailwater] control = "hold_toe" against the rest of the case (merged settings; a key is named
// where the case sets it, else at [case.tailwater] control; the basin start, where the toe is held,
// lies downstream of the inflow, since domain.upstream_length_m > 0):
//   - SPH steers the outflow buffer's depth, which a tailgate weir or a level held at the downstream
//     section would steer too: those need control = "fixed_depth";
//   - VOF legs: a whole number of output intervals, at most the run; unset: 0.5 s, or the whole
//     number of output intervals that fits a shorter run;
//   - T_V and T_x at least one leg (the volume error decays by (1 - leg / T_V) per leg; T_x below one
//     leg overshoots in a single leg, and the outlet just flips between its clamps).
void check_tailwater_control(TableReader& c, Case& result, StillingBasinCase& b) {
  if (!b.control.holds_toe()) {
    // The legs are the toe control's: a case's own leg length without that control is unused.
    if (auto v = c.table("vof"); v && v->has("tailwater_control_interval_s"))
      v->fail_at(v->raw().get("tailwater_control_interval_s"), "tailwater_control_interval_s",
                 "is only used with [case.tailwater] control = \"hold_toe\" (here \"" + b.control.mode + "\")");
    return;
  }
  auto tail = c.required_table("tailwater");
  const auto fail = [&](const char* table, const char* key, const std::string& what) {
    if (auto t = c.table(table); t && t->has(key)) t->fail_at(t->raw().get(key), key, what);
    tail.fail_at(tail.raw().get("control"), "control",
                 "= \"hold_toe\" (the default for stilling basins) cannot be used with " + std::string(table) + "." + key +
                     " " + what);
  };
  if (result.sph.outflow_condition == "tailgate")
    fail("sph", "outflow_condition", "= \"tailgate\": a weir sets the tailwater itself; use control = \"fixed_depth\" "
                                     "with a tailgate");
  if (result.sph.outflow_level_reference != "outlet")
    fail("sph", "outflow_level_reference", "= \"" + result.sph.outflow_level_reference +
                                               "\": that control holds the tailwater depth, which hold_toe predicts; use "
                                               "control = \"fixed_depth\" to hold a depth");
  double& leg = result.vof.tailwater_control_interval_s;
  const double out = result.run.output_interval_s;
  if (leg == 0.0) {  // unset: 0.5 s, or as many output intervals as fit a shorter run
    leg = std::max(1.0, std::floor(std::min(0.5, result.run.end_time_s) / out + 1e-9)) * out;
  } else {
    const double ratio = leg / out;
    if (std::abs(ratio - std::round(ratio)) > 1e-6 * ratio || std::round(ratio) < 1.0)
      fail("vof", "tailwater_control_interval_s",
           "= " + util::number_text(leg) + " is out of range: must be a whole number of run.output_interval_s (" +
               util::number_text(out) + " s), since the control reads the outputs of each leg");
    if (leg > result.run.end_time_s)
      fail("vof", "tailwater_control_interval_s",
           "= " + util::number_text(leg) + " is out of range: must be <= run.end_time_s (" +
               util::number_text(result.run.end_time_s) + " s), or the control never acts during the run");
  }
  for (const auto& [key, value] : {std::pair<const char*, double>{"volume_hold_time_s", b.control.volume_hold_time_s},
                                   std::pair<const char*, double>{"toe_hold_time_s", b.control.toe_hold_time_s}}) {
    if (!(value < leg)) continue;
    const std::string what = "is out of range: " + std::string(key) + " (" + util::number_text(value) +
                             " s) must be >= the VOF legs' length [vof] tailwater_control_interval_s (" +
                             util::number_text(leg) + " s), or the control overshoots";
    if (tail.has(key)) tail.fail_at(tail.raw().get(key), key, what);
    fail("vof", "tailwater_control_interval_s", "= " + util::number_text(leg) + ": [case.tailwater] " + what);
  }
}

// [case.run], or the study's [run] rule for a stilling basin without one.
void read_case_run(TableReader& c, const Study& study, Case& result) {
  if (auto run = c.table("run")) {
    read_run(*run, result.run);
  } else if (!study.run_rule) {
    c.required_table("run");  // names the missing table
  } else if (const auto* b = result.stilling_basin()) {
    result.run = run_from_sloshing_periods(*study.run_rule, *b, study.fluid.gravity_m_s2);
  } else {
    c.fail_at(nullptr, "run", "is missing: the study's [run] rule sets the run of stilling basins only (it needs a "
                              "sloshing period); give this " + result.kind + " case its [case.run] with end_time_s");
  }
}

// l = c_l y2* of a stilling basin (cases/case_rules.hpp) into sps_mixing_length_m.
void resolve_mixing_length_rule(TableReader& c, const Study& study, Case& result) {
  const double coefficient = result.sph.sps_mixing_length_per_sequent_depth;
  if (coefficient == 0.0) return;
  const auto* b = result.stilling_basin();
  if (!b)
    c.fail_at(nullptr, "sph", "inherits sps_mixing_length_per_sequent_depth = " + util::number_text(coefficient) +
                                  ", a rule for stilling basins (l = c_l y2*): give this " + result.kind +
                                  " case sps_mixing_length_m in [case.sph]");
  result.sph.sps_mixing_length_m = mixing_length_from_sequent_depth(coefficient, *b, study.fluid.gravity_m_s2);
}

// The study's levels scaled to a basin's inflow depth stay within the range a level is read with,
// (0, 10] m (read_resolution), so that the resolved case.toml the solvers read back holds them.
void check_scaled_resolutions(TableReader& c, const Study& study, const Case& result) {
  const auto* b = result.stilling_basin();
  if (!b || !study.resolution_for_inflow_depth_m) return;
  for (const auto& [name, r] : result.resolutions)
    for (const auto& [key, value] : {std::pair{"particle_spacing_m", r.particle_spacing_m},
                                     std::pair{"vof_cell_size_bed_m", r.vof_cell_size_bed_m},
                                     std::pair{"vof_cell_size_bulk_m", r.vof_cell_size_bulk_m}})
      if (!(value > 0.0 && value <= 10.0))
        c.fail_at(nullptr, "resolution." + name + "." + key,
                  "= " + util::number_text(value) + " m, the study's level scaled to this basin's inflow depth (" +
                      util::number_text(b->inflow_depth_m) + " m / [resolution] " + resolution_rule_key + " = " +
                      util::number_text(*study.resolution_for_inflow_depth_m) +
                      " m), is out of range: must be > 0 and <= 10 m; give the case its own [case.resolution." + name + "]");
}

Case read_case(TableReader& c, const Study& study, const SphSettings& sph,
               const VofSettings& vof, const std::map<std::string, Resolution>& resolutions,
               const std::filesystem::path& base_dir) {
  Case result;
  result.id = c.string("id");
  if (!is_plain_name(result.id)) {
    c.fail_at(c.raw().get("id"), "id", "= \"" + result.id + "\" is not usable as a directory name: " + std::string(plain_name_rule));
  }
  // "all" is what `--case all` selects every case with; a case of that name would make it ambiguous.
  if (result.id == "all")
    c.fail_at(c.raw().get("id"), "id", "= \"all\" is reserved: `--case all` selects every case; choose another id");
  result.kind = c.choice("kind", "", {"stilling_basin", "dam_break", "still_water", "poiseuille"}, true);
  result.description = c.string_or("description", "");
  result.sph = sph;
  result.vof = vof;
  if (auto t = c.table("sph")) read_sph(*t, result.sph);
  if (auto t = c.table("vof")) read_vof(*t, result.vof);
  const double g = study.fluid.gravity_m_s2;
  if (result.kind == "stilling_basin") {
    result.data = read_stilling_basin(c, g);
  } else if (result.kind == "dam_break") {
    result.data = read_dam_break(c, base_dir);
  } else if (result.kind == "still_water") {
    result.data = read_still_water(c);
  } else {
    result.data = read_poiseuille(c);
  }
  // The study's levels, scaled to this basin's inflow depth by the study's rule; then the case's own.
  result.resolutions = resolutions;
  if (const auto* b = std::get_if<StillingBasinCase>(&result.data); b && study.resolution_for_inflow_depth_m)
    for (auto& [name, r] : result.resolutions) {
      const double scale = b->inflow_depth_m / *study.resolution_for_inflow_depth_m;
      r.particle_spacing_m *= scale;
      r.vof_cell_size_bed_m *= scale;
      r.vof_cell_size_bulk_m *= scale;
    }
  read_resolutions(c, result.resolutions, false);
  check_scaled_resolutions(c, study, result);
  read_case_run(c, study, result);
  resolve_mixing_length_rule(c, study, result);
  // Sections need the domain, which make_geometry derives; use it (sections are not read yet).
  const CaseGeometry geo = make_geometry(result, study.fluid);
  if (const toml::array* array = c.array_of_tables("sections")) {
    const double basin_start = result.stilling_basin() ? geo.expected_toe_x_m : std::nan("");
    result.sections = read_sections(c, *array, geo.x_min_m, geo.x_max_m, basin_start);
    result.sections_given = true;
  } else if (const auto* b = result.stilling_basin()) {
    result.sections = default_stilling_basin_sections(*b);
    // The downstream section (y2, E2) must lie past the toe, and 3 y2 clear of the outlet.
    const double needed = 3.0 * b->tailwater_depth_m + (b->bed.profile == "sinusoidal" ? b->bed.wavelength_m : 0.0);
    if (result.sections.back().x_m <= b->upstream_length_m + b->tailwater_depth_m) {
      auto domain = c.required_table("domain");
      domain.fail_at(domain.raw().get("basin_length_m"), "basin_length_m",
                     "= " + util::number_text(b->basin_length_m) + " is too short for the default sections: basin_length_m + downstream_length_m must exceed " + util::number_text(needed + b->tailwater_depth_m) + " m (4 tailwater depths" + (b->bed.profile == "sinusoidal" ? std::string(" plus a wavelength") : std::string()) + "), or list [[case.sections]] explicitly");
    }
  } else if (const auto* d = result.dam_break()) {
    for (std::size_t i = 0; i < d->gauges_x_m.size(); ++i) {
      result.sections.push_back({"H" + std::to_string(i + 1), d->gauges_x_m[i], "gauge"});
    }
  }
  if (auto* b = std::get_if<StillingBasinCase>(&result.data)) check_tailwater_control(c, result, *b);
  c.reject_unknown_keys();
  return result;
}

}  // namespace

const Resolution& Case::resolution(const std::string& name) const {
  const auto it = resolutions.find(name);
  if (it == resolutions.end()) {
    std::string known;
    for (const auto& [k, v] : resolutions) known += (known.empty() ? "\"" : ", \"") + k + "\"";
    throw SpecError("case \"" + id + "\": no resolution called \"" + name + "\" (defined: " +
                    (known.empty() ? std::string("none") : known) + ")");
  }
  return it->second;
}

const Case* Study::find_case(const std::string& id) const {
  for (const auto& c : cases) {
    if (c.id == id) return &c;
  }
  return nullptr;
}

Study parse_study(std::string_view toml_text, const std::string& source_name,
                  const std::filesystem::path& base_dir, SpecPurpose purpose) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    throw SpecError(source_name + ":" + std::to_string(e.source().begin.line) + ": not valid TOML: " + std::string(e.description()));
  }
  Study study;
  study.source_file = source_name;
  TableReader top(root, source_name, "", "");

  auto head = top.required_table("study");
  study.name = head.string("name");
  // The name goes into the comments of the generated OpenFOAM dictionaries and into reports: one line.
  if (study.name.empty() || study.name.size() > 200 ||
      std::any_of(study.name.begin(), study.name.end(),
                  [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; }))
    head.fail_at(head.raw().get("name"), "name",
                 "is not usable: a study name is 1 to 200 characters on one line, with no control characters "
                 "(newlines, tabs), since it is written into the comments of the generated OpenFOAM files (here " +
                 std::to_string(study.name.size()) + " characters)");
  study.description = head.string_or("description", "");
  study.citations = head.string_array("citations");
  head.reject_unknown_keys();

  if (auto fluid = top.table("fluid")) {
    study.fluid.density_kg_m3 = fluid->number_or("density_kg_m3", study.fluid.density_kg_m3, positive("kg/m^3", 1e5));
    study.fluid.kinematic_viscosity_m2_s = fluid->number_or("kinematic_viscosity_m2_s", study.fluid.kinematic_viscosity_m2_s, positive("m^2/s", 1.0));
    study.fluid.gravity_m_s2 = fluid->number_or("gravity_m_s2", study.fluid.gravity_m_s2, positive("m/s^2", 100.0));
    fluid->reject_unknown_keys();
  }
  if (auto run = top.table("run")) study.run_rule = read_run_rule(*run);
  SphSettings sph;
  if (auto t = top.table("sph")) read_sph(*t, sph);
  VofSettings vof;
  if (auto t = top.table("vof")) read_vof(*t, vof);
  std::map<std::string, Resolution> resolutions;
  if (auto levels = top.table("resolution"); levels && levels->has(resolution_rule_key))
    study.resolution_for_inflow_depth_m = levels->number(resolution_rule_key, positive("m", 10.0));
  read_resolutions(top, resolutions, true);
  if (resolutions.empty()) {
    top.fail_at(nullptr, "resolution", "is missing: define at least one level, e.g. [resolution.quick] with particle_spacing_m, vof_cell_size_bed_m and vof_cell_size_bulk_m");
  }

  const toml::array* cases = top.array_of_tables("case");
  if (!cases || cases->empty()) top.fail_at(nullptr, "case", "is missing: a study needs at least one [[case]]");
  std::set<std::string> ids;
  std::size_t index = 0;
  for (const auto& node : *cases) {
    TableReader c = top.element(node, "case", index);
    // Name the case in every message about it once its id is known.
    std::string id;
    if (const auto* id_node = node.as_table()->get("id"); id_node && id_node->is_string()) id = *id_node->value<std::string>();
    TableReader named(*node.as_table(), source_name, id.empty() ? "" : "case \"" + id + "\": ", "");
    Case parsed = read_case(id.empty() ? c : named, study, sph, vof, resolutions, base_dir);
    if (!ids.insert(parsed.id).second) {
      named.fail_at(node.as_table()->get("id"), "id", "= \"" + parsed.id + "\" is used by two cases: ids must be unique");
    }
    for (const auto& [name, r] : parsed.resolutions) check_resolution(parsed, r, study.fluid.gravity_m_s2, source_name, purpose);
    study.cases.push_back(std::move(parsed));
    ++index;
  }
  top.reject_unknown_keys();
  return study;
}

Study load_study(const std::filesystem::path& file, SpecPurpose purpose) {
  // A directory opens as an empty stream on Linux and would be reported as a spec without [study].
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw SpecError(file.string() + ": is a directory, not a study file (a .toml spec or a generated case.toml)");
  // A pipe or a device would block the open or be read for ever.
  if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
    throw SpecError(file.string() + ": is not a regular file (a pipe or a device?), not a study file (a .toml spec "
                    "or a generated case.toml)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SpecError(file.string() + ": cannot open the study file");
  // At most max_input_file_bytes.
  std::string text;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_input_file_bytes)
      throw SpecError(file.string() + ": is larger than 16 MiB, not a study file (a .toml spec or a generated case.toml)");
  }
  const auto base = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  Study study = parse_study(text, file.string(), base, purpose);
  study.source_file = file;
  return study;
}

Study load_embedded_default_study() {
  // Relative data paths of the embedded study resolve against the source tree's cases/ folder.
  return parse_study(embedded_default_study_text(), "<embedded cases/ead2002.toml>", std::filesystem::path("cases"));
}

void validate_for_resolution(const Study& study, const Case& c, const std::string& resolution) {
  if (c.resolutions.count(resolution) == 0) {
    try {
      (void)c.resolution(resolution);  // its message lists the resolutions the case has
    } catch (const SpecError& e) {
      throw SpecError(study.source_file.string() + ": " + e.what());
    }
  }
  check_resolution(c, c.resolution(resolution), study.fluid.gravity_m_s2, study.source_file.string());
}

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", ch);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

// Writes "key = value" lines of a flat TOML table.
class TomlWriter {
 public:
  void header(const std::string& h) { out_ << "\n" << h << "\n"; }
  void num(const std::string& k, double v) { out_ << k << " = " << toml_number(v) << "\n"; }
  void integer(const std::string& k, long v) { out_ << k << " = " << v << "\n"; }
  void str(const std::string& k, const std::string& v) { out_ << k << " = " << quoted(v) << "\n"; }
  void opt(const std::string& k, const std::optional<double>& v) {
    if (v) num(k, *v);
  }
  void strings(const std::string& k, const std::vector<std::string>& v) {
    out_ << k << " = [";
    for (std::size_t i = 0; i < v.size(); ++i) out_ << (i ? ", " : "") << quoted(v[i]);
    out_ << "]\n";
  }
  void numbers(const std::string& k, const std::vector<double>& v) {
    out_ << k << " = [";
    for (std::size_t i = 0; i < v.size(); ++i) out_ << (i ? ", " : "") << toml_number(v[i]);
    out_ << "]\n";
  }
  void comment(const std::string& c) { out_ << "# " << c << "\n"; }
  std::string text() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

void write_sph(TomlWriter& w, const SphSettings& s) {
  w.str("kernel", s.kernel);
  w.str("viscosity", s.viscosity);
  // Only the parameters of the chosen models (read_sph rejects the others).
  if (s.viscosity == "artificial") {
    if (s.artificial_viscosity_nu_m2_s > 0.0) w.num("artificial_viscosity_nu_m2_s", s.artificial_viscosity_nu_m2_s);
    else w.num("artificial_viscosity_alpha", s.artificial_viscosity_alpha);
    w.num("artificial_viscosity_wall_factor", s.artificial_viscosity_wall_factor);
  } else {
    if (s.sps_mixing_length_m > 0.0) {
      if (s.sps_mixing_length_per_sequent_depth > 0.0)
        w.comment("from sps_mixing_length_per_sequent_depth = " + toml_number(s.sps_mixing_length_per_sequent_depth) +
                  " (l = c_l y2*)");
      w.num("sps_mixing_length_m", s.sps_mixing_length_m);
      w.str("sps_wall_distance", s.sps_wall_distance);
    } else {
      w.num("sps_smagorinsky_constant", s.sps_smagorinsky_constant);
    }
    w.num("sps_blin_constant", s.sps_blin_constant);
    w.str("viscous_wall_condition", s.viscous_wall_condition);
  }
  w.str("boundary", s.boundary);
  w.str("density_diffusion", s.density_diffusion);
  if (s.density_diffusion != "none") w.num("density_diffusion_coefficient", s.density_diffusion_coefficient);
  if (s.sound_speed_m_s > 0.0) {
    w.num("sound_speed_m_s", s.sound_speed_m_s);
  } else {
    w.num("sound_speed_coefficient", s.sound_speed_coefficient);
    w.num("sound_speed_min_flow_ratio", s.sound_speed_min_flow_ratio);
  }
  w.num("cfl_number", s.cfl_number);
  w.num("coef_h", s.coef_h);
  w.str("time_integrator", s.time_integrator);
  if (s.time_integrator == "verlet") w.integer("verlet_euler_interval", s.verlet_euler_interval);
  w.integer("boundary_layers", s.boundary_layers);
  w.integer("open_boundary_layers", s.open_boundary_layers);
  w.str("inflow_condition", s.inflow_condition);
  if (s.inflow_condition == "piston") {
    w.num("sluice_opening_m", s.sluice_opening_m);
    w.num("reservoir_length_m", s.reservoir_length_m);
    w.num("piston_level_gain_per_s", s.piston_level_gain_per_s);
  }
  w.str("outflow_condition", s.outflow_condition);
  if (s.outflow_condition == "tailgate") w.num("tailgate_height_m", s.tailgate_height_m);
  w.str("outflow_level_reference", s.outflow_level_reference);
  if (s.outflow_level_reference == "downstream_section") w.num("outflow_level_time_s", s.outflow_level_time_s);
  w.str("particle_shifting", s.particle_shifting);
  if (s.particle_shifting != "none") {
    w.num("particle_shifting_coefficient", s.particle_shifting_coefficient);
    w.num("particle_shifting_surface_threshold", s.particle_shifting_surface_threshold);
    w.str("particle_shifting_correction", s.particle_shifting_correction);
  }
  w.num("max_density_variation", s.max_density_variation);
  w.num("checkpoint_interval_wall_s", s.checkpoint_interval_wall_s);
}

void write_vof(TomlWriter& w, const VofSettings& v) {
  w.str("turbulence_model", v.turbulence_model);
  w.str("turbulence_stabilization", v.turbulence_stabilization);
  w.num("max_courant", v.max_courant);
  w.num("max_alpha_courant", v.max_alpha_courant);
  w.num("max_time_step_s", v.max_time_step_s);
  w.str("mesh_strategy", v.mesh_strategy);
  w.num("surface_refinement_band_m", v.surface_refinement_band_m);
  if (v.tailwater_control_interval_s > 0.0) w.num("tailwater_control_interval_s", v.tailwater_control_interval_s);
}

}  // namespace

void write_resolved_case(const Study& study, const Case& c, const std::string& resolution,
                         const std::filesystem::path& out_file) {
  // The measured data travel with the case: copied beside it first (so the case file never names a
  // file that is not there) and named relative to it, so the run directory can be moved and its
  // text does not depend on where the spec was read from.
  if (const auto* d = c.dam_break(); d != nullptr && !d->measured_front_file.empty()) {
    const std::filesystem::path copy = out_file.parent_path() / kResolvedFrontFileName;
    std::error_code ec;
    if (!std::filesystem::equivalent(d->measured_front_file, copy, ec))
      util::write_file_atomically(copy, util::read_text_file(d->measured_front_file));
  }
  util::write_file_atomically(out_file, resolved_case_text(study, c, resolution));
}

std::string resolved_case_text(const Study& study, const Case& c, const std::string& resolution) {
  const Resolution& r = c.resolution(resolution);
  TomlWriter w;
  w.comment("Resolved by hydrojump from " + study.source_file.string() + ": case \"" + c.id +
            "\" at resolution \"" + resolution + "\", every default made explicit.");
  w.header("[study]");
  w.str("name", study.name);
  w.str("description", study.description);
  w.strings("citations", study.citations);
  w.header("[fluid]");
  w.num("density_kg_m3", study.fluid.density_kg_m3);
  w.num("kinematic_viscosity_m2_s", study.fluid.kinematic_viscosity_m2_s);
  w.num("gravity_m_s2", study.fluid.gravity_m_s2);
  w.header("[sph]");
  write_sph(w, c.sph);
  w.header("[vof]");
  write_vof(w, c.vof);
  w.header("[resolution." + r.name + "]");
  w.num("particle_spacing_m", r.particle_spacing_m);
  w.num("vof_cell_size_bed_m", r.vof_cell_size_bed_m);
  w.num("vof_cell_size_bulk_m", r.vof_cell_size_bulk_m);
  w.header("[[case]]");
  w.str("id", c.id);
  w.str("kind", c.kind);
  w.str("description", c.description);
  w.header("[case.run]");
  w.num("end_time_s", c.run.end_time_s);
  w.num("output_interval_s", c.run.output_interval_s);
  w.num("average_start_s", c.run.average_start_s);
  w.num("average_end_s", c.run.average_end_s);
  if (const auto* b = c.stilling_basin()) {
    w.header("[case.bed]");
    w.str("profile", b->bed.profile);
    if (b->bed.profile == "sinusoidal") {
      w.num("wavelength_m", b->bed.wavelength_m);
      w.num("height_m", b->bed.height_m);
      w.num("reach_start_m", b->bed.reach_start_m);
      w.num("reach_end_m", b->bed.reach_end_m);
    }
    w.header("[case.inflow]");
    w.num("depth_m", b->inflow_depth_m);
    w.num("velocity_m_s", b->inflow_velocity_m_s);
    w.opt("discharge_m2_s", b->stated_discharge_m2_s);
    w.opt("froude", b->stated_froude);
    w.header("[case.tailwater]");
    if (b->tailwater_rule == "belanger") w.comment("from rule = \"belanger\" (y2* of the inflow)");
    w.num("depth_m", b->tailwater_depth_m);
    w.str("control", b->control.mode);
    if (b->control.holds_toe()) {
      w.num("volume_hold_time_s", b->control.volume_hold_time_s);
      w.num("toe_hold_time_s", b->control.toe_hold_time_s);
    }
    w.header("[case.domain]");
    w.num("upstream_length_m", b->upstream_length_m);
    w.num("basin_length_m", b->basin_length_m);
    w.num("downstream_length_m", b->downstream_length_m);
    w.num("air_height_m", b->air_height_m);
    w.opt("initial_toe_x_m", b->initial_toe_x_m);
    const auto& m = b->measured;
    w.header("[case.measured]");
    w.opt("sequent_depth_m", m.sequent_depth_m);
    w.opt("jump_length_m", m.jump_length_m);
    w.opt("roller_length_m", m.roller_length_m);
    w.opt("eta_percent", m.eta_percent);
    w.opt("eta_smooth_percent", m.eta_smooth_percent);
    w.opt("published_sph_eta_percent", m.published_sph_eta_percent);
    if (!m.source.empty()) w.str("source", m.source);
    if (!m.note.empty()) w.str("note", m.note);
  } else if (const auto* d = c.dam_break()) {
    w.header("[case.column]");
    w.num("width_m", d->column_width_m);
    w.num("height_m", d->column_height_m);
    w.header("[case.tank]");
    w.num("length_m", d->tank_length_m);
    w.num("height_m", d->tank_height_m);
    w.header("[case.gate]");
    w.str("type", d->gate);
    if (d->gate == "lifted") w.num("lift_speed_m_s", d->gate_lift_speed_m_s);
    if (!d->gauges_x_m.empty()) {
      w.header("[case.gauges]");
      w.numbers("x_m", d->gauges_x_m);
    }
    if (!d->measured_front_file.empty()) {
      w.header("[case.measured]");
      w.str("front_file", kResolvedFrontFileName);  // the copy write_resolved_case puts beside it
    }
  } else if (const auto* s = c.still_water()) {
    w.header("[case.tank]");
    w.num("length_m", s->tank_length_m);
    w.num("height_m", s->tank_height_m);
    w.header("[case.water]");
    w.num("depth_m", s->water_depth_m);
  } else if (const auto* p = c.poiseuille()) {
    w.header("[case.channel]");
    w.num("width_m", p->channel_width_m);
    w.num("length_m", p->channel_length_m);
    w.num("body_force_m_s2", p->body_force_m_s2);
  }
  for (const auto& s : c.sections) {
    w.header("[[case.sections]]");
    w.str("name", s.name);
    w.num("x_m", s.x_m);
    w.str("role", s.role);
  }
  return w.text();
}

}  // namespace hydrojump::cases
