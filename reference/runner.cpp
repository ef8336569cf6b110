#include "reference/runner.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <deque>
#include <map>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <iomanip>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "util/atomic_file.hpp"
#include "util/child_process.hpp"
#include "util/directory_lock.hpp"
#include "util/fingerprint.hpp"
#include "cases/geometry.hpp"
#include "cases/results_case.hpp"
#include "cases/spec_reader.hpp"
#include "util/stop_signals.hpp"
#include "util/time_directories.hpp"
#include "reference/case_writer.hpp"
#include "reference/discharge_samples.hpp"
#include "reference/foam_dictionary.hpp"
#include "reference/line_samples.hpp"
#include "reference/solver_log.hpp"
#include "reference/tailwater_control.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

namespace {

constexpr const char* default_project_dir = "/usr/share/openfoam";

// The signal the generated controlDict tells interFoam to treat as "write now and stop"
// (OptimisationSwitches/stopAtWriteNowSignal); SIGUSR2 is forwarded to the ranks by mpirun.
constexpr int write_and_stop_signal = SIGUSR2;

// A scratch directory removed when the scope ends, also when a step inside it fails (errors while
// removing are ignored: they must not replace the step's own error).
class ScratchDirectory {
 public:
  explicit ScratchDirectory(fs::path path) : path_(std::move(path)) {}
  ~ScratchDirectory() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// The stop requests (Ctrl-C, SIGTERM, a hangup) since the StopRequestGuard of this run was installed.
volatile std::sig_atomic_t stop_requests = 0;
void reference_runner_request_stop(int) { stop_requests = stop_requests + 1; }

// Installs SIGINT/SIGTERM handlers for its lifetime (one run of `hydrojump vof`), and a SIGHUP one
// unless SIGHUP is ignored (nohup): a closed terminal stops the solver with its state written, instead
// of leaving it running unowned (it runs in its own process group, which the hangup does not reach).
// The run stops at the next safe point: the solver writes its current time and stops, a utility
// (blockMesh, decomposePar, reconstructPar, ...) is stopped, and no further step starts.
class StopRequestGuard {
 public:
  StopRequestGuard() { stop_requests = 0; }

 private:
  // A progress line written to a pipe whose reader a hangup ended must not kill the runner before it
  // has stopped the solver (the write fails instead).
  util::StopSignalHandlers handlers_{reference_runner_request_stop,
                                      {.restart_interrupted_calls = false, .ignore_sigpipe = true}};
};

// The last `n` lines of a text file, indented.
std::string tail_file(const fs::path& file, std::size_t n = 20) {
  std::ifstream in(file);
  std::deque<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    lines.push_back(line);
    if (lines.size() > n) lines.pop_front();
  }
  std::string out;
  for (const std::string& l : lines) out += "    " + l + "\n";
  return out;
}

// Starts `argv` in `cwd` with stdout and stderr going to `log` (appended or truncated), in its own
// process group: Ctrl-C reaches hydrojump, which asks the solver to write and stop; when hydrojump ends
// in any way, SIGKILL included, the child gets SIGUSR2 (interFoam writes its current time and stops;
// mpirun passes it to the ranks; the utilities end). OpenFOAM warns when PWD differs from the working
// directory.
pid_t spawn(const std::vector<std::string>& argv, const fs::path& cwd, const fs::path& log, bool append,
            std::vector<int> inherited_descriptors = {}) {
  try {
    util::ChildCommand command(argv, log);
    command.append_to_log = append;
    command.inherited_descriptors = std::move(inherited_descriptors);
    command.working_directory = cwd;
    command.own_process_group = true;
    command.parent_death_signal = write_and_stop_signal;  // hydrojump killed outright (SIGKILL) stops it too
    command.environment = {"PWD=" + cwd.string()};
    return util::start_child(command);
  } catch (const std::exception& e) {
    throw OpenFoamError(e.what());
  }
}

// The exit status (128 + signal when killed) of a child started by spawn.
int wait_for(pid_t pid) { return util::wait_child(pid).status(); }

std::string command_text(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) s += (s.empty() ? "" : " ") + a;
  return s;
}

// Whether a step runs after a stop request made before it started: a step of the run does not
// start; the reconstruction of what an interrupted parallel run wrote does (a new request stops it).
enum class AfterStopRequest { skip, run };

