// The runner's edits of system/controlDict: the endTime entry (--end-time), and the controlDict of one
// leg of the solver, which replaces the case's for the leg's duration.
//
// interFoam counts its write times, and its function objects their sampling times, from the time it
// starts at (Time and timeControl in OpenFOAM v1912):
//
//   write index = floor((t - t_start + dt/2) / writeInterval)
//
// so a run resumed from a time off the grid (a stop on Ctrl-C writes the current time, e.g. 4.41491 s)
// would write every later output shifted (4.51491, 4.61491 s, ...). The legs of plan_solver_legs
// (runner.hpp) avoid that. A leg's controlDict replaces the case's for its duration: the case's is
// kept as system/controlDict.hydrojump-original and put back when the leg ends (or fails), or by the
// next `hydrojump vof` if the runner was killed meanwhile.
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <regex>
#include <sstream>
#include <utility>

#include "reference/runner_parts.hpp"
#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

namespace {

// The `endTime` entry of CASE/system/controlDict (what interFoam obeys): the file's text and where
// the entry's value lies in it.
struct EndTimeEntry {
  std::string text;
  std::size_t value_begin = 0, value_length = 0;
  double value_s = 0.0;
};

// The entry in `text`, the controlDict `file` (named in errors).
EndTimeEntry parse_end_time_entry(std::string text, const fs::path& file) {
  static const std::regex entry(R"((^|\n)[ \t]*endTime[ \t]+([^;\n]+);)");
  EndTimeEntry e;
  e.text = std::move(text);
  std::smatch m;
  if (!std::regex_search(e.text, m, entry)) {
    throw OpenFoamError(file.string() + ": no `endTime` entry (regenerate the case with `hydrojump generate`)");
  }
  e.value_begin = static_cast<std::size_t>(m.position(2));
  e.value_length = static_cast<std::size_t>(m.length(2));
  const std::string value = m[2].str();
  char* end = nullptr;
  e.value_s = std::strtod(value.c_str(), &end);
  if (end == value.c_str() || !(e.value_s > 0.0)) {
    throw OpenFoamError(file.string() + ": endTime \"" + value + "\" is not a positive number of seconds");
  }
  return e;
}

EndTimeEntry read_end_time_entry(const fs::path& dir) {
  const fs::path file = dir / "system/controlDict";
  return parse_end_time_entry(util::read_text_file(file), file);
}

// A controlDict value as written by the runner: 12 significant digits.
std::string control_dict_number(double v) {
  std::ostringstream s;
  s << std::setprecision(12) << v;
  return s.str();
}

// The text with that entry's value set to `end_time_s` (the rest, hand edits included, kept).
std::string with_end_time(const EndTimeEntry& e, double end_time_s) {
  return e.text.substr(0, e.value_begin) + control_dict_number(end_time_s) +
         e.text.substr(e.value_begin + e.value_length);
}

// The top-level entry `key` of a controlDict's text (the part before `functions`, where the function
// objects' own writeControl and writeInterval are), or nothing.
std::optional<std::string> top_level_entry(const std::string& text, const std::string& key) {
  static const std::regex functions(R"((^|\n)[ \t]*functions\b)");
  std::smatch f;
  const std::string head = std::regex_search(text, f, functions) ? text.substr(0, static_cast<std::size_t>(f.position(0))) : text;
  const std::regex entry("(^|\\n)[ \\t]*" + key + "[ \\t]+([^;\\n]+);");
  std::smatch m;
  if (!std::regex_search(head, m, entry)) return std::nullopt;
  return m[2].str();
}

// Whether a writeControl counts simulated time (so that its writeInterval is in seconds).
bool counts_simulated_time(const std::string& write_control) {
  return write_control == "adjustable" || write_control == "adjustableRunTime" || write_control == "runTime";
}

// The dictionary block around `pos` in a controlDict's text: [begin, end) between its braces, or the
// whole text at the top level.
std::pair<std::size_t, std::size_t> enclosing_block(const std::string& text, std::size_t pos) {
  std::size_t begin = 0, end = text.size();
  int depth = 0;
  for (std::size_t i = pos; i-- > 0;) {
    if (text[i] == '}') ++depth;
    if (text[i] == '{' && depth-- == 0) {
      begin = i + 1;
      break;
    }
  }
  depth = 0;
  for (std::size_t i = pos; i < text.size(); ++i) {
    if (text[i] == '{') ++depth;
    if (text[i] == '}' && depth-- == 0) {
      end = i;
      break;
    }
  }
  return {begin, end};
}

// The writeControl of the block [begin, end) itself (not of a block nested in it), or nothing.
std::optional<std::string> block_write_control(const std::string& text, std::size_t begin, std::size_t end) {
  static const std::regex entry(R"((^|[\n{;])[ \t]*writeControl[ \t]+([^;\n]+);)");
  const std::string block = text.substr(begin, end - begin);
  for (auto it = std::sregex_iterator(block.begin(), block.end(), entry); it != std::sregex_iterator(); ++it) {
    int depth = 0;
    const auto keyword = static_cast<std::size_t>(it->position(0) + (*it)[1].length());  // past the '{' or ';' before it
    for (std::size_t i = 0; i < keyword; ++i) {
      if (block[i] == '{') ++depth;
      if (block[i] == '}') --depth;
    }
    if (depth == 0) return (*it)[2].str();
  }
  return std::nullopt;
}

}  // namespace

