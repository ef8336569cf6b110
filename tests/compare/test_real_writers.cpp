// Integration with the project's own writers: `generate` writes case A (quick) for both methods; the
// SPH half's initial particle file (sph/vtk_output) and the OpenFOAM half's mesh and initial fields
// (blockMesh, topoSet, subsetMesh, setFields; compressed, staircase bed) are read back by the
// comparator as if they were results. Both describe the same initial water, so they must agree.
// Fails when the OpenFOAM tools are not installed (they are a dependency).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cases/spec_reader.hpp"
#include "compare/case_comparison.hpp"
#include "app/generate.hpp"
#include "../sph/basin_fixture.hpp"
#include "sph/basin_monitor.hpp"
#include "tests/temp_dir.hpp"

using namespace hydrojump;
using namespace hydrojump::compare;
namespace fs = std::filesystem;

TEST_CASE("The initial states written by the SPH generator and the OpenFOAM writer compare consistently",
          "[compare][integration]") {
  // OpenFOAM is a dependency (scripts/setup.sh installs Debian's openfoam): missing is a failure.
  REQUIRE((fs::exists("/usr/bin/blockMesh") && fs::exists("/usr/bin/setFields")));
  hydrojump::testing::TempDir tmp("writers");
  const cases::Study study = cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  const cases::Case* c = study.find_case("A");
  REQUIRE(c != nullptr);
  std::ostringstream log;
  app::generate_cases(study, {c}, "quick", tmp.path(), log);
  const fs::path run = tmp.path() / "A";
  REQUIRE(fs::exists(run / "sph" / "initial_particles.vtp"));

  const std::string cmd = "cd '" + (run / "vof").string() +
                          "' && export WM_PROJECT_DIR=/usr/share/openfoam && blockMesh > log.blockMesh 2>&1 && "
                          "topoSet > log.topoSet 2>&1 && subsetMesh fluidCells -patch bed -overwrite > "
                          "log.subsetMesh 2>&1 && rm -rf 0 && cp -r 0.orig 0 && setFields > log.setFields 2>&1";
  REQUIRE(std::system(cmd.c_str()) == 0);
  // Present both initial states as results at t = 7 s (inside the window 6-10 s).
  fs::copy(run / "vof" / "0", run / "vof" / "7", fs::copy_options::recursive);
  {
    std::ofstream pvd(run / "sph" / "particles.pvd");
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n"
           "<DataSet timestep=\"7\" part=\"0\" file=\"initial_particles.vtp\"/>\n</Collection>\n</VTKFile>\n";
  }
  CompareOptions options;
  options.plots = false;
  const CaseComparison r = compare_case_directory(run, options, log);
  INFO(log.str());
  REQUIRE(r.sph.available);
  REQUIRE(r.vof.available);
  const double dx = r.particle_spacing_m, y1 = r.inflow_depth_m, y2 = r.tailwater_depth_m;
  INFO("SPH y1 " << r.sph.metrics.upstream_depth_m << " y2 " << r.sph.metrics.sequent_depth_m << "; VOF y1 "
                 << r.vof.metrics.upstream_depth_m << " y2 " << r.vof.metrics.sequent_depth_m << "; surface RMS "
                 << r.surface.rms_m << " m, max " << r.surface.max_abs_m << " m");
  // Each writer puts the initial water where the spec says, within one particle spacing / bed cell.
  CHECK(r.sph.metrics.upstream_depth_m == Approx(y1).margin(dx));
  CHECK(r.vof.metrics.upstream_depth_m == Approx(y1).margin(r.vof_cell_size_m));
  CHECK(r.sph.metrics.sequent_depth_m == Approx(y2).margin(dx));
  CHECK(r.vof.metrics.sequent_depth_m == Approx(y2).margin(r.vof_cell_size_m));
  // The two agree along the basin (a coordinate or orientation mix-up would fail this at once).
  CHECK(r.surface.n_stations > 100);
  CHECK(r.surface.rms_m < dx);
  // The initial velocity u = q/h: the discharge at the downstream section is the inflow q.
  for (const MethodOutcome* m : {&r.sph, &r.vof}) {
    INFO(m->method);
    CHECK(m->stats.sections.back().discharge.mean == Approx(y1 * r.inflow_velocity_m_s).epsilon(0.10));
  }
}

