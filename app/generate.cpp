#include "app/generate.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <pthread.h>
#include <signal.h>
#include <stdlib.h>

#include "cases/geometry.hpp"
#include "cases/hydraulics.hpp"
#include "util/cli_checks.hpp"
#include "util/fingerprint.hpp"
#include "cases/results_case.hpp"
#include "cases/spec_reader.hpp"
#include "reference/cli.hpp"
#include "sph/cli.hpp"

namespace hydrojump::app {
namespace {

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// The SPH viscosity model in a few words: "artificial alpha 0.1", "SPS l 0.0132 m free_slip".
std::string sph_model_text(const cases::SphSettings& s) {
  if (s.viscosity == cases::Viscosity::artificial)
    return s.artificial_viscosity_nu_m2_s > 0.0 ? "artificial nu " + fixed(s.artificial_viscosity_nu_m2_s * 1e3, 3) + "e-3"
                                                : "artificial alpha " + fixed(s.artificial_viscosity_alpha, 3);
  const std::string length = s.sps_mixing_length_m > 0.0 ? "l " + fixed(s.sps_mixing_length_m, 4) + " m"
                                                         : "Cs " + fixed(s.sps_smagorinsky_constant, 2);
  return "SPS " + length + " " + std::string(cases::option_name(s.viscous_wall_condition));
}

// Each basin's models and run after the rules (cases/case_rules.hpp): one line per case, so that a study
// that sets one model per method shows it, and one that does not shows where.
void print_models_and_runs(const cases::Study& study, int id_width, std::ostream& out) {
  bool header = false;
  for (const auto& c : study.cases) {
    if (!c.stilling_basin()) continue;
    if (!header) {
      out << "\n  models and runs (after the rules: l = c_l y2*, window from the sloshing period 2 L / sqrt(g y2*))\n"
          << "  " << std::left << std::setw(id_width) << "case" << std::setw(34) << "SPH viscosity"
          << std::setw(28) << "VOF turbulence" << "averaging window, s\n";
      header = true;
    }
    const std::string vof = std::string(cases::option_name(c.vof.turbulence_model)) +
                            (c.vof.turbulence_stabilization == cases::TurbulenceStabilization::none
                                 ? ""
                                 : " + " + std::string(cases::option_name(c.vof.turbulence_stabilization)));
    out << "  " << std::left << std::setw(id_width) << c.id << std::setw(34) << sph_model_text(c.sph) << std::setw(28)
        << vof << fixed(c.run.average_start_s, 1) << " - " << fixed(c.run.average_end_s, 1) << " (run "
        << fixed(c.run.end_time_s, 1) << ")\n";
  }
}

}  // namespace

void print_study_summary(const cases::Study& study, std::ostream& out) {
  out << "study \"" << study.name << "\" (" << study.source_file.string() << "): " << study.cases.size()
      << " case" << (study.cases.size() == 1 ? "" : "s") << "\n";
  if (!study.description.empty()) out << "  " << study.description << "\n";
  const double g = study.fluid.gravity_m_s2;
  bool basin_header = false;
  int id_width = 10;
  for (const auto& c : study.cases) id_width = std::max(id_width, static_cast<int>(c.id.size()) + 2);
  for (const auto& c : study.cases) {
    if (const auto* b = c.stilling_basin()) {
      if (!basin_header) {
        out << "\n  stilling basins (q per unit width; E above the local floor; y2 m: the case's tailwater depth, "
               "eta with it: the initial level under\n  control hold_toe, where the solvers predict y2; the held "
               "depth under fixed_depth, where y2 and eta are imposed)\n";
        out << "  " << std::left << std::setw(id_width) << "case" << std::setw(12) << "bed" << std::right
            << std::setw(8) << "y1 m" << std::setw(8) << "U1 m/s" << std::setw(10) << "q m2/s"
            << std::setw(7) << "Fr1" << std::setw(9) << "y2* m" << std::setw(9) << "y2 m" << std::setw(9)
            << "E1 m" << std::setw(9) << "E2 m" << std::setw(9) << "eta %" << std::setw(11) << "eta* %"
            << std::setw(11) << "lab eta %" << "  control" << "\n";
        basin_header = true;
      }
      const auto j = cases::jump_hydraulics(b->inflow_depth_m, b->inflow_velocity_m_s,
                                            b->tailwater_depth_m, g);
      std::string bed = b->bed.profile == cases::BedShape::sinusoidal
                            ? "S" + fixed(b->bed.wavelength_m * 1000, 0) + "/T" + fixed(b->bed.height_m * 1000, 0)
                            : "smooth";
      out << "  " << std::left << std::setw(id_width) << c.id << std::setw(12) << bed << std::right
          << std::setw(8) << fixed(b->inflow_depth_m, 4) << std::setw(8) << fixed(b->inflow_velocity_m_s, 2)
          << std::setw(10) << fixed(j.discharge_m2_s, 4) << std::setw(7) << fixed(j.froude1, 2)
          << std::setw(9) << fixed(j.belanger_y2_m, 3) << std::setw(9) << fixed(b->tailwater_depth_m, 3)
          << std::setw(9) << fixed(j.e1_m, 4) << std::setw(9) << fixed(j.e2_m, 4) << std::setw(9)
          << fixed(100 * j.eta, 2) << std::setw(11) << fixed(100 * j.eta_smooth, 2) << std::setw(11)
          << (b->measured.eta_percent ? fixed(*b->measured.eta_percent, 2) : std::string("-")) << "  "
          << cases::option_name(b->control.mode) << "\n";
    }
  }
  print_models_and_runs(study, id_width, out);
  for (const auto& c : study.cases) {
    if (c.stilling_basin()) continue;
    out << "\n  " << c.id << " (" << c.kind << "): " << c.description << "\n";
    const auto geo = cases::make_geometry(c, study.fluid);
    out << "    domain x " << geo.x_min_m << ".." << geo.x_max_m << " m, z " << geo.z_min_m << ".."
        << geo.z_max_m << " m; H_max " << geo.max_water_height_m << " m; expected max speed "
        << fixed(geo.max_flow_speed_m_s, 3) << " m/s\n";
  }
  // Each case's levels, one line per distinct set (the study's rule scales them with a basin's y1).
  std::vector<std::pair<std::string, std::vector<std::string>>> sets;  // levels text, cases
  for (const auto& c : study.cases) {
    std::ostringstream levels;
    for (const auto& [name, r] : c.resolutions)
      levels << "  " << name << " (SPH dx " << r.particle_spacing_m << " m, VOF " << r.vof_cell_size_bed_m << "/"
             << r.vof_cell_size_bulk_m << " m)";
    auto it = std::find_if(sets.begin(), sets.end(), [&](const auto& s) { return s.first == levels.str(); });
    if (it == sets.end()) sets.push_back({levels.str(), {c.id}});
    else it->second.push_back(c.id);
  }
  out << "\n  resolutions";
  if (study.resolution_for_inflow_depth_m)
    out << " (given for y1 = " << *study.resolution_for_inflow_depth_m << " m; each basin's scaled by its own y1)";
  out << ":\n";
  for (const auto& [levels, ids] : sets) {
    out << "   ";
    if (sets.size() > 1) {
      out << " ";
      for (std::size_t i = 0; i < ids.size(); ++i) out << (i ? "," : "") << ids[i];
      out << ":";
    }
    out << levels << "\n";
  }
}

namespace {

// The input of both solvers for one case: DIR/sph and DIR/vof.
void write_case(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                const std::filesystem::path& dir) {
  sph::write_sph_input(study, c, resolution, dir / "sph");
  reference::write_vof_case(study, c, resolution, dir / "vof");
}

// Writes case `c` into `dir` as `generate` would, reporting what the solvers' derivations refuse
// (particle generation, gates, the OpenFOAM mesh plan) as an error of the spec: its file, the case
// and the resolution.
void write_trial_case(const cases::Study& study, const cases::Case& c, const std::string& resolution,
                      const std::filesystem::path& dir) {
  // The derivations refuse a case with std::invalid_argument; anything else (a full disk, memory)
  // is not the spec's fault and passes unchanged.
  try {
    write_case(study, c, resolution, dir);
  } catch (const std::invalid_argument& e) {
    // The derivations name the case themselves (for `hydrojump vof DIR`); here it is named once.
    std::string what = e.what();
    const std::string named = "case \"" + c.id + "\": ";
    if (what.rfind(named, 0) == 0) what.erase(0, named.size());
    throw cases::SpecError(study.source_file.string() + ": case \"" + c.id + "\" at resolution \"" + resolution +
                           "\": " + what);
  }
}

// A fresh directory under the system's temporary directory, removed with its contents at scope exit.
// Ctrl-C, SIGTERM and a hangup are held back (blocked in this thread) while it exists and act once it
// is removed, so that an interrupted `check` or `generate` leaves no scratch directory behind; a long
// loop polls stop_requested() and ends early (its exception unwinds through the removal).
class ScratchDirectory {
 public:
  ScratchDirectory() {
    // (The name first: temp_directory_path() throws for a TMPDIR that does not exist, and the mask
    // must not stay blocked then.)
    std::string name = (std::filesystem::temp_directory_path() / "hydrojump-generate-XXXXXX").string();
    sigset_t stops;
    sigemptyset(&stops);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&stops, sig);
    ::pthread_sigmask(SIG_BLOCK, &stops, &previous_mask_);
    if (::mkdtemp(name.data()) == nullptr) {
      const int error = errno;
      ::pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
      throw std::runtime_error("cannot create a scratch directory under " + std::filesystem::temp_directory_path().string() +
                               ": " + std::strerror(error));
    }
    path_ = name;
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
    ::pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);  // a stop request held back acts now
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

