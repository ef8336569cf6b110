// `hydrojump vof DIR --map-from SRC`: a fresh start from the latest complete time of another run of the
// same case (mesh sequencing: a finer run started from a settled coarser one), interpolated onto this
// mesh by `mapFields -consistent` instead of the setFields state. Refused when SRC holds another case or
// no result, or is the case itself; settings of SRC's case that differ beyond the resolution are listed.
#include <set>

#include "cases/results_case.hpp"
#include "cases/spec_reader.hpp"
#include "reference/runner_parts.hpp"
#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"
#include "util/time_directories.hpp"

namespace hydrojump::reference::detail {

namespace fs = std::filesystem;

namespace {

// The setting lines (cases::setting_lines) of one resolved case that the other lacks, each as
// "source: LINE" or "this case: LINE", leaving out the resolution's own lines (its table header and
// sizes), which a mapped run changes on purpose.
std::vector<std::string> settings_beyond_resolution(const std::string& source_text, const std::string& target_text) {
  const auto resolution_line = [](const std::string& line) {
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos) return true;
    const std::string body = line.substr(start);
    for (const char* key : {"[resolution.", "particle_spacing_m", "vof_cell_size_bed_m", "vof_cell_size_bulk_m"})
      if (body.rfind(key, 0) == 0) return true;
    return false;
  };
  std::multiset<std::string> source, target;
  for (const auto& line : cases::setting_lines(source_text))
    if (!resolution_line(line)) source.insert(line);
  for (const auto& line : cases::setting_lines(target_text))
    if (!resolution_line(line)) target.insert(line);
  std::vector<std::string> out;
  for (const auto& line : source)
    if (source.count(line) > target.count(line) && (out.empty() || out.back() != "source: " + line)) out.push_back("source: " + line);
  for (const auto& line : target)
    if (target.count(line) > source.count(line) && (out.empty() || out.back() != "this case: " + line)) out.push_back("this case: " + line);
  return out;
}

// The name of a field file without the ".gz" that compressed output adds.
std::string field_name(const fs::path& file) {
  std::string name = file.filename().string();
  if (name.size() > 3 && name.compare(name.size() - 3, 3, ".gz") == 0) name.resize(name.size() - 3);
  return name;
}

}  // namespace

MapSource check_map_source(const fs::path& source_in, const fs::path& target, const std::string& case_id) {
  const fs::path source = fs::absolute(source_in).lexically_normal();
  const std::string what = "--map-from " + source.string();
  std::error_code ec;
  if (!fs::is_directory(source, ec)) throw OpenFoamError(what + ": no such directory");
  if (fs::equivalent(source, target, ec)) throw OpenFoamError(what + ": that is the case being run");
  if (!fs::exists(source / "case.toml")) {
    throw OpenFoamError(what + ": not a generated OpenFOAM case (case.toml is missing)");
  }
  const cases::Study source_study = cases::load_study(source / "case.toml");
  if (source_study.cases.size() != 1 || source_study.cases.front().id != case_id) {
    throw OpenFoamError(what + ": holds case \"" +
                        (source_study.cases.empty() ? std::string() : source_study.cases.front().id) +
                        "\", not \"" + case_id + "\" (the state of another case is not an initial state for this one)");
  }
  auto times = util::time_directories(source, 0.0);
  while (!times.empty() && !time_directory_complete(times.back().path)) times.pop_back();
  if (times.empty()) {
    const bool decomposed = latest_time(source / "processor0").has_value();
    throw OpenFoamError(what + ": no complete time directory after t = 0" +
                        (decomposed ? std::string(" (its results are in processor*/: run reconstructPar there first)")
                                    : std::string()));
  }
  return MapSource{source, times.back().path.filename().string()};
}


// Interpolates the source's fields at its latest time onto this mesh (into 0/).
//   mapFields SRC' -sourceTime T -consistent
// SRC' is a view of the source (DIR/.map-source: links to its constant/ and system/, and to those
// files of its time directory that the case starts with, i.e. those in 0.orig/). mapFields maps every
// field of the source time; a field the target's 0/ lacks (p, fieldAverage means) it creates, and
// where the target mesh reaches beyond the source's (a taller air layer, a longer basin) those cells
// hold no value, so writing the field stops mapFields with a floating-point exception. Restricted to
// the case's own fields, cells outside the source keep setFields' initial state.
void map_initial_state(const StepPlace& place, const MapSource& source) {
  const fs::path& dir = place.dir;
  std::ostream& out = place.out;
  out << "Initial state from " << source.dir.string() << " at t = " << source.time_name << " s\n";
  // Mapping across resolutions is the purpose; across other settings (a longer basin, a taller air
  // layer) it is allowed, but said, so that a wrong source is not taken silently.
  const auto differences = settings_beyond_resolution(util::read_text_file(source.dir / "case.toml"),
                                                      util::read_text_file(dir / "case.toml"));
  if (!differences.empty()) {
    out << "  note: the source's settings differ from this case's beyond the resolution ("
        << differences.size() << " line(s); cells outside the source's domain keep setFields' initial state):\n";
    for (std::size_t k = 0; k < differences.size() && k < 8; ++k) out << "    " << differences[k] << "\n";
  }
  std::set<std::string> initial;
  for (const auto& entry : fs::directory_iterator(dir / "0.orig")) initial.insert(field_name(entry.path()));
  fs::remove_all(dir / ".map-source");  // left by a killed run
  const ScratchDirectory scratch(fs::absolute(dir / ".map-source"));
  const fs::path& view = scratch.path();
  fs::create_directories(view / source.time_name);
  fs::create_directory_symlink(source.dir / "constant", view / "constant");
  fs::create_directory_symlink(source.dir / "system", view / "system");
  for (const auto& entry : fs::directory_iterator(source.dir / source.time_name)) {
    if (entry.is_regular_file() && initial.count(field_name(entry.path()))) {
      fs::create_symlink(entry.path(), view / source.time_name / entry.path().filename());
    }
  }
  run_step(place, {"mapFields", view.string(), "-sourceTime", source.time_name, "-consistent"}, "log.mapFields");
}

}  // namespace hydrojump::reference::detail