namespace {

// The SPH run monitor of a stationary jump (basin_fixture's step at x = 0.5 m) over 0-2 s, outputs
// every 0.1 s, averaging window 1.5-2 s; inflow q = 0.05 m^2/s throughout, the outflow's volume since
// t = 0 being q * outflow_seconds(t).
template <class OutflowSeconds>
hydrojump::sph::BasinMonitor stationary_jump_monitor(OutflowSeconds outflow_seconds) {
  hydrojump::sph::BasinMonitorSetup s = basin_fixture::setup();
  s.average_end_s = 2.0;
  hydrojump::sph::BasinMonitor monitor(s);
  const hydrojump::sph::ParticleSet ps = basin_fixture::step_particles(0.5);
  const double rho_q = 1000.0 * 0.05;
  for (int k = 0; k <= 20; ++k) {
    const double t = 0.1 * k;
    monitor.record(ps, t, rho_q * t, rho_q * outflow_seconds(t));
  }
  return monitor;
}

}  // namespace

TEST_CASE("The comparator reads the SPH run monitor's verdict from its summary.json", "[compare][sph]") {
  hydrojump::testing::TempDir dir("sph_note");
  // A summary written by the SPH run monitor itself: a stationary jump, in = out = q, window 1.5-2 s.
  const auto monitor = stationary_jump_monitor([](double t) { return t; });
  std::ofstream(dir.path() / "summary.json") << monitor.summary_json();
  const std::string note = hydrojump::compare::sph_run_note(dir.path() / "summary.json");
  CHECK_THAT(note, Catch::Contains("jump in_basin"));
  CHECK_THAT(note, Catch::Contains("steady over the averaging window"));
  CHECK_THAT(note, Catch::Contains("steady from t = 1 s"));
  CHECK_THAT(note, Catch::Contains("outflow - inflow = 0 % of q"));
  CHECK_THAT(note, Catch::Contains("(steady by the window means)"));
  CHECK_THAT(note, Catch::Contains("its averaging window 1.5-2 s"));
  CHECK_THAT(note, !Catch::Contains("not for this comparison"));
  // Compared over the run's own window: nothing to warn, and the verdict's numbers; over another: the
  // verdicts are not for it.
  hydrojump::compare::RunBalance balance;
  CHECK_THAT(hydrojump::compare::sph_run_note(dir.path() / "summary.json", 1.5, 2.0, 1e-9, &balance),
             !Catch::Contains("not for this comparison"));
  CHECK(balance.imbalance == Approx(0.0).margin(1e-12));
  CHECK(balance.steady == true);
  CHECK_THAT(hydrojump::compare::sph_run_note(dir.path() / "summary.json", 0.5, 1.0),
             Catch::Contains("these verdicts are for the run's window, not for this comparison's 0.5-1 s"));
  CHECK(hydrojump::compare::sph_run_note(dir.path() / "absent.json").empty());
}

TEST_CASE("A damaged SPH summary.json or basin.csv is reported in the comparator's note, not dropped", "[compare][sph]") {
  hydrojump::testing::TempDir dir("sph_note_damaged");
  const auto monitor = stationary_jump_monitor([](double t) { return t; });
  const std::filesystem::path summary = dir.path() / "summary.json";
  // Truncated to nothing (a disk that filled up): the note says that the verdict is missing.
  std::ofstream(summary) << "{\n";
  CHECK_THAT(hydrojump::compare::sph_run_note(summary),
             Catch::Contains("summary.json): no jump_state in it") && Catch::Contains("verdict is not shown"));
  // A value that is not a number: named and left out, the rest of the verdict still given.
  std::string json = monitor.summary_json();
  const std::string key = "\"inflow_discharge_relative_error\": ";
  const auto at = json.find(key);
  REQUIRE(at != std::string::npos);
  json.replace(at + key.size(), json.find_first_of(",}\n", at + key.size()) - at - key.size(), "1.2.3x");
  std::ofstream(summary) << json;
  std::string note;
  REQUIRE_NOTHROW(note = hydrojump::compare::sph_run_note(summary));
  CHECK_THAT(note, Catch::Contains("jump in_basin"));
  CHECK_THAT(note, !Catch::Contains("inflow discharge error"));
  CHECK_THAT(note, Catch::Contains("holds values that are not numbers (inflow_discharge_relative_error = '1.2.3x')"));

  // basin.csv with a short row in its middle (damage) and a torn last line (a run still writing): the
  // damaged row is counted and the window not called steady; the torn last line is not damage.
  std::ofstream(summary) << monitor.summary_json();
  std::istringstream csv(monitor.csv());
  std::vector<std::string> lines;
  for (std::string line; std::getline(csv, line);) lines.push_back(line);
  REQUIRE(lines.size() > 10);
  const auto write_basin = [&](bool damage_middle) {
    std::ofstream out(dir.path() / "basin.csv");
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (damage_middle && i == lines.size() / 2) out << lines[i].substr(0, lines[i].find(',')) << "\n";
      else out << lines[i] << "\n";
    }
    out << lines.back().substr(0, lines.back().size() / 2);  // torn last line
  };
  write_basin(false);
  CHECK_THAT(hydrojump::compare::sph_run_note(summary, 0.5, 1.0), !Catch::Contains("damaged row"));
  write_basin(true);
  const std::string damaged = hydrojump::compare::sph_run_note(summary, 0.5, 1.0);
  INFO(damaged);
  CHECK_THAT(damaged, Catch::Contains("1 damaged row(s) of basin.csv (not as many cells as its header, text that is not a number, or no time) left out"));
  CHECK_THAT(damaged, Catch::Contains("(NOT steady by the window means)"));
  // A time that is not a number (t_s = "abc") is damage too, not a row at an unknown time.
  {
    std::ofstream out(dir.path() / "basin.csv");
    for (std::size_t i = 0; i < lines.size(); ++i)
      out << (i == lines.size() / 2 ? "abc" + lines[i].substr(lines[i].find(',')) : lines[i]) << "\n";
  }
  CHECK_THAT(hydrojump::compare::sph_run_note(summary, 0.5, 1.0),
             Catch::Contains("1 damaged row(s) of basin.csv") && Catch::Contains("(NOT steady by the window means)"));
}