  // Whether a stop request is waiting (held back since this directory was made). A signal this
  // process ignores (SIGHUP under nohup) stays pending while blocked on Linux but is no request.
  bool stop_requested() const {
    sigset_t pending;
    sigemptyset(&pending);
    ::sigpending(&pending);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
      if (sigismember(&pending, sig) != 1) continue;
      struct sigaction disposition {};
      if (::sigaction(sig, nullptr, &disposition) == 0 && disposition.sa_handler == SIG_IGN) continue;
      return true;
    }
    return false;
  }

 private:
  std::filesystem::path path_;
  sigset_t previous_mask_{};
};

// The spec's rules for every selected case at `resolution`, then what only the solvers' derivations
// find: each case written into `scratch`/<id> (the caller's scratch directory, which `generate` reads
// the resolved case.toml files back from).
void write_trial_cases(const cases::Study& study, const std::vector<const cases::Case*>& selected,
                       const std::string& resolution, const std::filesystem::path& scratch) {
  for (const auto* c : selected) cases::validate_for_resolution(study, *c, resolution);
  for (const auto* c : selected) write_trial_case(study, *c, resolution, scratch / c->id);
}

}  // namespace

std::vector<const cases::Case*> select_cases(const cases::Study& study,
                                             const std::vector<std::string>& ids) {
  std::vector<const cases::Case*> selected;
  // "all" (alone; no case may be called so) is every case, as no ids are.
  const bool all = std::find(ids.begin(), ids.end(), "all") != ids.end();
  if (all && ids.size() > 1)
    throw cases::SpecError(study.source_file.string() + ": case \"all\" selects every case and cannot be combined "
                           "with other case ids; give either \"all\" or the ids");
  if (ids.empty() || all) {
    for (const auto& c : study.cases) selected.push_back(&c);
    return selected;
  }
  for (const auto& id : ids) {
    const auto* c = study.find_case(id);
    if (!c) {
      std::string known;
      for (const auto& k : study.cases) known += (known.empty() ? "" : ", ") + k.id;
      throw cases::SpecError(study.source_file.string() + ": case \"" + id +
                             "\": no such case (cases in this study: " + known + "; \"all\" for every case)");
    }
    // A case named twice runs once (two runs of one case would share its directory).
    if (std::find(selected.begin(), selected.end(), c) == selected.end()) selected.push_back(c);
  }
  return selected;
}

