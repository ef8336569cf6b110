#include "compare/cli.hpp"

#include <cmath>
#include <iostream>
#include <string>
#include <memory>

#include "util/cli_checks.hpp"
#include "compare/case_comparison.hpp"
#include "compare/dam_break_report.hpp"

namespace hydrojump::compare {

namespace {
struct CompareCommandOptions {
  std::filesystem::path run_dir;
  std::filesystem::path out_dir;
  std::string interpolation = "mls_linear";
  std::vector<double> window;
  bool no_plots = false;
  std::filesystem::path sph_pvd;
  double station_spacing_m = 0.0;
};
// A dam break: the surge front of both methods against the measured one (dam_break_report.hpp).
// --interpolation, --window, --sph-pvd and --station-spacing belong to stilling basins.
void compare_dam_break_command(const cases::Study& study, const CompareCommandOptions& o) {
  if (!o.window.empty() || !o.sph_pvd.empty() || o.station_spacing_m > 0.0)
    throw CLI::ValidationError("a dam-break case compares the surge front over the whole run: --window, --sph-pvd "
                               "and --station-spacing are for stilling basins");
  const DamBreakComparison c = compare_dam_break(study, o.run_dir);
  const std::filesystem::path out = o.out_dir.empty() ? o.run_dir : o.out_dir;
  const std::string figures_problem = write_dam_break_report(c, out, !o.no_plots, std::cout);
  std::cout << dam_break_summary_text(c) << std::flush;
  if (!c.sph.available && !c.vof.available) {
    std::cerr << "hydrojump compare: neither result is available:\n  sph: " << c.sph.status
              << "\n  vof: " << c.vof.status << "\n";
    throw CLI::RuntimeError(1);
  }
  if (!figures_problem.empty()) {
    std::cerr << "hydrojump compare: the figure was not made (comparison.json, csv/front.csv and report.md were "
                 "written): " << figures_problem << "\n(--no-plots skips it)\n";
    throw CLI::RuntimeError(1);
  }
}

}  // namespace

void register_commands(CLI::App& app) {
  auto o = std::make_shared<CompareCommandOptions>();
  auto* cmd = app.add_subcommand(
      "compare",
      "Compare the SPH and VOF results of one case directory written by `hydrojump generate` (RUN_DIR/sph with "
      "its .pvd particle series, RUN_DIR/vof with the OpenFOAM case) on the case's sections over its averaging "
      "window: free surface, velocity profiles, discharge, kinetic-energy coefficient, specific energy, toe, "
      "sequent depth y2, jump and roller lengths, eta = (E1-E2)/E1, velocity decay; SPH vs VOF discrepancies and "
      "both against the laboratory values in the spec. Writes comparison.json, csv/*.csv, figures/*.png, "
      "report.md and report.html into RUN_DIR (or --out). A missing result is reported as missing. For a "
      "dam-break case: the surge front of both methods against the measured one, in the experiment's time origin "
      "(t_model = t_exp - 0.175 sqrt(L/(2g)), the gate's opening) and unshifted: comparison.json, csv/front.csv, "
      "figures/front.png, report.md.");
  cmd->add_option("RUN_DIR", o->run_dir, "case directory (holds sph/ and vof/)")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--out,-o", o->out_dir, "output directory (default: RUN_DIR)")->check(util::non_empty_path());
  cmd->add_option("--interpolation", o->interpolation,
                  "mls_linear: Shepard with a linear (moving-least-squares) correction, exact for linear fields; "
                  "shepard: plain Shepard normalisation")
      ->check(CLI::IsMember({"mls_linear", "shepard"}))
      ->capture_default_str();
  cmd->add_option("--window", o->window, "averaging window T0 T1 in s (default: the case's run.average_*)")
      ->expected(2);
  cmd->add_option("--sph-pvd", o->sph_pvd, "the SPH .pvd series (default: the one found under RUN_DIR/sph)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--station-spacing", o->station_spacing_m,
                  "spacing of the columns along the channel in m, at most y1 (default: the finer of SPH dx and the VOF bed cell; at most 3000 columns)")
      ->check(util::positive_finite_number());
  cmd->add_flag("--no-plots", o->no_plots, "skip the matplotlib figures");
  cmd->callback([o] {
    CompareOptions options;
    options.out_dir = o->out_dir;
    options.scheme = parse_interpolation_scheme(o->interpolation);
    if (o->window.size() == 2) {
      for (const double t : o->window)
        if (!std::isfinite(t) || t < 0.0)
          throw CLI::ValidationError("--window", "T0 and T1 must be finite times >= 0 s, got " + std::to_string(t));
      if (!(o->window[1] >= o->window[0])) throw CLI::ValidationError("--window", "T1 must be >= T0");
      options.window_start_s = o->window[0];
      options.window_end_s = o->window[1];
    }
    options.plots = !o->no_plots;
    options.sph_pvd = o->sph_pvd;
    options.station_spacing_m = o->station_spacing_m;
    if (const cases::Study study = load_run_case(o->run_dir); study.cases.front().dam_break() != nullptr) {
      compare_dam_break_command(study, *o);
      return;
    }
    const CaseComparison c = compare_case_directory(o->run_dir, options, std::cout);
    if (!c.sph.available && !c.vof.available) {
      std::cerr << "hydrojump compare: neither result is available:\n  sph: " << c.sph.status
                << "\n  vof: " << c.vof.status << "\n(the report lists them as missing)\n";
      throw CLI::RuntimeError(1);
    }
    // Exit 1, so that a study does not keep this comparison as finished (it would not redraw it).
    if (!c.figures_problem.empty()) {
      std::cerr << "hydrojump compare: the figures were not made (the tables, comparison.json and the report "
                   "were written): "
                << c.figures_problem << "\n(--no-plots skips them)\n";
      throw CLI::RuntimeError(1);
    }
  });
}

}  // namespace hydrojump::compare
