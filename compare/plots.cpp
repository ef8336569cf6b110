#include "compare/plots.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "util/child_process.hpp"

namespace fs = std::filesystem;

namespace hydrojump::compare {

fs::path plot_script_dir() {
  std::vector<fs::path> tried;
  auto ok = [&](const fs::path& p) {
    tried.push_back(p);
    return fs::exists(p / "plot_case.py");
  };
  if (const char* env = std::getenv("HYDROJUMP_PLOT_DIR"); env && *env && ok(env)) return env;
#ifdef HYDROJUMP_PLOT_SCRIPT_DIR
  if (ok(HYDROJUMP_PLOT_SCRIPT_DIR)) return HYDROJUMP_PLOT_SCRIPT_DIR;
#endif
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    if (ok(exe.parent_path() / ".." / "share" / "hydrojump" / "plot"))
      return fs::weakly_canonical(exe.parent_path() / ".." / "share" / "hydrojump" / "plot");
    if (ok(exe.parent_path() / "plot")) return exe.parent_path() / "plot";
  }
  std::string list;
  for (const auto& p : tried) {
    list += ' ';
    list += p.string();
  }
  throw std::runtime_error("the plot scripts (plot_case.py) were not found; tried:" + list +
                           " (set HYDROJUMP_PLOT_DIR to the compare/plot directory)");
}

static std::string last_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

std::string run_plot_script(const std::string& script, const std::vector<std::string>& args, const fs::path& log_file) {
  const char* python = "/usr/bin/python3";
  if (::access(python, X_OK) != 0) return "/usr/bin/python3 is not available";
  fs::path dir;
  try {
    dir = plot_script_dir();
  } catch (const std::exception& e) {
    return e.what();
  }
  // -s: no user site packages (~/.local) shadowing Debian's matplotlib; PYTHONPATH removed for the same
  // reason; matplotlib without a display.
  std::vector<std::string> argv = {python, "-s", (dir / script).string()};
  argv.insert(argv.end(), args.begin(), args.end());
  fs::create_directories(log_file.parent_path());
  util::ChildCommand command(argv, log_file);
  // Unbuffered: the script's last line (its summary of what failed, on stderr) stays the log's last line,
  // after its "wrote ..." lines on stdout.
  command.environment = {"MPLBACKEND=Agg", "PYTHONPATH", "PYTHONUNBUFFERED=1"};
  command.parent_death_signal = SIGTERM;
  util::ChildExit ended;
  try {
    ended = util::run_child(command);
  } catch (const std::exception& e) {
    return e.what();
  }
  if (ended.status() == 0) return "";
  std::ostringstream s;
  s << script << " failed (it " << ended.describe() << "): " << last_line(log_file) << " (log: " << log_file.string() << ")";
  return s.str();
}

std::string plot_case_figures(const fs::path& csv_dir, const fs::path& fig_dir) {
  fs::create_directories(fig_dir);
  return run_plot_script("plot_case.py", {csv_dir.string(), fig_dir.string()}, fig_dir / "plot.log");
}

std::string plot_eta_bars(const std::vector<fs::path>& eta_csv_files, const fs::path& png, const fs::path& log_file) {
  std::vector<std::string> args;
  for (const auto& f : eta_csv_files) args.push_back(f.string());
  args.push_back("--out");
  args.push_back(png.string());
  return run_plot_script("plot_eta_bars.py", args, log_file);
}

std::string plot_study_eta_bars(const std::vector<fs::path>& case_dirs, const fs::path& png) {
  std::vector<fs::path> files;
  for (const auto& d : case_dirs)
    if (fs::exists(d / "csv" / "eta.csv")) files.push_back(d / "csv" / "eta.csv");
  if (files.empty()) return "no case has csv/eta.csv (no comparison finished)";
  fs::path log = png;
  log.replace_extension(".log");
  return plot_eta_bars(files, png, log);
}

}  // namespace hydrojump::compare
