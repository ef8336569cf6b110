#include "reference/tailwater_control.hpp"

#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.hpp"
#include "util/csv_table.hpp"
#include "cases/hydraulics.hpp"
#include "cases/jump_toe.hpp"
#include "reference/foam_dictionary.hpp"
#include "util/fingerprint.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

TailwaterControlLaw tailwater_control_law(const cases::Case& c, const cases::CaseGeometry& geo) {
  TailwaterControlLaw law;
  law.gains = cases::toe_hold_gains(c, geo);
  const cases::InflowBoundary& in = geo.inflows.front();
  law.discharge_m2_s = cases::unit_discharge(in.depth_m, in.velocity_m_s);
  law.toe_search_from_m = geo.x_min_m;
  for (const cases::Section& s : geo.sections) {
    if (s.role == cases::SectionRole::upstream) law.toe_search_from_m = s.x_m;
  }
  law.interval_s = c.vof.tailwater_control_interval_s;
  law.output_interval_s = c.run.output_interval_s;
  law.volume_hold_time_s = c.stilling_basin()->control.volume_hold_time_s;
  return law;
}

// P = k_p (y2* - y1) (x_toe - x_target)
TailwaterControlStep tailwater_control_step(const TailwaterControlLaw& law, std::optional<double> previous_integral,
                                            double time_s, double leg_s, const std::vector<double>& output_toes_x_m,
                                            double water_volume_m2) {
  TailwaterControlStep step;
  step.time_s = time_s;
  step.water_volume_m2 = water_volume_m2;
  double sum = 0.0;
  for (double x : output_toes_x_m) {
    if (!std::isfinite(x)) continue;
    sum += x;
    ++step.toe_outputs;
  }
  step.toe_x_m = step.toe_outputs > 0 ? sum / step.toe_outputs : std::numeric_limits<double>::quiet_NaN();
  // V*(n) of cases/toe_hold_law.hpp, from I(-1) = V(0) - P(0) at the first step
  const double first_integral = water_volume_m2 - cases::toe_hold_proportional(law.gains, step.toe_x_m);
  step.volume_target_m2 =
      cases::toe_hold_volume_target(law.gains, previous_integral.value_or(first_integral), step.toe_x_m, leg_s).volume_target_m2;
  const double y2 = law.gains.tailwater_depth_m;
  // Umean = (q + (V - V*) / T_V) / y2*, within [1/4, 4] q / y2*
  const double q = law.discharge_m2_s;
  const double umean = (q + (water_volume_m2 - step.volume_target_m2) / law.volume_hold_time_s) / y2;
  step.outlet_mean_velocity_m_s = std::clamp(umean, 0.25 * q / y2, 4.0 * q / y2);
  return step;
}

double toe_on_surface(const std::vector<double>& x_m, const std::vector<double>& z_m, double x_from, double x_to,
                      double inflow_depth_m) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double spacing = 0.25 * inflow_depth_m;
  if (!(x_to > x_from) || !(spacing > 0.0)) return nan;
  const auto stations = static_cast<std::size_t>(std::floor((x_to - x_from) / spacing)) + 1;
  std::vector<double> x(stations), zeta(stations, nan);
  for (std::size_t k = 0; k < stations; ++k) x[k] = x_from + static_cast<double>(k) * spacing;
  for (std::size_t i = 0; i < x_m.size() && i < z_m.size(); ++i) {
    const double k = std::round((x_m[i] - x_from) / spacing);
    if (!(k >= 0.0) || k >= static_cast<double>(stations) || !std::isfinite(z_m[i])) continue;
    double& z = zeta[static_cast<std::size_t>(k)];
    if (std::isnan(z) || z_m[i] > z) z = z_m[i];
  }
  const std::size_t i = cases::find_jump_toe(x, zeta, x_from, inflow_depth_m, cases::ToeCriterion{});
  return i < x.size() ? x[i] : nan;
}

void read_surface_points(const std::filesystem::path& vtp, std::vector<double>& x_m, std::vector<double>& z_m) {
  x_m.clear();
  z_m.clear();
  if (!std::filesystem::exists(vtp)) throw std::runtime_error(vtp.string() + ": no such file");
  vtkNew<vtkXMLPolyDataReader> reader;
  if (!reader->CanReadFile(vtp.string().c_str()))  // checked quietly, before VTK prints its own parse errors
    throw std::runtime_error(vtp.string() + ": not a VTK XML PolyData (.vtp) file");
  reader->SetFileName(vtp.string().c_str());
  reader->Update();
  vtkPolyData* surface = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || surface == nullptr) throw std::runtime_error(vtp.string() + ": not a readable VTK PolyData file");
  vtkPoints* points = surface->GetPoints();
  const vtkIdType n = points ? points->GetNumberOfPoints() : 0;
  x_m.reserve(static_cast<std::size_t>(n));
  z_m.reserve(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    points->GetPoint(i, p);
    x_m.push_back(p[0]);
    z_m.push_back(p[1]);  // OpenFOAM's y is the vertical
  }
}