void check_cases(const cases::Study& study, const std::vector<const cases::Case*>& selected,
                 const std::string& resolution) {
  const ScratchDirectory scratch;
  write_trial_cases(study, selected, resolution, scratch.path());
}

void generate_cases(const cases::Study& study, const std::vector<const cases::Case*>& selected,
                    const std::string& resolution, const std::filesystem::path& out_dir,
                    std::ostream& log) {
  // Validate everything first: nothing is written while any selected case is invalid. The spec's
  // rules, then what only the solvers' own derivations find (particle generation, gates, the
  // OpenFOAM mesh plan): every selected case is written once into a scratch directory that is
  // removed again, and a failure there is reported as the spec's, naming the file and the case.
  const ScratchDirectory scratch;
  write_trial_cases(study, selected, resolution, scratch.path());
  // A directory holding a run's results keeps them only for the case that made them: regenerating
  // it with other settings would leave results that `compare` then reports under the new ones.
  for (const auto* c : selected) {
    const auto dir = out_dir / c->id;
    for (const char* method : {"sph", "vof"}) {
      if (!cases::holds_results(dir / method)) continue;
      const auto recorded = cases::recorded_case_file(dir / method);
      const auto wanted = scratch.path() / c->id / method / "case.toml";
      if (!std::filesystem::exists(recorded))
        throw std::runtime_error((dir / method).string() + " holds the results of a run but no case.toml: move it away or choose another --out");
      const auto d = cases::first_setting_difference(util::read_text_file(recorded), util::read_text_file(wanted));
      if (d.any())
        throw std::runtime_error((dir / method).string() + " holds the results of a run of case \"" + c->id +
                                 "\" with other settings (its " + recorded.filename().string() + " has '" + d.a +
                                 "' where the spec now gives '" + d.b + "' from " + study.source_file.string() +
                                 " at resolution \"" + resolution + "\"): move it away or choose another --out");
    }
  }
  for (const auto* c : selected) {
    const auto dir = out_dir / c->id;
    write_case(study, *c, resolution, dir);
    log << "generated " << (dir / "sph").string() << " and " << (dir / "vof").string() << "\n";
  }
}