// Waits for a child started by spawn; a stop request made since `requests_before` stops it instead
// (nothing is returned then).
std::optional<util::ChildExit> wait_unless_stop_requested(pid_t pid, std::sig_atomic_t requests_before) {
  for (;;) {
    if (auto ended = util::poll_child(pid)) return ended;
    if (stop_requests != requests_before) {
      util::stop_child(pid);
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

// Thrown by run_step when a stop request stopped its utility or kept it from starting; the run adds
// how to go on.
class StepStopped : public OpenFoamError {
 public:
  using OpenFoamError::OpenFoamError;
};

// Where a run's utilities run: the case directory, the stream their command lines are shown on, and
// the directory's lock, which each utility inherits, so that one still writing when hydrojump dies
// (killed) keeps the directory from a second run until it ends, as the solver does.
struct StepPlace {
  const fs::path& dir;
  std::ostream& out;
  const util::DirectoryLock& lock;
};

// Runs one utility to completion; a non-zero exit stops the run with the tail of its log. A stop
// request stops it (what it wrote is not used: the next run starts the step again).
void run_step(const StepPlace& place, const std::vector<std::string>& argv, const std::string& log_name,
              AfterStopRequest after_request = AfterStopRequest::skip) {
  const fs::path& dir = place.dir;
  std::ostream& out = place.out;
  const std::sig_atomic_t requests_before = after_request == AfterStopRequest::run ? stop_requests : 0;
  const std::string interrupted = "interrupted: " + argv.front() + " in " + dir.string() + " was stopped on request.";
  if (stop_requests != requests_before) throw StepStopped(interrupted);
  out << "  " << command_text(argv) << "  (log: " << log_name << ")\n" << std::flush;
  const fs::path log = dir / log_name;
  const auto ended =
      wait_unless_stop_requested(spawn(argv, dir, log, false, {place.lock.descriptor()}), requests_before);
  if (!ended) throw StepStopped(interrupted);
  if (ended->status() != 0) {
    throw OpenFoamError(argv.front() + " failed (it " + ended->describe() + ") in " + dir.string() +
                        "; last lines of " + log_name + ":\n" + tail_file(log));
  }
}

// processor0/, processor1/, ... of a decomposed case, up to the first missing rank.
std::vector<fs::path> processor_directories(const fs::path& dir) {
  std::vector<fs::path> out;
  for (fs::path p = dir / "processor0"; fs::is_directory(p); p = dir / ("processor" + std::to_string(out.size())))
    out.push_back(p);
  return out;
}

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

std::string format_seconds(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", t);
  return buffer;
}

// ---------------------------------------------------------------------------- self-test case

void write_self_test_case(const fs::path& dir, double shear_m) {
  using foam::Dictionary;
  const double L = 0.1, t = 0.01;
  auto write = [&](const std::string& path, const std::string& cls, const Dictionary& d) {
    const auto slash = path.find('/');
    util::write_file_atomically(dir / path, foam::format_file({cls, path.substr(0, slash), path.substr(slash + 1)}, d));
  };
  Dictionary bm;
  std::vector<foam::Value> v;
  for (double z : {-0.5 * t, 0.5 * t}) {
    v.push_back(foam::vector(0, 0, z));
    v.push_back(foam::vector(L, 0, z));
    v.push_back(foam::vector(L + shear_m, L, z));
    v.push_back(foam::vector(shear_m, L, z));
  }
  bm.set("scale", 1);
  bm.set("vertices", foam::list(v));
  bm.set("blocks", foam::list({foam::sequence({foam::word("hex"), foam::list({0, 1, 2, 3, 4, 5, 6, 7}),
                                               foam::list({16, 16, 1}), foam::word("simpleGrading"),
                                               foam::list({1, 1, 1})})}));
  auto patch = [](const std::string& type, std::vector<foam::Value> faces) {
    Dictionary p;
    p.set("type", foam::word(type));
    p.set("faces", foam::list(std::move(faces)));
    return p;
  };
  bm.set("boundary",
         foam::list({foam::named_dict("walls", patch("wall", {foam::list({0, 4, 7, 3}), foam::list({2, 6, 5, 1}),
                                                               foam::list({1, 5, 4, 0})})),
                     foam::named_dict("atmosphere", patch("patch", {foam::list({3, 7, 6, 2})})),
                     foam::named_dict("frontAndBack", patch("empty", {foam::list({0, 3, 2, 1}),
                                                                      foam::list({4, 5, 6, 7})}))}));
  write("system/blockMeshDict", "dictionary", bm);

  Dictionary cd;
  cd.set("application", foam::word("interFoam"));
  cd.set("startFrom", foam::word("startTime"));
  cd.set("startTime", 0);
  cd.set("stopAt", foam::word("endTime"));
  cd.set("endTime", 0.1);
  cd.set("deltaT", 0.001);
  cd.set("writeControl", foam::word("timeStep"));
  cd.set("writeInterval", 100000);
  cd.set("runTimeModifiable", foam::word("no"));
  cd.set("adjustTimeStep", foam::word("no"));
  cd.set("maxCo", 1);
  cd.set("maxAlphaCo", 1);
  write("system/controlDict", "dictionary", cd);

  Dictionary sf;
  sf.set("defaultFieldValues", foam::list({foam::word("volScalarFieldValue alpha.water 0")}));
  Dictionary box;
  box.set("box", foam::sequence({foam::vector(-1, -1, -1), foam::vector(1, 0.5 * L, 1)}));
  box.set("fieldValues", foam::list({foam::word("volScalarFieldValue alpha.water 1")}));
  sf.set("regions", foam::list({foam::named_dict("boxToCell", box)}));
  write("system/setFieldsDict", "dictionary", sf);

  // Schemes and solvers as in the generated cases.
  const Dictionary fs_d = interfoam_fv_schemes("laminar");
  write("system/fvSchemes", "dictionary", fs_d);

  Dictionary sol;
  Dictionary& solvers = sol.subdict("solvers");
  solvers.set("\"alpha.water.*\"", mules_alpha_solver());
  Dictionary pcg;
  pcg.set("solver", foam::word("PCG"));
  pcg.set("preconditioner", foam::word("DIC"));
  pcg.set("tolerance", 1e-8);
  pcg.set("relTol", 0);
  solvers.set("\"(pcorr|p_rgh).*\"", pcg);
  solvers.set("\"U.*\"", smooth_solver(1e-8));
  Dictionary& pimple = sol.subdict("PIMPLE");
  pimple.set("momentumPredictor", foam::word("no"));
  pimple.set("nOuterCorrectors", 1);
  pimple.set("nCorrectors", 3);
  pimple.set("nNonOrthogonalCorrectors", 1);
  write("system/fvSolution", "dictionary", sol);

  Dictionary g;
  g.set("dimensions", foam::dimensions({0, 1, -2, 0, 0, 0, 0}));
  g.set("value", foam::vector(0, -9.81, 0));
  write("constant/g", "uniformDimensionedVectorField", g);
  Dictionary tp;
  tp.set("phases", foam::list({foam::word("water"), foam::word("air")}));
  Dictionary water, air;
  water.set("transportModel", foam::word("Newtonian"));
  water.set("nu", 1e-6);
  water.set("rho", 1000);
  air.set("transportModel", foam::word("Newtonian"));
  air.set("nu", 1.48e-5);
  air.set("rho", 1);
  tp.set("water", water);
  tp.set("air", air);
  tp.set("sigma", 0.07);
  write("constant/transportProperties", "dictionary", tp);
  Dictionary tu;
  tu.set("simulationType", foam::word("laminar"));
  write("constant/turbulenceProperties", "dictionary", tu);

  auto field = [&](const std::string& name, const std::string& cls, const std::array<int, 7>& dims,
                   const foam::Value& internal, const Dictionary& walls, const Dictionary& atmosphere) {
    Dictionary f;
    f.set("dimensions", foam::dimensions(dims));
    f.set("internalField", internal);
    Dictionary& bf = f.subdict("boundaryField");
    bf.set("walls", walls);
    bf.set("atmosphere", atmosphere);
    Dictionary empty;
    empty.set("type", foam::word("empty"));
    bf.set("frontAndBack", empty);
    write("0/" + name, cls, f);
  };
  Dictionary no_slip, zero_grad, ffp, piov, io, tot;
  no_slip.set("type", foam::word("noSlip"));
  zero_grad.set("type", foam::word("zeroGradient"));
  ffp.set("type", foam::word("fixedFluxPressure"));
  piov.set("type", foam::word("pressureInletOutletVelocity"));
  piov.set("value", foam::uniform(foam::vector(0, 0, 0)));
  io.set("type", foam::word("inletOutlet"));
  io.set("inletValue", foam::uniform(0));
  io.set("value", foam::uniform(0));
  tot.set("type", foam::word("totalPressure"));
  tot.set("p0", foam::uniform(0));
  field("U", "volVectorField", {0, 1, -1, 0, 0, 0, 0}, foam::uniform(foam::vector(0, 0, 0)), no_slip, piov);
  field("alpha.water", "volScalarField", {0, 0, 0, 0, 0, 0, 0}, foam::uniform(0), zero_grad, io);
  field("p_rgh", "volScalarField", {1, -1, -2, 0, 0, 0, 0}, foam::uniform(0), ffp, tot);
}

// Runs one self-test box; returns the largest Courant number (inf when the solver crashed).
double run_self_test_box(const fs::path& dir, double shear_m) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_self_test_case(dir, shear_m);
  // A stop request (Ctrl-C while `hydrojump vof` runs it) ends the self-test at once.
  const auto run_stoppable = [&dir](const std::string& app) {
    const auto ended = wait_unless_stop_requested(spawn({app}, dir, dir / ("log." + app), false), 0);
    if (!ended) throw OpenFoamError("interrupted: the self-test of interFoam was stopped on request");
    return ended->status();
  };
  for (const char* app : {"blockMesh", "setFields"}) {
    if (run_stoppable(app) != 0) {
      throw OpenFoamError(std::string("self-test: ") + app + " failed in " + dir.string() + ":\n" +
                          tail_file(dir / (std::string("log.") + app)));
    }
  }
  const int rc = run_stoppable("interFoam");
  SolverLog log(DivergenceLimits{1.0, 1e300, 0.0});
  std::ifstream in(dir / "log.interFoam");
  std::string line;
  double worst = 0.0;
  while (std::getline(in, line)) {
    log.add_line(line);
    if (line.rfind("Courant Number mean:", 0) == 0 && log.courant_max()) {
      worst = std::isfinite(*log.courant_max()) ? std::max(worst, *log.courant_max())
                                                : std::numeric_limits<double>::infinity();
    }
  }
  if (rc != 0) return std::numeric_limits<double>::infinity();
  return worst;
}

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

// Rewrites that entry's value in the case's controlDict, atomically.
void set_control_dict_end_time(const fs::path& dir, double end_time_s) {
  util::write_file_atomically(dir / "system/controlDict", with_end_time(read_end_time_entry(dir), end_time_s));
}

}  // namespace

// ------------------------------------------------------------------------------------ public

std::string SelfTestResult::summary() const {
  auto co = [](double c) { return std::isfinite(c) ? format_seconds(c) : std::string("inf (crashed)"); };
  return "still water for 100 steps: axis-aligned box max Courant " + co(axis_aligned_courant) +
         (axis_aligned_ok ? " (ok)" : " (FAILED)") + "; box sheared by 2 degrees max Courant " +
         co(sheared_courant) + (sheared_ok ? " (ok)" : " (FAILED)");
}

SelfTestResult self_test_non_orthogonal(const fs::path& work_dir) {
  const ScratchDirectory root(work_dir / (".hydrojump-selftest-" + std::to_string(::getpid())));
  SelfTestResult r;
  const double healthy = 1e-2;  // a resting fluid stays far below this Courant number
  r.axis_aligned_courant = run_self_test_box(root.path() / "aligned", 0.0);
  r.sheared_courant = run_self_test_box(root.path() / "sheared", 0.1 * std::tan(2.0 * M_PI / 180.0));
  r.axis_aligned_ok = r.axis_aligned_courant < healthy;
  r.sheared_ok = r.sheared_courant < healthy;
  return r;
}

OpenFoamInstallation check_openfoam(bool need_mpi) {
  OpenFoamInstallation inst;
  const char* env = std::getenv("WM_PROJECT_DIR");
  if (env && *env) {
    inst.project_dir = env;
  } else if (fs::is_directory(default_project_dir)) {
    inst.project_dir = default_project_dir;
    ::setenv("WM_PROJECT_DIR", default_project_dir, 1);
  } else {
    throw OpenFoamError(
        "OpenFOAM not found: WM_PROJECT_DIR is not set and /usr/share/openfoam does not exist. Install "
        "the Debian package `openfoam` (apt-get install openfoam) or set WM_PROJECT_DIR.");
  }
  if (!fs::is_directory(inst.project_dir / "etc")) {
    throw OpenFoamError("OpenFOAM not usable: WM_PROJECT_DIR = " + inst.project_dir.string() +
                        " has no etc/ directory (OpenFOAM's binaries need it)");
  }
  std::vector<std::string> apps = {"blockMesh", "topoSet",      "subsetMesh",     "checkMesh", "setFields",
                                   "interFoam", "decomposePar", "reconstructPar", "foamDictionary"};
  if (need_mpi) apps.push_back("mpirun");
  for (const std::string& app : apps) {
    if (!util::find_on_path(app)) {
      throw OpenFoamError("OpenFOAM not found: `" + app + "` is not on PATH. Install the Debian packages " +
                          (app == "mpirun" ? std::string("`openmpi-bin`") : std::string("`openfoam`")) +
                          " (or add OpenFOAM's bin directory to PATH).");
    }
  }
  // interFoam must start: its help text names the version.
  char tmpl[] = "/tmp/hydrojump-foam-XXXXXX";
  const int fd = ::mkstemp(tmpl);
  if (fd >= 0) ::close(fd);
  const fs::path log = tmpl;
  int rc = 0;
  try {
    rc = wait_for(spawn({"interFoam", "-help"}, fs::temp_directory_path(), log, false));
  } catch (...) {
    std::error_code ec;
    fs::remove(log, ec);
    throw;
  }
  const std::string text = util::read_text_file(log);
  std::error_code ec;
  fs::remove(log, ec);
  if (rc != 0) {
    throw OpenFoamError("OpenFOAM not usable: `interFoam -help` failed (exit code " + std::to_string(rc) +
                        "):\n" + text.substr(0, 2000));
  }
  const auto pos = text.find("OpenFOAM-");
  if (pos != std::string::npos) {
    const auto open = text.find('(', pos), close = text.find(')', pos);
    if (open != std::string::npos && close != std::string::npos && close > open) {
      inst.version = text.substr(open + 1, close - open - 1);
    }
  }
  return inst;
}

namespace {

// The run whose state `--map-from` starts this one from: its directory and the name of its latest
// complete time directory (as mapFields -sourceTime wants it).
struct MapSource {
  fs::path dir;
  std::string time_name;
};

// Checks that `source` holds a finished (or interrupted) run of case `case_id`, not `target` itself.
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

// ------------------------------------------------------------ legs on the output grid
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

const char* const control_dict_original = "system/controlDict.hydrojump-original";

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

namespace {

// A leg's controlDict in place of the case's for its lifetime (see above).
class ControlDictOverride {
 public:
  ControlDictOverride(const fs::path& dir, const SolverLeg& leg) : dir_(dir), leg_(leg) {
    const fs::path file = dir / "system/controlDict";
    const std::string original = util::read_text_file(file);
    util::write_file_atomically(dir / control_dict_original, original);
    leg_text_ = leg_control_dict(original, file, leg);
    util::write_file_atomically(file, leg_text_);
  }
  ~ControlDictOverride() {
    try {
      restore(nullptr);
    } catch (...) {
      // the next `hydrojump vof` puts it back (restore_control_dict_left_behind)
    }
  }
  ControlDictOverride(const ControlDictOverride&) = delete;
  ControlDictOverride& operator=(const ControlDictOverride&) = delete;
  // Puts the case's controlDict back, keeping an edit made by hand during the leg (runTimeModifiable:
  // a changed maxCo, say) where it can (control_dict_after_leg); says so on `out` when given.
  void restore(std::ostream* out) {
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

 private:
  fs::path dir_;
  SolverLeg leg_;
  std::string leg_text_;
  bool restored_ = false;
};

// Puts back a case controlDict left aside by a runner killed during an aligning leg.
void restore_control_dict_left_behind(const fs::path& dir, std::ostream& out) {
  if (!fs::exists(dir / control_dict_original)) return;
  fs::rename(dir / control_dict_original, dir / "system/controlDict");
  out << "  system/controlDict restored from " << control_dict_original
      << " (left by a run stopped while aligning with the output times)\n";
}

// Present while decomposePar runs: processor*/ are then not a decomposition to resume from.
constexpr const char* decomposing_marker = ".decomposing";

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

// --------------------------------------------------------------------------------- the solver

// What every leg of interFoam needs: the case, the command (interFoam, or mpirun ... -parallel).
struct SolverRun {
  fs::path dir;
  const cases::Case& c;
  double thickness_m;                // spanwise cell size: discharges per unit width
  std::vector<std::string> command;
  bool parallel;
  const RunOptions& options;
  double run_end_s;                  // the end time of the whole run (progress and ETA)
  const util::DirectoryLock& lock;  // the case directory's, which the solver holds while it runs
};

// Runs the solver from `start` (nothing: t = 0) until `end_time_s`, showing progress, and returns the
// time reached. A failure (divergence, crash, an early end) or a stop request throws OpenFoamError with
// the last lines of the log and how to resume.
double run_solver(const SolverRun& run, std::optional<double> start, double end_time_s, std::ostream& out) {
  const fs::path& dir = run.dir;
  const cases::Case& c = run.c;
  const fs::path log_file = dir / "log.interFoam";
  std::uintmax_t offset = 0;
  if (start) {
    std::ofstream mark(log_file, std::ios::app);
    mark << "\n// ---- resumed by hydrojump from t = " << format_seconds(*start) << " s ----\n";
    mark.close();
    std::error_code ec;
    offset = fs::file_size(log_file, ec);
    if (ec) offset = 0;
  }
  out << "Running " << command_text(run.command) << " to t = " << format_seconds(end_time_s)
      << " s (log: log.interFoam)\n" << std::flush;
  // The solver holds the directory's lock too: if this runner dies (SIGKILL, out of memory) while
  // interFoam goes on, a second `hydrojump vof DIR` is refused until that solver has ended.
  const pid_t pid = spawn(run.command, dir, log_file, start.has_value(), {run.lock.descriptor()});
  // What a second runner is shown, also when this one was killed and the solver runs on.
  run.lock.set_note("its solver " + run.command.front() + ", pid " + std::to_string(pid),
                    "`kill -USR2 " + std::to_string(pid) + "` makes it write its current time and stop (then `hydrojump vof " +
                        dir.string() + " --resume" + (run.parallel ? " --np " + std::to_string(run.options.np) : std::string()) +
                        "`)");
  struct NoteCleared {
    const util::DirectoryLock& lock;
    ~NoteCleared() { lock.set_note(""); }
  } note_cleared{run.lock};
  SolverLog log(DivergenceLimits{c.vof.max_courant, 25.0, 1e-9});
  const bool interactive = (&out == &std::cout) && ::isatty(STDOUT_FILENO);
  const double t_begin = start.value_or(0.0);
  const auto solver_begin = std::chrono::steady_clock::now();
  auto last_report = solver_begin;
  std::optional<util::ChildExit> ended;  // how interFoam ended; nullopt while it runs
  auto read_new = [&]() {
    std::ifstream in(log_file, std::ios::binary);
    if (!in) return;
    in.seekg(static_cast<std::streamoff>(offset));
    std::string chunk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    offset += chunk.size();
    log.add_text(chunk);
  };
  auto progress = [&](bool final_line) {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - solver_begin).count();
    const double t = log.time_s().value_or(t_begin);
    const double done = t - t_begin;
    const double eta = done > 0 ? (run.run_end_s - t) * wall / done : std::nan("");
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, "  t = %.4g / %.4g s (%.1f %%), dt = %.3g s, Co max %.3g, wall %s, ETA %s",
                  t, run.run_end_s, 100.0 * t / run.run_end_s, log.time_step_s().value_or(0.0),
                  log.courant_max().value_or(0.0), format_duration(wall).c_str(),
                  format_duration(eta).c_str());
    std::string line = buffer;
    // A stilling basin's water balance over the last simulated second of this run, or since it
    // started (discharge_samples.hpp).
    const double balance_from = std::max(t_begin, t - 1.0);
    if (c.stilling_basin() && t > balance_from) {
      try {
        if (const auto q = patch_discharges(dir, balance_from, t, run.thickness_m)) {
          std::ostringstream balance;
          balance << std::setprecision(4) << ", q_in " << q->inflow_m2_s << ", q_out " << q->outflow_m2_s;
          if (q->top_outflow_m2_s > 0.001 * q->inflow_m2_s) balance << " + top " << q->top_outflow_m2_s;
          balance << " m2/s (last " << t - balance_from << " s)";
          line += balance.str();
        }
      } catch (const std::exception&) {
        // a sample file being written: the next progress line reads it again
      }
    }
    if (interactive) {
      out << "\r" << line << "    " << (final_line ? "\n" : "") << std::flush;
    } else {
      out << line << "\n" << std::flush;
    }
  };
  bool stop_sent = false;
  std::chrono::steady_clock::time_point stop_time;
  while (!ended) {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    ended = util::poll_child(pid);
    if (stop_requests > 0 && !ended && !stop_sent) {
      ::kill(pid, write_and_stop_signal);  // first: the message may go to a pipe a hangup has closed
      out << (interactive ? "\n" : "") << "Stop requested: interFoam writes the current time and stops...\n"
          << std::flush;
      stop_sent = true;
      stop_time = std::chrono::steady_clock::now();
    }
    if (stop_sent && !ended &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - stop_time).count() > 120.0) {
      ended = util::stop_child(pid);
    }
    read_new();
    if (log.failed() && !ended) {
      ended = util::stop_child(pid);
      read_new();
    }
    const auto now = std::chrono::steady_clock::now();
    const double since = std::chrono::duration<double>(now - last_report).count();
    if (!ended && (interactive ? since >= 1.0 : since >= run.options.progress_interval_s)) {
      progress(false);
      last_report = now;
    }
  }
  progress(true);
  const std::string np_option = run.parallel ? " --np " + std::to_string(run.options.np) : std::string();
  if (stop_sent) {
    const auto written = latest_time(run.parallel ? dir / "processor0" : dir);
    throw OpenFoamError("interrupted: interFoam stopped at t = " + format_seconds(log.time_s().value_or(t_begin)) +
                        " s; latest time directory " + (written ? format_seconds(*written) + " s" : std::string("none")) +
                        ". Continue with `hydrojump vof " + dir.string() + " --resume" + np_option + "`.");
  }
  const auto last_written = latest_time(run.parallel ? dir / "processor0" : dir);
  const std::string resume_hint =
      last_written ? " The last time directory written is t = " + format_seconds(*last_written) +
                         " s (inspect it; a run that diverged may have written non-physical fields just "
                         "before stopping). To retry, lower maxCo/maxAlphaCo in system/controlDict, delete the "
                         "bad time directories and run `hydrojump vof DIR --resume`."
                   : std::string();
  if (log.failed() || ended->status() != 0) {
    const std::string why = log.failed() ? log.failure() : "the solver " + ended->describe();
    throw OpenFoamError("interFoam stopped in " + dir.string() + ": " + why + "." + resume_hint +
                        "\nLast lines of log.interFoam" + (log.failed() ? " up to the failure" : "") + ":\n" +
                        (log.failed() ? log.failure_context() : log.tail()));
  }
  const double reached = log.time_s().value_or(t_begin);
  if (reached < end_time_s * (1.0 - 1e-6) - 1e-12) {
    throw OpenFoamError("interFoam ended at t = " + format_seconds(reached) + " s before the end time " +
                        format_seconds(end_time_s) + " s." + resume_hint + "\nLast lines of log.interFoam:\n" +
                        log.tail());
  }
  return reached;
}

}  // namespace