// The controlDict of one leg: endTime = the leg's end, and when the leg sets its own write interval,
// every writeInterval equal to the case's (the top-level one and the function objects') set to it where
// it counts simulated time (writeControl adjustable, adjustableRunTime or runTime in the same block; a
// function object's writeInterval under timeStep, its default, counts time steps and is kept); the rest
// of the text is kept.
std::string leg_control_dict(const std::string& text, const fs::path& file, const SolverLeg& leg) {
  std::string result;
  std::size_t copied = 0;
  const auto interval_text = top_level_entry(text, "writeInterval");
  const double interval = interval_text ? std::strtod(interval_text->c_str(), nullptr) : 0.0;
  if (leg.write_interval_s && interval > 0.0) {
    static const std::regex entry(R"((^|\n)[ \t]*writeInterval[ \t]+([^;\n]+);)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it) {
      const std::smatch& m = *it;
      if (std::abs(std::strtod(m[2].str().c_str(), nullptr) - interval) > 1e-9 * interval) continue;
      const auto value_pos = static_cast<std::size_t>(m.position(2));
      const auto [begin, end] = enclosing_block(text, value_pos);
      const auto control = block_write_control(text, begin, end);
      if (!control || !counts_simulated_time(*control)) continue;
      result += text.substr(copied, value_pos - copied) + control_dict_number(*leg.write_interval_s);
      copied = value_pos + static_cast<std::size_t>(m.length(2));
    }
  }
  return with_end_time(parse_end_time_entry(result + text.substr(copied), file), leg.end_s);
}

std::optional<std::string> control_dict_after_leg(const std::string& original, const std::string& leg_text,
                                                  const std::string& current, const fs::path& file, const SolverLeg& leg) {
  if (current == leg_text) return original;
  if (leg.write_interval_s) return std::nullopt;
  const EndTimeEntry case_end = parse_end_time_entry(original, file);
  const EndTimeEntry edited = parse_end_time_entry(current, file);
  return edited.text.substr(0, edited.value_begin) + case_end.text.substr(case_end.value_begin, case_end.value_length) +
         edited.text.substr(edited.value_begin + edited.value_length);
}

namespace detail {

double control_dict_end_time(const fs::path& dir) { return read_end_time_entry(dir).value_s; }

// Rewrites that entry's value in the case's controlDict, atomically.
void set_control_dict_end_time(const fs::path& dir, double end_time_s) {
  util::write_file_atomically(dir / "system/controlDict", with_end_time(read_end_time_entry(dir), end_time_s));
}

// The controlDict's output interval when its writeControl counts simulated time, else nothing.
std::optional<double> output_grid_interval(const fs::path& dir) {
  const std::string text = util::read_text_file(dir / "system/controlDict");
  const auto control = top_level_entry(text, "writeControl");
  const auto interval_text = top_level_entry(text, "writeInterval");
  if (!control || !interval_text) return std::nullopt;
  if (!counts_simulated_time(*control)) return std::nullopt;
  char* end = nullptr;
  const double interval = std::strtod(interval_text->c_str(), &end);
  if (end == interval_text->c_str() || !(interval > 0.0)) return std::nullopt;
  return interval;
}

ControlDictOverride::ControlDictOverride(const fs::path& dir, const SolverLeg& leg) : dir_(dir), leg_(leg) {
  const fs::path file = dir / "system/controlDict";
  const std::string original = util::read_text_file(file);
  util::write_file_atomically(dir / control_dict_original, original);
  leg_text_ = leg_control_dict(original, file, leg);
  util::write_file_atomically(file, leg_text_);
}

ControlDictOverride::~ControlDictOverride() {
  try {
    restore(nullptr);
  } catch (...) {
    // the next `hydrojump vof` puts it back (restore_control_dict_left_behind)
  }
}

void ControlDictOverride::restore(std::ostream* out) {
  if (restored_) return;
  const fs::path file = dir_ / "system/controlDict", saved = dir_ / control_dict_original;
  const std::string current = util::read_text_file(file);
  const auto back = control_dict_after_leg(util::read_text_file(saved), leg_text_, current, file, leg_);
  if (!back) {
    util::write_file_atomically(dir_ / "system/controlDict.edited-during-leg", current);
    fs::rename(saved, file);
    if (out != nullptr)
      *out << "  system/controlDict was edited during a leg that wrote at its own interval: the case's is put "
              "back and the edited one kept as system/controlDict.edited-during-leg (apply the edit again)\n";
  } else if (current != leg_text_) {
    util::write_file_atomically(file, *back);
    fs::remove(saved);
    if (out != nullptr) *out << "  system/controlDict was edited during the leg: the edit is kept, with the case's endTime\n";
  } else {
    fs::rename(saved, file);
  }
  restored_ = true;
}

// Puts back a case controlDict left aside by a runner killed during an aligning leg.
void restore_control_dict_left_behind(const fs::path& dir, std::ostream& out) {
  if (!fs::exists(dir / control_dict_original)) return;
  fs::rename(dir / control_dict_original, dir / "system/controlDict");
  out << "  system/controlDict restored from " << control_dict_original
      << " (left by a run stopped while aligning with the output times)\n";
}

}  // namespace detail

}  // namespace hydrojump::reference