namespace {

// Where the value of Umean stands in the `outlet { ... }` entry of boundaryField: [begin, end).
struct UmeanEntry {
  std::size_t value_begin = 0;
  std::size_t value_end = 0;
};

bool is_word_char(char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '.'; }

// Position of `word` as a whole token in text[from, to), or npos.
std::size_t find_token(const std::string& text, const std::string& word, std::size_t from, std::size_t to) {
  for (std::size_t p = text.find(word, from); p != std::string::npos && p < to; p = text.find(word, p + 1)) {
    const bool before = p == 0 || !is_word_char(text[p - 1]);
    const bool after = p + word.size() >= text.size() || !is_word_char(text[p + word.size()]);
    if (before && after) return p;
  }
  return std::string::npos;
}

UmeanEntry find_umean(const std::string& text, const fs::path& file) {
  const auto fail = [&](const std::string& what) -> UmeanEntry {
    throw std::runtime_error(file.string() + ": " + what + " (the tailwater control rewrites the outlet's Umean "
                             "of an outletPhaseMeanVelocity condition in an uncompressed field file)");
  };
  const std::size_t boundary = find_token(text, "boundaryField", 0, text.size());
  if (boundary == std::string::npos) return fail("no boundaryField");
  // The token `outlet` followed by '{' (not a word in a comment or a value).
  std::size_t open = std::string::npos;
  for (std::size_t at = find_token(text, "outlet", boundary, text.size()); at != std::string::npos;
       at = find_token(text, "outlet", at + 1, text.size())) {
    const std::size_t next = text.find_first_not_of(" \t\r\n", at + 6);
    if (next != std::string::npos && text[next] == '{') {
      open = next;
      break;
    }
  }
  if (open == std::string::npos) return fail("no outlet entry in boundaryField");
  // The entry's closing brace (its value list holds parentheses, not braces).
  int depth = 0;
  std::size_t close = std::string::npos;
  for (std::size_t p = open; p < text.size(); ++p) {
    if (text[p] == '{') ++depth;
    if (text[p] == '}' && --depth == 0) {
      close = p;
      break;
    }
  }
  if (close == std::string::npos) return fail("the outlet entry is not closed");
  const std::size_t key = find_token(text, "Umean", open, close);
  if (key == std::string::npos) return fail("the outlet entry has no Umean");
  const std::size_t value_begin = text.find_first_not_of(" \t", key + 5);
  const std::size_t value_end = text.find(';', value_begin);
  if (value_begin == std::string::npos || value_end == std::string::npos || value_end > close) {
    return fail("the outlet's Umean has no value");
  }
  return UmeanEntry{value_begin, value_end};
}

}  // namespace

namespace {
std::string read_field_file(const fs::path& u_file) {
  if (!fs::is_regular_file(u_file)) throw std::runtime_error(u_file.string() + ": no such field file");
  return util::read_text_file(u_file);
}
}  // namespace

double read_outlet_mean_velocity(const fs::path& u_file) {
  const std::string text = read_field_file(u_file);
  const UmeanEntry e = find_umean(text, u_file);
  const std::string value = text.substr(e.value_begin, e.value_end - e.value_begin);
  const double v = util::csv_number(value);
  if (!std::isfinite(v)) throw std::runtime_error(u_file.string() + ": the outlet's Umean \"" + value + "\" is not a number");
  return v;
}

void write_outlet_mean_velocity(const fs::path& u_file, double umean_m_s) {
  if (!std::isfinite(umean_m_s)) throw std::invalid_argument("outlet Umean must be finite");
  std::string text = read_field_file(u_file);
  const UmeanEntry e = find_umean(text, u_file);
  if (!std::isfinite(util::csv_number(text.substr(e.value_begin, e.value_end - e.value_begin)))) {
    throw std::runtime_error(u_file.string() + ": the outlet's Umean \"" +
                             text.substr(e.value_begin, e.value_end - e.value_begin) + "\" is not a number");
  }
  text.replace(e.value_begin, e.value_end - e.value_begin, foam::format_number(umean_m_s));
  util::write_file_atomically(u_file, text);
}