std::optional<std::string> openfoam_path_problem(const fs::path& dir) {
  const std::string path = fs::absolute(dir).lexically_normal().string();
  for (const char ch : path) {
    if (std::isspace(static_cast<unsigned char>(ch)) || ch == '"' || ch == '\'') {
      return "OpenFOAM cannot run a case in " + path + ": its path holds a " +
             (ch == ' ' ? std::string("blank") : std::isspace(static_cast<unsigned char>(ch)) ? std::string("white-space character") : std::string("quote")) +
             ", which OpenFOAM v1912 strips from file names (its utilities then look elsewhere); use a directory whose "
             "path has none";
    }
  }
  return std::nullopt;
}

std::optional<double> latest_time(const fs::path& case_dir) {
  const auto times = util::time_directories(case_dir, 0.0);
  if (times.empty()) return std::nullopt;
  return times.back().time_s;
}

std::vector<SolverLeg> plan_solver_legs(double start_s, double end_s, std::optional<double> interval) {
  if (!(end_s > start_s)) return {};  // the run already reached its end time
  if (!interval) return {SolverLeg{end_s, std::nullopt}};
  const double dt = *interval, eps = 1e-6;
  const double first = std::ceil(start_s / dt - eps) * dt;
  const double last = std::floor(end_s / dt + eps) * dt;
  auto on = [&](double a, double b) { return std::abs(a - b) <= eps * dt; };
  if (first > last + eps * dt) return {SolverLeg{end_s, end_s - start_s}};  // no grid time in between
  std::vector<SolverLeg> legs;
  if (!on(first, start_s)) legs.push_back(SolverLeg{on(first, end_s) ? end_s : first, first - start_s});
  if (last > first + eps * dt) legs.push_back(SolverLeg{on(last, end_s) ? end_s : last, std::nullopt});
  if (!on(last, end_s)) legs.push_back(SolverLeg{end_s, end_s - last});
  return legs;
}

