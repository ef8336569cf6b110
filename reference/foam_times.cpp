// The time directories of a case: which are complete (written to the end, on every rank), moving a
// half-written one aside (<time>.incomplete), the latest time, and the leftovers of a run killed while
// it wrote (a decomposition cut short, the samples of an abandoned part).
#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>

#include "reference/runner_parts.hpp"
#include "util/time_directories.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

std::optional<double> latest_time(const fs::path& case_dir) {
  const auto times = util::time_directories(case_dir, 0.0);
  if (times.empty()) return std::nullopt;
  return times.back().time_s;
}

namespace detail {

namespace {

// Whether an OpenFOAM file was written to the end: compressed files pass `gzip -t`, plain ones hold
// OpenFOAM's closing rule.
bool foam_file_complete(const fs::path& file) {
  std::error_code ec;
  if (file.extension() == ".gz") {
    if (fs::file_size(file, ec) == 0 || ec) return false;
    return wait_for(spawn({"gzip", "-t", file.string()}, file.parent_path(), "/dev/null", true)) == 0;
  }
  // The rule is the file's last line (a blank line may follow it): its tail is enough to read.
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size <= 0) return false;
  const std::streamoff tail = std::min<std::streamoff>(size, 4096);
  std::string text(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(text.data(), tail);
  return in && text.find("// ****") != std::string::npos;
}

}  // namespace

// processor0/, processor1/, ... of a decomposed case, up to the first missing rank.
std::vector<fs::path> processor_directories(const fs::path& dir) {
  std::vector<fs::path> out;
  for (fs::path p = dir / "processor0"; fs::is_directory(p); p = dir / ("processor" + std::to_string(out.size())))
    out.push_back(p);
  return out;
}

// A time directory is complete when its main fields are present and every field file in it (the
// turbulence fields, phi, uniform/time too) was written to the end.
bool time_directory_complete(const fs::path& time_dir) {
  std::error_code ec;
  for (const char* field : {"alpha.water", "U", "p_rgh"}) {
    if (!fs::exists(time_dir / field, ec) && !fs::exists(time_dir / (std::string(field) + ".gz"), ec)) return false;
  }
  for (const fs::path& sub : {time_dir, time_dir / "uniform"}) {
    if (!fs::is_directory(sub, ec)) continue;
    for (const auto& entry : fs::directory_iterator(sub, ec)) {
      // Not OpenFOAM's: a temporary file of an atomic write cut short, an editor's swap or backup file.
      const std::string name = entry.path().filename().string();
      if (name.empty() || name.front() == '.' || name.back() == '~') continue;
      if (entry.is_regular_file(ec) && !foam_file_complete(entry.path())) return false;
    }
  }
  return true;
}

// Moves `dir` aside as <dir>.<suffix> (<dir>.<suffix>.2, ... when that name is left from an earlier
// kill); returns the new name. Throws naming `what` when it cannot.
std::string move_aside(const fs::path& dir, const std::string& suffix, const std::string& what) {
  std::error_code ec;
  fs::path aside = dir.string() + "." + suffix;
  for (int n = 2; fs::exists(aside, ec); ++n) aside = dir.string() + "." + suffix + "." + std::to_string(n);
  fs::rename(dir, aside, ec);
  if (ec) {
    throw OpenFoamError("cannot move " + what + " " + dir.string() + " aside to " + aside.string() + ": " +
                        ec.message() + " (move or delete it, then resume)");
  }
  return aside.filename().string();
}

// A half-written time directory, as <name>.incomplete.
std::string move_incomplete_aside(const fs::path& time_dir) {
  return move_aside(time_dir, "incomplete", "the half-written time directory");
}

// Removes processor*/ left by a decomposePar that was stopped or killed (the marker is still there).
// Nothing in them is lost: decomposePar runs only for a new run or when the case directory holds the
// newest time (which it decomposes, replacing processor*/ with -force), and that time is still there.
void remove_cut_short_decomposition(const fs::path& dir, std::ostream& out) {
  if (!fs::exists(dir / decomposing_marker)) return;
  std::vector<fs::path> ranks;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("processor", 0) == 0 && name.size() > 9 &&
        name.find_first_not_of("0123456789", 9) == std::string::npos)
      ranks.push_back(it->path());
  }
  for (const fs::path& rank : ranks) {
    fs::remove_all(rank, ec);
    if (ec) {
      throw OpenFoamError("cannot remove " + rank.string() + ", left by a decomposePar that was cut short: " +
                          ec.message() + " (delete processor*/ and " + decomposing_marker + ", then run again)");
    }
  }
  fs::remove(dir / decomposing_marker);
  if (!ranks.empty()) {
    out << "  removed " << ranks.size() << " processor directories left by a decomposePar that was cut short "
        << "(the case is decomposed again)\n";
  }
}

std::optional<double> discard_incomplete_times(const fs::path& dir, bool continue_decomposed, std::ostream& out) {
  // A time directory left half-written by a killed run is moved aside: decomposed, a time is
  // complete only when every rank has it complete (a rank killed while writing, or one that never
  // got there, would make interFoam fail or start the ranks at different times).
  // The times of every rank: one that only some ranks reached is incomplete too.
  const std::vector<fs::path> ranks = continue_decomposed ? processor_directories(dir) : std::vector<fs::path>{dir};
  std::map<double, std::string> times;
  for (const fs::path& rank : ranks)
    for (const auto& [t, path] : util::time_directories(rank, 0.0)) times.emplace(t, path.filename().string());
  const auto complete_everywhere = [&ranks](const std::string& name) {
    for (const fs::path& rank : ranks) {
      if (!time_directory_complete(rank / name)) return false;
    }
    return true;
  };
  while (!times.empty() && !complete_everywhere(times.rbegin()->second)) {
    const std::string name = times.rbegin()->second;
    std::string aside;
    for (const fs::path& rank : ranks) {
      std::error_code ec;
      if (fs::exists(rank / name, ec)) aside = move_incomplete_aside(rank / name);
    }
    out << "  time directory " << name << (continue_decomposed ? " (processor*/)" : "")
        << " is incomplete (killed while writing): moved to " << aside << "\n";
    times.erase(std::prev(times.end()));
  }
  const std::optional<double> start =
      times.empty() ? std::nullopt : std::optional<double>(times.rbegin()->first);
  // Samples the abandoned part wrote after the start (a function object's start-time directory of a
  // later leg, a surface at a time the run never kept) would be read as this run's: moved aside.
  std::error_code ec;
  for (fs::directory_iterator fo(dir / "postProcessing", ec), end; !ec && fo != end; fo.increment(ec)) {
    if (!fo->is_directory(ec)) continue;
    for (const auto& [t, path] : util::time_directories(fo->path(), start.value_or(0.0) + 1e-12))
      move_aside(path, "abandoned", "the abandoned samples");
  }
  if (continue_decomposed) {
    // reconstructPar -newTimes skips a time already at the top level, so a reconstruction killed
    // while writing would stay half-written there: move it aside to be reconstructed again.
    auto reconstructed = util::time_directories(dir, 0.0);
    while (!reconstructed.empty() && !time_directory_complete(reconstructed.back().path)) {
      out << "  reconstructed time directory " << reconstructed.back().path.filename().string()
          << " is incomplete: moved to " << move_incomplete_aside(reconstructed.back().path)
          << " (reconstructed again at the end)\n";
      reconstructed.pop_back();
    }
  }
  return start;
}

}  // namespace detail

}  // namespace hydrojump::reference