namespace {
const char* const log_header = "time_s,toe_x_m,toe_outputs,water_volume_m2,volume_target_m2,outlet_mean_velocity_m_s";
}

std::vector<TailwaterControlStep> read_tailwater_control_log(const fs::path& case_dir) {
  std::vector<TailwaterControlStep> steps;
  const fs::path file = case_dir / tailwater_control_log;
  if (!fs::exists(file)) return steps;
  const util::CsvTable table = util::read_csv_table(file);
  const auto col = [&](const char* name) {
    const auto c = table.column(name);
    if (!c) throw std::runtime_error(file.string() + ": no column \"" + name + "\" (expected " + log_header + ")");
    return *c;
  };
  const std::size_t t = col("time_s"), x = col("toe_x_m"), n = col("toe_outputs"), v = col("water_volume_m2"),
                    vt = col("volume_target_m2"), u = col("outlet_mean_velocity_m_s");
  // The log is only ever rewritten whole (append_tailwater_control_log), so a row of another width or
  // without its numbers is damage, not a torn last line: named, not skipped.
  std::size_t line = 1;
  for (const auto& row : table.rows) {
    ++line;
    const auto damaged = [&](const std::string& what) {
      return std::runtime_error(file.string() + ":" + std::to_string(line) + ": " + what + " (expected " + log_header +
                                ", the numbers finite except toe_x_m, which is nan for a leg without a toe)");
    };
    if (row.size() != table.header.size())
      throw damaged(std::to_string(row.size()) + " columns where the header has " + std::to_string(table.header.size()));
    TailwaterControlStep s;
    s.time_s = util::csv_number(row[t]);
    s.toe_x_m = util::csv_number(row[x]);
    const double outputs = util::csv_number(row[n]);
    s.toe_outputs = std::isfinite(outputs) && outputs >= 0.0 && outputs < 1e9 ? static_cast<int>(outputs) : 0;
    s.water_volume_m2 = util::csv_number(row[v]);
    s.volume_target_m2 = util::csv_number(row[vt]);
    s.outlet_mean_velocity_m_s = util::csv_number(row[u]);
    if (!std::isfinite(s.time_s) || !std::isfinite(s.water_volume_m2) || !std::isfinite(s.volume_target_m2) ||
        !std::isfinite(s.outlet_mean_velocity_m_s) || !std::isfinite(outputs))
      throw damaged("a row with a value that is not a finite number");
    if (!steps.empty() && !(s.time_s > steps.back().time_s))
      throw damaged("time_s = " + row[t] + " does not follow the previous row's " + foam::format_number(steps.back().time_s));
    steps.push_back(s);
  }
  return steps;
}

namespace {
std::string log_row(const TailwaterControlStep& step) {
  std::ostringstream row;
  row << std::setprecision(10) << step.time_s << ',' << step.toe_x_m << ',' << step.toe_outputs << ','
      << step.water_volume_m2 << ',' << step.volume_target_m2 << ',' << step.outlet_mean_velocity_m_s << '\n';
  return row.str();
}

void write_log(const fs::path& case_dir, const std::vector<TailwaterControlStep>& rows) {
  std::string text = std::string(log_header) + "\n";
  for (const TailwaterControlStep& r : rows) text += log_row(r);
  util::write_file_atomically(case_dir / tailwater_control_log, text);
}
}  // namespace

void append_tailwater_control_log(const fs::path& case_dir, const TailwaterControlStep& step) {
  std::vector<TailwaterControlStep> rows = read_tailwater_control_log(case_dir);
  rows.push_back(step);
  write_log(case_dir, rows);
}

void truncate_tailwater_control_log(const fs::path& case_dir, std::optional<double> time_s) {
  const fs::path file = case_dir / tailwater_control_log;
  if (!fs::exists(file)) return;
  if (!time_s) {
    fs::remove(file);
    return;
  }
  std::vector<TailwaterControlStep> rows = read_tailwater_control_log(case_dir);
  const std::size_t before = rows.size();
  rows.erase(std::remove_if(rows.begin(), rows.end(), [&](const TailwaterControlStep& r) { return r.time_s > *time_s + 1e-9; }),
             rows.end());
  if (rows.size() != before) write_log(case_dir, rows);
}

}  // namespace hydrojump::reference