std::vector<SolverLeg> split_legs_for_control(const std::vector<SolverLeg>& legs, double start_s, double interval_s) {
  if (!(interval_s > 0.0)) return legs;
  std::vector<SolverLeg> out;
  double begin = start_s;
  for (const SolverLeg& leg : legs) {
    if (!leg.write_interval_s) {
      // at k interval from t = 0, so that a resumed run acts when an uninterrupted one would
      const double eps = 1e-6 * interval_s;
      for (double k = std::floor((begin + eps) / interval_s) + 1.0; k * interval_s < leg.end_s - eps; k += 1.0) {
        out.push_back(SolverLeg{k * interval_s, std::nullopt});
      }
    }
    out.push_back(leg);
    begin = leg.end_s;
  }
  return out;
}

namespace {

// After a leg that ended at `leg_end_s` (started at leg_start_s): the law's step from the leg's outputs,
// logged, and the outlet's Umean rewritten in the latest time directory (each processor's when decomposed).
void tailwater_control_after_leg(const fs::path& dir, const TailwaterControlLaw& law, double thickness_m,
                                 double max_time_step_s, bool parallel, double leg_start_s, double leg_end_s,
                                 std::ostream& out) {
  const double tol = 1e-6 * std::max(law.interval_s, 1e-3);
  // The step integrates from the previous step (the log's last row at or before the leg's start), not
  // from the leg's start: a run resumed between two control times, or after a step that was never
  // logged (the runner killed between the leg's end and its log row), still moves the volume target by
  // the toe over the whole time since that step.
  std::optional<double> previous_target;
  double previous_step_s = 0.0;
  for (const TailwaterControlStep& s : read_tailwater_control_log(dir)) {
    if (s.time_s <= leg_start_s + tol) {
      previous_target = s.volume_target_m2;
      previous_step_s = s.time_s;
    }
  }
  std::vector<double> toes;
  int samples = 0;
  const fs::path surfaces = dir / "postProcessing" / free_surface_function;
  std::vector<double> x, z;
  for (const auto& [t, time_dir] : util::time_directories(surfaces)) {
    if (t <= previous_step_s + tol || t > leg_end_s + tol) continue;
    // Before a resume, a stop wrote its time off the output grid (4.41491 s): an uninterrupted run has
    // no sample there, so the step does not count it either.
    const double k = t / law.output_interval_s;
    if (t <= leg_start_s + tol && std::abs(k - std::round(k)) > 1e-6 * std::max(1.0, k)) continue;
    const fs::path file = time_dir / free_surface_file;
    if (!fs::exists(file)) continue;
    ++samples;
    try {
      read_surface_points(file, x, z);
    } catch (const std::exception& e) {
      throw OpenFoamError(std::string("tailwater control: ") + e.what());
    }
    toes.push_back(toe_on_surface(x, z, law.toe_search_from_m, law.outlet_x_m, law.inflow_depth_m));
  }
  if (samples == 0) {
    throw OpenFoamError("tailwater control: no free surface (" + std::string(free_surface_file) + ") in " +
                        surfaces.string() + " for (" + format_seconds(previous_step_s) + ", " + format_seconds(leg_end_s) +
                        "] s (the case's controlDict lacks the freeSurface function object: regenerate the case)");
  }
  // The volume at the leg's end: a row of this leg's last time step, not one left by an earlier run.
  const fs::path volume_dir = dir / "postProcessing" / water_volume_function;
  std::optional<std::pair<double, double>> volume_m3;
  for (const auto& row : read_surface_field_value(volume_dir, "volFieldValue.dat")) {
    if (row.first <= leg_end_s + tol) volume_m3 = row;
  }
  if (!volume_m3 || volume_m3->first < leg_end_s - max_time_step_s - tol) {
    throw OpenFoamError("tailwater control: no water volume at t = " + format_seconds(leg_end_s) + " s in " +
                        volume_dir.string() + "/*/volFieldValue.dat" +
                        (volume_m3 ? " (its last row before is at t = " + format_seconds(volume_m3->first) + " s)"
                                   : std::string(" (the case's controlDict lacks the water_volume function object: "
                                                 "regenerate the case)")));
  }
  const TailwaterControlStep step = tailwater_control_step(law, previous_target, leg_end_s, leg_end_s - previous_step_s,
                                                          toes, volume_m3->second / thickness_m);
  std::vector<fs::path> u_files;
  if (parallel) {
    for (const fs::path& rank : processor_directories(dir)) {
      const auto times = util::time_directories(rank, 0.0);
      if (!times.empty()) u_files.push_back(times.back().path / "U");
    }
  } else {
    const auto times = util::time_directories(dir, 0.0);
    if (!times.empty()) u_files.push_back(times.back().path / "U");
  }
  if (u_files.empty()) throw OpenFoamError("tailwater control: no time directory in " + dir.string());
  for (const fs::path& f : u_files) {
    if (!fs::exists(f) && fs::exists(f.string() + ".gz")) {
      throw OpenFoamError("tailwater control: " + f.string() + ".gz is compressed, but the control rewrites the "
                          "outlet's Umean in plain field files (a case with tailwater.control = \"hold_toe\" is "
                          "written with writeCompression off: regenerate it with `hydrojump generate`)");
    }
  }
  const double previous_umean = read_outlet_mean_velocity(u_files.front());
  for (const fs::path& f : u_files) write_outlet_mean_velocity(f, step.outlet_mean_velocity_m_s);
  append_tailwater_control_log(dir, step);
  std::ostringstream line;
  line << std::setprecision(4) << "  tailwater control at t = " << format_seconds(leg_end_s) << " s: toe ";
  if (step.toe_outputs > 0) {
    line << step.toe_x_m << " m (" << step.toe_outputs << " outputs)";
  } else {
    line << "none (counted at the outlet)";
  }
  line << ", target " << law.target_toe_x_m << " m; water " << step.water_volume_m2 << " m2, target "
       << step.volume_target_m2 << " m2; outlet Umean " << previous_umean << " -> " << step.outlet_mean_velocity_m_s
       << " m/s\n";
  out << line.str() << std::flush;
}

// After a parallel run stopped early (interrupted, diverged, or stopped by the tailwater control): the
// complete times the processors wrote reconstructed into `dir` (reconstructPar -newTimes), so that
// `compare`, ParaView and a serial resume see them; processor*/ stay for `--resume --np N`. Returns a
// sentence for the error message (empty when there was nothing to reconstruct).
std::string reconstruct_written_times(const StepPlace& place, int np) {
  const fs::path& dir = place.dir;
  auto times = util::time_directories(dir / "processor0", 0.0);
  while (!times.empty() && !time_directory_complete(times.back().path)) times.pop_back();
  const auto reconstructed = latest_time(dir);
  if (times.empty() || (reconstructed && *reconstructed >= times.back().time_s - 1e-12)) return "";
  const std::string last = times.back().path.filename().string();
  try {
    run_step(place, {"reconstructPar", "-newTimes", "-time", ":" + last}, "log.reconstructPar", AfterStopRequest::run);
  } catch (const OpenFoamError& e) {
    const std::string why = e.what();
    return "\nThe times written so far are only in processor*/: reconstructPar failed (" +
           why.substr(0, why.find('\n')) + ").";
  }
  return "\nThe times written up to t = " + last + " s were reconstructed into " + dir.string() +
         " (for `hydrojump compare` and ParaView); processor*/ are kept for `--resume --np " + std::to_string(np) + "`.";
}

}  // namespace

