// Whether OpenFOAM can run a case here: the binaries on PATH, WM_PROJECT_DIR (default
// /usr/share/openfoam) and `interFoam -help` (check_openfoam), and a case path OpenFOAM v1912 would
// mangle (openfoam_path_problem).
#include <cctype>
#include <cstdlib>

#include <unistd.h>

#include "reference/foam_process.hpp"
#include "reference/runner.hpp"
#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"

namespace hydrojump::reference {

namespace fs = std::filesystem;

namespace {

constexpr const char* default_project_dir = "/usr/share/openfoam";

}  // namespace

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
    rc = detail::wait_for(detail::spawn({"interFoam", "-help"}, fs::temp_directory_path(), log, false));
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

}  // namespace hydrojump::reference