cases::Study load_spec_argument(const std::string& spec) {
  if (spec == "default" || spec == "embedded") return cases::load_embedded_default_study();
  return cases::load_study(spec);
}

void register_case_commands(CLI::App& app) {
  auto* check = app.add_subcommand(
      "check",
      "Validate a study spec and print every case with its derived quantities (q, Fr1, Belanger's y2*, "
      "E1, E2, eta); then generate every case at every resolution into a scratch directory (removed "
      "again), so that what the solvers' own derivations refuse is found here too. Exit status 2 and "
      "one message naming file, line and key (or file, case and resolution) if the spec is invalid.");
  auto check_spec = std::make_shared<std::string>();
  check->add_option("SPEC", *check_spec,
                    "study file (TOML), or \"default\" for the embedded cases/ead2002.toml")
      ->required();
  check->callback([check_spec] {
    const auto study = load_spec_argument(*check_spec);
    print_study_summary(study, std::cout);
    // What only the solvers' derivations find: every case at every resolution it defines is written
    // once, as `generate` would, into a scratch directory that is removed again.
    const ScratchDirectory scratch;
    for (const auto& c : study.cases)
      for (const auto& [resolution, level] : c.resolutions) {
        if (scratch.stop_requested()) throw std::runtime_error("check interrupted (its scratch directory was removed)");
        write_trial_case(study, c, resolution, scratch.path() / resolution / c.id);
      }
    std::cout << "every case generates at every resolution (" << study.cases.size() << " cases)\n";
  });

  struct GenerateOptions {
    std::string spec;
    std::filesystem::path out;
    std::vector<std::string> cases;
    std::string resolution = "quick";
  };
  auto options = std::make_shared<GenerateOptions>();
  auto* generate = app.add_subcommand(
      "generate",
      "Write the case directories of both solvers: OUT/<case>/sph/ (read by `hydrojump sph`) and "
      "OUT/<case>/vof/ (a complete OpenFOAM case, run by `hydrojump vof` or its Allrun), each with the "
      "resolved spec (case.toml) for provenance. Every selected case is validated first; nothing is "
      "written if one fails.");
  generate->add_option("SPEC", options->spec, "study file (TOML), or \"default\" for the embedded one")
      ->required();
  generate->add_option("--out,-o", options->out, "output directory")->required()->check(util::non_empty_path());
  generate->add_option("--case,-c", options->cases,
                       "case ids to generate, comma-separated or repeated (default or \"all\": every case)")
      ->delimiter(',');
  generate->add_option("--resolution,-r", options->resolution,
                       "resolution level defined in the spec (quick, default, fine)")
      ->capture_default_str();
  generate->callback([options] {
    const auto study = load_spec_argument(options->spec);
    generate_cases(study, select_cases(study, options->cases), options->resolution, options->out,
                   std::cout);
  });
}

}  // namespace hydrojump::app