namespace {

void run_vof_case_steps(const fs::path& dir, const RunOptions& options, std::ostream& out) {
  if (options.np < 1) throw OpenFoamError("--np must be >= 1");
  const fs::path spec_file = dir / "case.toml";
  if (!fs::exists(spec_file)) {
    throw OpenFoamError(dir.string() + " is not a generated OpenFOAM case: " + spec_file.string() +
                        " is missing (write it with `hydrojump generate SPEC --out DIR`)");
  }
  // One process per case directory (a second one stops here, naming the first).
  const util::DirectoryLock lock(dir, "hydrojump vof");
  // What a run killed outright left half-written (its complete files are all in place).
  util::remove_orphaned_temporaries(dir);
  util::remove_orphaned_temporaries(dir / "system");
  const StepPlace place{dir, out, lock};
  // Ctrl-C, SIGTERM or a hangup from here on stop the run at its next safe point.
  const StopRequestGuard stop_guard;
  restore_control_dict_left_behind(dir, out);
  remove_cut_short_decomposition(dir, out);
  const cases::Study study = cases::load_study(spec_file);
  if (study.cases.size() != 1 || study.cases.front().resolutions.size() != 1) {
    throw OpenFoamError(spec_file.string() + " must hold exactly one case with one resolution table "
                        "(the resolved case written by `hydrojump generate`)");
  }
  const cases::Case& c = study.cases.front();
  if (const auto reason = vof_unsupported_reason(c)) throw OpenFoamError(*reason);
  for (const char* f : {"system/controlDict", "system/blockMeshDict", "system/setFieldsDict", "0.orig/U"}) {
    if (!fs::exists(dir / f)) {
      throw OpenFoamError(dir.string() + " is not a complete OpenFOAM case: " + f +
                          " is missing (regenerate it with `hydrojump generate`)");
    }
  }
  // The dictionaries were written from the case.toml `generate` wrote (it rewrites both together): a
  // run starting afresh from an edited one would record settings its dictionaries do not have. (A
  // first run that failed before its first output starts afresh too; a resumed one is checked
  // against its record below.)
  const bool starts_afresh = !latest_time(dir) && !latest_time(dir / "processor0");
  if (const fs::path generated = dir / generated_case_file_name; starts_afresh && fs::exists(generated)) {
    const auto d = cases::first_setting_difference(util::read_text_file(generated), util::read_text_file(spec_file));
    if (d.any()) {
      throw OpenFoamError(spec_file.string() + " was edited after `hydrojump generate` wrote the OpenFOAM dictionaries "
                          "from it: it has '" + d.b + "' where they were written with '" + d.a +
                          "'. Run `hydrojump generate` again to rewrite them from it (or restore the line).");
    }
  }
  const std::string resolution = c.resolutions.begin()->first;
  const VofCase vof = build_vof_case(study, c, resolution);

  const OpenFoamInstallation inst = check_openfoam(options.np > 1);
  out << "OpenFOAM " << (inst.version.empty() ? "?" : inst.version) << " (WM_PROJECT_DIR="
      << inst.project_dir.string() << "), case \"" << c.id << "\", resolution \"" << resolution << "\", "
      << vof.mesh.strategy << " mesh of " << vof.mesh.cell_count() << " cells, "
      << (options.np > 1 ? std::to_string(options.np) + " MPI ranks" : std::string("serial")) << "\n";

  if (vof.mesh.strategy == "body_fitted") {
    out << "Self-test of interFoam on faces not aligned with the axes (body_fitted mesh)...\n" << std::flush;
    const SelfTestResult st = self_test_non_orthogonal(dir);
    if (!st.axis_aligned_ok) {
      throw OpenFoamError("interFoam does not keep still water at rest even on an axis-aligned mesh: " +
                          st.summary() + ". This OpenFOAM installation is not usable.");
    }
    if (!st.sheared_ok && options.force_body_fitted) {
      out << "  WARNING: " << st.summary() << "; running the body_fitted mesh anyway (--force-body-fitted): "
          << "expect divergence on this build\n";
    } else if (!st.sheared_ok) {
      throw OpenFoamError(
          "vof.mesh_strategy = \"body_fitted\" refused: this OpenFOAM build has the known defect of "
          "interFoam on faces not aligned with the coordinate axes (fvc::reconstruct returns wrong "
          "vertical velocities and the run diverges within a few steps); self-test: " + st.summary() +
          ". Use mesh_strategy = \"cartesian_cut\" (a staircase bed, every face axis-aligned), which runs "
          "correctly on this build.");
    }
    if (st.sheared_ok) out << "  " << st.summary() << "\n";
  }

  // Processor directories from an earlier parallel run.
  const int existing_ranks = static_cast<int>(processor_directories(dir).size());
  const bool parallel = options.np > 1;

  // Where to start: the decomposed results when continuing in parallel and they are the newest,
  // else the reconstructed (or serial) ones.
  const std::optional<double> start_decomposed =
      existing_ranks > 0 ? latest_time(dir / "processor0") : std::nullopt;
  const std::optional<double> start_serial = latest_time(dir);
  const bool continue_decomposed =
      parallel && start_decomposed && (!start_serial || *start_decomposed >= *start_serial);
  std::optional<double> start = continue_decomposed ? start_decomposed : start_serial;
  const bool mesh_exists = fs::exists(dir / "constant/polyMesh/owner") || fs::exists(dir / "constant/polyMesh/owner.gz");
  if (start && options.map_from) {
    throw OpenFoamError("--map-from starts a new run, but " + dir.string() + " already holds results up to t = " +
                        format_seconds(*start) + " s: generate a fresh case directory for the mapped run");
  }
  const std::optional<MapSource> map_source =
      options.map_from ? std::optional<MapSource>(check_map_source(*options.map_from, dir, c.id)) : std::nullopt;
  if (start && !options.resume) {
    throw OpenFoamError(dir.string() + " already holds results up to t = " + format_seconds(*start) +
                        " s: use --resume to continue from there, or delete the time directories to "
                        "start again");
  }
  if (options.resume && start) {
    // The dictionaries were written from the case the run started with: an edited case.toml would
    // describe other results (checked before anything is moved).
    cases::require_results_of(dir, dir / "case.toml");
    if (continue_decomposed && existing_ranks != options.np) {
      throw OpenFoamError(dir.string() + " was decomposed for " + std::to_string(existing_ranks) +
                          " MPI ranks: resume with --np " + std::to_string(existing_ranks));
    }
    if (!parallel && existing_ranks > 0 && latest_time(dir / "processor0").value_or(0.0) > *start + 1e-12) {
      throw OpenFoamError(dir.string() + " holds newer parallel results in processor*/: resume with --np " +
                          std::to_string(existing_ranks));
    }
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
    start = times.empty() ? std::nullopt : std::optional<double>(times.rbegin()->first);
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
  }

  // The end time: system/controlDict's endTime, which --end-time rewrites (to extend a run).
  double end_time_s = read_end_time_entry(dir).value_s;
  if (options.end_time_s) {
    if (*options.end_time_s > c.run.latest_end_time_s()) {
      throw OpenFoamError("--end-time " + format_seconds(*options.end_time_s) + " s is out of range for " +
                          spec_file.string() + ": must be <= " + format_seconds(c.run.latest_end_time_s()) +
                          " s (at most 100000 outputs, one every " + format_seconds(c.run.output_interval_s) +
                          " s, and at most 100000 s)");
    }
    if (!(*options.end_time_s > 0.0) || (start && *options.end_time_s <= *start + 1e-12)) {
      throw OpenFoamError("--end-time " + format_seconds(*options.end_time_s) + " s: must be after " +
                          (start ? "the latest time " + format_seconds(*start) + " s of " + dir.string()
                                 : std::string("t = 0")));
    }
    if (std::abs(*options.end_time_s - end_time_s) > 1e-12) {
      set_control_dict_end_time(dir, *options.end_time_s);
      out << "End time " << format_seconds(*options.end_time_s) << " s (was " << format_seconds(end_time_s)
          << " s; system/controlDict updated)\n";
      end_time_s = *options.end_time_s;
    }
  } else if (start && *start >= end_time_s - 1e-12) {
    out << "The run already reached its end time " << format_seconds(end_time_s)
        << " s (extend it with --resume --end-time T)\n";
  }

  const auto wall_begin = std::chrono::steady_clock::now();
  if (!start) {
    // What `compare` and `generate` check these results against.
    cases::record_results_case(dir);
    // ---- mesh, check, initial fields
    out << "Meshing (" << vof.mesh.strategy << ")\n";
    std::map<std::string, int> used;
    for (const FoamStep& step : vof.mesh_steps) {
      std::vector<std::string> argv = {step.application};
      argv.insert(argv.end(), step.arguments.begin(), step.arguments.end());
      const int k = used[step.application]++;
      run_step(place, argv, "log." + step.application + (k > 0 ? "." + std::to_string(k + 1) : ""));
    }
    out << "Checking the mesh\n";
    run_step(place, {"checkMesh"}, "log.checkMesh");
    {
      const std::string text = util::read_text_file(dir / "log.checkMesh");
      if (text.find("Mesh OK.") == std::string::npos) {
        std::string report;
        std::istringstream lines(text);
        std::string line;
        while (std::getline(lines, line)) {
          if (line.find("***") != std::string::npos || line.find("Failed") != std::string::npos) {
            report += "    " + line + "\n";
          }
        }
        throw OpenFoamError("checkMesh found a bad mesh in " + dir.string() + " (full report in log.checkMesh):\n" +
                            report);
      }
    }
    out << "Initial fields\n";
    std::error_code ec;
    fs::remove_all(dir / "0", ec);
    fs::copy(dir / "0.orig", dir / "0", fs::copy_options::recursive);
    run_step(place, {"setFields"}, "log.setFields");
    if (map_source) map_initial_state(place, *map_source);
  } else {
    out << "Resuming from t = " << format_seconds(*start) << " s"
        << (mesh_exists ? "" : " (no mesh found: run without --resume)") << "\n";
    if (!mesh_exists) throw OpenFoamError("cannot resume " + dir.string() + ": constant/polyMesh is missing");
  }

  // ---- solver
  std::vector<std::string> solver = {"interFoam"};
  if (parallel) {
    const bool decomposed_current = start && continue_decomposed && existing_ranks == options.np;
    if (!decomposed_current) {
      util::write_file_atomically(
          dir / "system/decomposeParDict",
          foam::format_file({"dictionary", "system", "decomposeParDict"}, decompose_par_dict(options.np)));
      std::vector<std::string> argv = {"decomposePar", "-force"};
      if (start) argv.push_back("-latestTime");
      // Until it has finished, processor*/ are not a decomposition to resume from.
      if (stop_requests > 0) throw StepStopped("interrupted: stopped on request before decomposePar.");
      util::write_file_atomically(dir / decomposing_marker, "decomposePar started by hydrojump vof\n");
      run_step(place, argv, "log.decomposePar");
      fs::remove(dir / decomposing_marker);
    }
    solver = {"mpirun"};
    if (::geteuid() == 0) solver.push_back("--allow-run-as-root");
    if (static_cast<unsigned>(options.np) > std::thread::hardware_concurrency()) solver.push_back("--oversubscribe");
    for (const std::string& a : {std::string("-np"), std::to_string(options.np), std::string("-x"),
                                 std::string("WM_PROJECT_DIR"), std::string("interFoam"), std::string("-parallel")}) {
      solver.push_back(a);
    }
  }
  const SolverRun run{dir, c, vof.mesh.thickness_m, solver, parallel, options, end_time_s, lock};
  // Legs that keep every output on the case's grid (plan_solver_legs): usually one.
  const double t_begin = start.value_or(0.0);
  std::optional<double> leg_start = start;
  double reached = t_begin;
  std::vector<SolverLeg> legs = plan_solver_legs(t_begin, end_time_s, output_grid_interval(dir));
  std::optional<TailwaterControlLaw> control;
  if (c.holds_toe()) {
    control = tailwater_control_law(c, cases::make_geometry(c, study.fluid));
    legs = split_legs_for_control(legs, t_begin, control->interval_s);
    // The log describes this run: rows of an abandoned later part or of an earlier run go.
    truncate_tailwater_control_log(dir, start);
    std::ostringstream line;
    line << "Tailwater control (hold_toe): every " << format_seconds(control->interval_s)
         << " s the outlet's Umean is reset to hold the water volume, and the volume moved to bring the toe to x = "
         << control->target_toe_x_m << " m (log: " << tailwater_control_log << ")\n";
    out << line.str();
  }
  // A parallel run that stops early leaves its written times where compare and ParaView look.
  // Between two steps (after a leg, during the control step) a stop request ends the run here.
  const auto stop_if_requested = [&]() {
    if (stop_requests == 0) return;
    const auto written = latest_time(parallel ? dir / "processor0" : dir);
    throw OpenFoamError("interrupted: stopped on request with the latest time directory at " +
                        (written ? "t = " + format_seconds(*written) + " s" : std::string("none")) +
                        ". Continue with `hydrojump vof " + dir.string() + " --resume" +
                        (parallel ? " --np " + std::to_string(options.np) : std::string()) + "`.");
  };
  try {
    for (const SolverLeg& leg : legs) {
      stop_if_requested();
      std::optional<ControlDictOverride> leg_control;
      if (leg.write_interval_s || std::abs(leg.end_s - end_time_s) > 1e-12) {
        if (leg_start && leg.write_interval_s && leg.end_s < end_time_s) {
          out << "Aligning with the output times: t = " << format_seconds(*leg_start)
              << " s lies between two of them, so interFoam first runs to t = " << format_seconds(leg.end_s)
              << " s (it counts its write times from where it starts)\n";
        } else if (leg.write_interval_s) {
          out << "The end time " << format_seconds(end_time_s)
              << " s lies between two output times: interFoam runs to the last one, then to the end time "
                 "in a closing leg that writes it\n";
        }
        leg_control.emplace(dir, leg);
      }
      reached = run_solver(run, leg_start, leg.end_s, out);
      if (leg_control) leg_control->restore(&out);
      if (control) {
        tailwater_control_after_leg(dir, *control, vof.mesh.thickness_m, c.vof.max_time_step_s, parallel,
                                    leg_start.value_or(0.0), leg.end_s, out);
      }
      leg_start = leg.end_s;
    }
  } catch (const OpenFoamError& e) {
    if (!parallel) throw;
    throw OpenFoamError(e.what() + reconstruct_written_times(place, options.np));
  }
  if (parallel) {
    std::vector<std::string> argv = {"reconstructPar"};
    if (start) argv.push_back("-newTimes");
    run_step(place, argv, "log.reconstructPar");
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_begin).count();
  out << "Done: case \"" << c.id << "\" reached t = " << format_seconds(reached) << " s in "
      << format_duration(wall) << " of wall time; fields in the time directories, section samples in "
      << (dir / "postProcessing").string() << "\n";
}

}  // namespace

void run_vof_case(const fs::path& dir_in, const RunOptions& options, std::ostream& out) {
  const fs::path dir = fs::absolute(dir_in);
  if (const auto problem = openfoam_path_problem(dir)) throw OpenFoamError(*problem);
  try {
    run_vof_case_steps(dir, options, out);
  } catch (const StepStopped& e) {
    // A utility stopped on request (meshing, decomposing, reconstructing): how to go on depends on
    // what the run has written.
    const bool written = latest_time(dir).has_value() || latest_time(dir / "processor0").has_value();
    const std::string np = options.np > 1 ? " --np " + std::to_string(options.np) : std::string();
    throw OpenFoamError(std::string(e.what()) +
                        (written ? " Continue with `hydrojump vof " + dir.string() + " --resume" + np + "`."
                                 : " Nothing was computed yet: run the same `hydrojump vof` command again to start "
                                   "over."));
  }
}

}  // namespace hydrojump::reference