TEST_CASE("Over another window the comparator recomputes the SPH water balance from basin.csv", "[compare][sph]") {
  hydrojump::testing::TempDir dir("sph_note_window");
  // The outflow carries 10 % more than q until t = 1 s (the basin drains), then exactly q; the toe
  // stands still. Window of the run 1.5-2 s.
  const auto monitor = stationary_jump_monitor([](double t) { return t + 0.1 * std::min(t, 1.0); });
  std::ofstream(dir.path() / "summary.json") << monitor.summary_json();
  const std::filesystem::path summary = dir.path() / "summary.json";
  // The run's own window: balanced, and nothing recomputed.
  const std::string own = hydrojump::compare::sph_run_note(summary, 1.5, 2.0);
  CHECK_THAT(own, Catch::Contains("(steady by the window means)"));
  CHECK_THAT(own, !Catch::Contains("this comparison's window"));
  // Without basin.csv the note says that it cannot recompute.
  CHECK_THAT(hydrojump::compare::sph_run_note(summary, 0.5, 1.0), Catch::Contains("no basin.csv beside it to recompute them"));
  std::ofstream(dir.path() / "basin.csv") << monitor.csv();
  // 0.5-1 s: q_out = 1.1 q throughout, so outflow - inflow = +10 % of q and the window is not steady.
  hydrojump::compare::RunBalance balance;
  const std::string early = hydrojump::compare::sph_run_note(summary, 0.5, 1.0, 1e-9, &balance);
  INFO(early);
  CHECK(balance.imbalance == Approx(0.1));
  CHECK(balance.steady == false);
  CHECK_THAT(early, Catch::Contains("over this comparison's window (basin.csv, outputs 0.5-1 s) outflow - inflow = 10 % of q"));
  CHECK_THAT(early, Catch::Contains("toe trend 0 m/s (NOT steady by the window means)"));
  // 0.5-1.5 s: half the window drains at +10 %, so +5 %.
  CHECK_THAT(hydrojump::compare::sph_run_note(summary, 0.5, 1.5), Catch::Contains("outflow - inflow = 5 % of q"));
  // A window reaching past the run's end (2 s): balanced, but not complete, so not called steady.
  CHECK_THAT(hydrojump::compare::sph_run_note(summary, 1.5, 2.5),
             Catch::Contains("the run has not reached 2.5 s (NOT steady by the window means)"));
  // A window past the run's end: no outputs to balance.
  CHECK_THAT(hydrojump::compare::sph_run_note(summary, 3.0, 4.0),
             Catch::Contains("basin.csv has 0 output(s) in this comparison's window, too few for its water balance"));
  // 1.2-1.8 s: balanced (to rounding) and steady.
  CHECK_THAT(hydrojump::compare::sph_run_note(summary, 1.2, 1.8),
             Catch::Contains("% of q, toe trend 0 m/s (steady by the window means)"));
}
