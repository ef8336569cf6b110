// End to end: a run directory with a synthetic hydraulic jump written as an SPH .pvd series and as an
// OpenFOAM case (by the test), compared with compare_case_directory; and the "missing result" paths.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <optional>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include "util/csv_table.hpp"
#include "util/fingerprint.hpp"
#include "cases/geometry.hpp"
#include "cases/hydraulics.hpp"
#include "cases/spec_reader.hpp"
#include "cases/output_times.hpp"
#include "compare/case_comparison.hpp"
#include "compare/plots.hpp"
#include "compare/report.hpp"
#include "compare/study_summary.hpp"
#include "foam_case_writer.hpp"
#include "tests/temp_dir.hpp"
#include "vtp_writer.hpp"

using namespace hydrojump;
using namespace hydrojump::compare;
using namespace hydrojump::compare::testing;
using hydrojump::testing::TempDir;
namespace fs = std::filesystem;

namespace {

// Synthetic mean jump of a stilling basin: depth y1 up to the toe x_t, a linear rise to y2 over
// 4 y2, then y2; uniform discharge q = y1 U1; velocity u = q/h + A(x) cos(pi s/h) (s above the bed),
// whose cosine part integrates to zero over the depth (q unchanged) and, with A = 1.5 q/h over
// (x_t, x_t + Lr), reverses the near-surface flow there: a roller of length Lr.
struct SyntheticJump {
  double y1, u1, y2, x_t, rise, lr;
  const cases::BedProfile* bed;
  double surface(double x) const {
    const double depth = x < x_t ? y1 : (x < x_t + rise ? y1 + (y2 - y1) * (x - x_t) / rise : y2);
    return depth;  // above the floor z = 0 (the crest level)
  }
  double depth(double x) const { return surface(x) - bed->elevation(x); }
  double u(double x, double z) const {
    const double h = depth(x), q = y1 * u1;
    const double a = (x > x_t && x < x_t + lr) ? 1.5 * q / h : 0.0;
    return q / h + a * std::cos(M_PI * (z - bed->elevation(x)) / h);
  }
};

struct RunFixture {
  TempDir tmp{"run"};
  cases::Study study;
  const cases::Case* c = nullptr;
  cases::CaseGeometry geo;
  SyntheticJump jump{};

  RunFixture() {
    study = cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
    c = study.find_case("A");
    REQUIRE(c != nullptr);
    geo = cases::make_geometry(*c, study.fluid);
    const auto* b = c->stilling_basin();
    jump = {b->inflow_depth_m, b->inflow_velocity_m_s, b->tailwater_depth_m, geo.expected_toe_x_m,
            4.0 * b->tailwater_depth_m, 2.0 * b->tailwater_depth_m, &geo.bed};
  }
  fs::path run() const { return tmp.path() / "A"; }

  // Particles in columns dx apart: fluid from the bed to the surface (n = round(h/dx) layers, so the
  // continuum surface is exactly the synthetic one; density rho0 dx/d keeps V = dx d), and 3 layers of
  // boundary particles below the bed.
  void write_sph(double dx, const std::vector<double>& times) {
    const fs::path dir = run() / "sph";
    fs::create_directories(dir / "output");
    cases::write_resolved_case(study, *c, "quick", dir / "case.toml");
    ParticleFrame f;
    for (double x = geo.x_min_m + 0.5 * dx; x < geo.x_max_m; x += dx) {
      const double zb = geo.bed.elevation(x), h = jump.depth(x);
      const int n = std::max(1, static_cast<int>(std::lround(h / dx)));
      const double d = h / n;
      for (int k = -3; k < n; ++k) {
        const double z = k < 0 ? zb + (k + 0.5) * dx : zb + (k + 0.5) * d;
        f.x.push_back(x); f.z.push_back(z);
        f.type.push_back(k < 0 ? 1 : 0);
        f.u.push_back(k < 0 ? 0.0 : jump.u(x, z));
        f.w.push_back(0.0);
        f.density.push_back(k < 0 ? 1000.0 : 1000.0 * dx / d);
        f.pressure.push_back(0.0);
      }
    }
    std::vector<std::pair<double, std::string>> entries;
    for (std::size_t i = 0; i < times.size(); ++i) {
      const std::string name = "output/particles_" + std::to_string(i) + ".vtp";
      write_vtp(dir / name, f);
      entries.push_back({times[i], name});
    }
    write_pvd(dir / "particles.pvd", entries);
  }

  // A Cartesian OpenFOAM mesh from the trough level up, cells dx x dz; alpha = water fraction of the
  // cell between bed and surface (by sub-sampling), U at the cell centre (0 in cells without water).
  void write_vof(int nx, int nz, const std::vector<std::string>& times) {
    const fs::path dir = run() / "vof";
    FoamBox box;
    box.x0 = geo.x_min_m;
    box.z0 = geo.bed.lowest_elevation();
    box.length = geo.x_max_m - geo.x_min_m;
    box.height = 0.2 - box.z0;
    box.nx = nx;
    box.nz = nz;
    write_foam_mesh(dir, box);
    cases::write_resolved_case(study, *c, "quick", dir / "case.toml");
    const double dx = box.length / nx, dz = box.height / nz;
    auto alpha = [&](double x, double y) {
      int wet = 0;
      for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 8; ++k) {
          const double xs = x + (i + 0.5 - 4) * dx / 8, ys = y + (k + 0.5 - 4) * dz / 8;
          if (ys > geo.bed.elevation(xs) && ys < jump.surface(xs)) ++wet;
        }
      return wet / 64.0;
    };
    auto u = [&](double x, double y) { return alpha(x, y) > 0 ? jump.u(x, std::max(y, geo.bed.elevation(x))) : 0.0; };
    auto zero = [](double, double) { return 0.0; };
    for (const auto& t : times) write_foam_fields(dir, t, box, alpha, u, zero);
  }
};

const MetricRow& row(const CaseComparison& c, const std::string& q) {
  for (const auto& r : c.metrics)
    if (r.quantity == q) return r;
  FAIL("no metric " << q);
  return c.metrics.front();
}

}  // namespace

TEST_CASE("compare_case_directory on a synthetic jump gives both methods with metrics and report and plots",
          "[compare][case][long]") {
  RunFixture fx;
  const double dx = 0.005;
  fx.write_sph(dx, {5.0, 6.5, 8.0, 9.5});
  fx.write_vof(352, 60, {"5", "7", "9"});
  CompareOptions options;
  options.station_spacing_m = 0.005;
  std::ostringstream log;
  const CaseComparison c = compare_case_directory(fx.run(), options, log);
  INFO(log.str());
  REQUIRE(c.sph.available);
  REQUIRE(c.vof.available);
  CHECK(c.sph.stats.times.size() == 3u);  // 6.5, 8, 9.5 in the window [6, 10]
  CHECK(c.vof.stats.times.size() == 2u);

  const auto& j = fx.jump;
  const double q = j.y1 * j.u1, g = fx.study.fluid.gravity_m_s2;
  const double e1 = cases::specific_energy(j.y1, q, g), e2 = cases::specific_energy(j.y2, q, g);
  const double x_toe = j.x_t + 0.5 * j.y1 * j.rise / (j.y2 - j.y1);  // where the rise passes 1.5 y1
  for (const MethodOutcome* m : {&c.sph, &c.vof}) {
    INFO(m->method);
    const JumpMetrics& r = m->metrics;
    for (const auto& n : r.notes) INFO("note: " << n);
    CHECK(r.sequent_depth_m == Approx(j.y2).margin(0.001));
    CHECK(r.upstream_depth_m == Approx(j.y1).margin(0.001));
    CHECK(r.toe_x_m == Approx(x_toe).margin(0.01));
    CHECK(r.roller_end_x_m == Approx(j.x_t + j.lr).margin(0.015));
    CHECK(r.jump_end_x_m == Approx(j.x_t + 0.95 * j.rise).margin(0.015));
    // eta from the section energies E = z_b + h + alpha U^2/(2g) (the downstream section sits on a
    // crest, where the uniform tailwater gives E2 exactly). The depths are interpolated: at Fr1 = 4,
    // dE1/dy1 = 1 - Fr1^2 = -15, so 0.1 mm of y1 (0.02 dx) moves eta by 0.33 points; 0.2 points
    // allows 0.06 mm (0.012 dx) on the flat synthetic inflow, which both samplers resolve much more
    // closely than the 0.1 dx bound of a general surface (the flat-surface tests: <= 0.0035 dx).
    INFO("eta " << 100 * r.eta << " formula " << 100 * (e1 - e2) / e1);
    CHECK(100 * r.eta == Approx(100 * (e1 - e2) / e1).margin(0.2));
    CHECK(100 * r.eta_crest_depth == Approx(100 * (e1 - e2) / e1).margin(0.3));
    // Discharge at every section equals q (the synthetic field conserves it).
    for (const auto& s : m->stats.sections) {
      INFO(s.spec.name);
      CHECK(s.discharge.mean == Approx(q).epsilon(0.03));
      // The fraction-integral check agrees with the 0.5-level surface.
      CHECK(s.surface_from_fraction.mean == Approx(s.surface.mean).margin(0.002));
    }
  }
  // The two renderings of the same jump agree closely.
  CHECK(c.surface.n_stations > 100);
  CHECK(c.surface.rms_m < 0.002);
  CHECK(std::abs(row(c, "eta").sph - row(c, "eta").vof) < 0.2);
  CHECK(row(c, "eta").experiment == Approx(48.43));
  // The console summary: both methods, with the experiment's values in brackets and Bélanger's y2* in
  // braces; run A holds its toe (the default protocol): the toe imposed, y2 and eta predicted.
  CHECK_THAT(log.str(), Catch::Contains("summary over [6, 10] s (experiment in brackets):\nsph: toe ") &&
                            Catch::Contains("\nvof: toe ") && Catch::Contains("% (predicted) [48.43], Lj ") &&
                            Catch::Contains(" m (predicted) [0.104] {y2* 0.1318, y2/y2* 0.789") &&
                            Catch::Contains(" m (imposed)"));

  // Outputs.
  for (const char* f : {"comparison.json", "report.md", "report.html", "csv/sections.csv", "csv/profiles.csv",
                        "csv/longitudinal.csv", "csv/metrics.csv", "csv/eta.csv", "csv/section_timeseries.csv", "csv/snapshot_sph.csv",
                        "csv/snapshot_vof.csv", "csv/toe_frames.csv"})
    CHECK(fs::exists(fx.run() / f));
  {
    // One row per frame in the window, in time order per method, each frame's toe where the mean surface's is
    // (the synthetic jump stands still).
    const util::CsvTable toes = util::read_csv_table(fx.run() / "csv" / "toe_frames.csv");
    REQUIRE(toes.header == std::vector<std::string>{"method", "time_s", "toe_x_m"});
    REQUIRE(toes.rows.size() == 5u);
    const std::vector<std::string> methods{"sph", "sph", "sph", "vof", "vof"};
    const std::vector<double> times{6.5, 8.0, 9.5, 7.0, 9.0};
    for (std::size_t k = 0; k < toes.rows.size(); ++k) {
      INFO("row " << k);
      REQUIRE(toes.rows[k].size() == 3u);
      CHECK(toes.rows[k][0] == methods[k]);
      CHECK(util::csv_number(toes.rows[k][1]) == Approx(times[k]).margin(1e-9));
      CHECK(util::csv_number(toes.rows[k][2]) == Approx(c.sph.metrics.toe_x_m).margin(0.01));
    }
  }
  {
    // The stations' means are over their wet frames: how many there were stands beside each mean (every
    // station on the synthetic jump is wet in every frame).
    const util::CsvTable lon = util::read_csv_table(fx.run() / "csv" / "longitudinal.csv");
    REQUIRE(lon.header.size() >= 2u);
    CHECK(lon.header[lon.header.size() - 2] == "n_times");
    CHECK(lon.header.back() == "n_wet");
    REQUIRE(lon.rows.size() > 200u);
    for (const auto& r : lon.rows) {
      REQUIRE(r.size() == lon.header.size());
      const double frames = r[0] == "sph" ? 3.0 : 2.0;
      CHECK(util::csv_number(r[r.size() - 2]) == frames);
      CHECK(util::csv_number(r.back()) == frames);
    }
  }
  std::ifstream md(fx.run() / "report.md");
  std::stringstream mds;
  mds << md.rdbuf();
  CHECK_THAT(mds.str(), Catch::Contains("Energy dissipation rate"));
  // study summary across case directories: a finished case and a missing one (no Python involved)
  const StudySummary sum = summarize_study({{"A", fx.run()}, {"B", fx.tmp.path() / "B"}});
  CHECK(sum.eta_files.size() == 1u);
  CHECK_THAT(sum.markdown, Catch::Contains("| A | 39.") && Catch::Contains("| 48.43 | 47.08 |") &&
                               Catch::Contains("| B | missing"));
  const std::string positions = sum.markdown.substr(sum.markdown.find("### Jump position and momentum balance"));
  CHECK_THAT(positions, Catch::Contains("| A | ") && Catch::Contains("| B | missing"));
  CHECK_THAT(sum.eta_csv, Catch::StartsWith("case,") && Catch::Contains("\nA,"));
  // comparison.json is valid JSON (NaN written as null); the figures need /usr/bin/python3 with
  // matplotlib, a dependency (scripts/setup.sh installs python3-matplotlib): missing is a failure.
  REQUIRE(std::system("/usr/bin/python3 -c 'import matplotlib' > /dev/null 2>&1") == 0);
  const std::string cmd = "/usr/bin/python3 -c \"import json,sys; json.load(open(sys.argv[1]))\" '" +
                          (fx.run() / "comparison.json").string() + "'";
  CHECK(std::system(cmd.c_str()) == 0);
  for (const char* f : {"surface.png", "profiles.png", "velocity_decay.png", "eta.png", "toe_frames.png", "snapshot_sph.png",
                        "snapshot_vof.png"})
    CHECK(fs::exists(fx.run() / "figures" / f));
  // eta bars across runs (the study-level figure) from the case directories
  CHECK(plot_study_eta_bars({fx.run(), fx.tmp.path() / "no-such-case"}, fx.tmp.path() / "eta_bars.png") == "");
  CHECK(fs::exists(fx.tmp.path() / "eta_bars.png"));
  std::ifstream html(fx.run() / "report.html");
  std::stringstream hs;
  hs << html.rdbuf();
  CHECK_THAT(hs.str(), Catch::Contains("data:image/png;base64,"));
}

// A figure that cannot be made: the comparison still writes its tables, comparison.json and report, and
// says why with the plot log where it ends up (figures/plot.log); the real plot_case.py makes the
// figures whose inputs are sound and names the file and column of the one that is not.
TEST_CASE("A plot script that fails is named with its log, and one bad table costs only its own figure",
          "[compare][case][long]") {
  RunFixture fx;
  fx.write_sph(0.005, {5.0, 6.5, 8.0, 9.5});
  fx.write_vof(352, 60, {"5", "7", "9"});
  CompareOptions options;
  options.station_spacing_m = 0.005;
  std::ostringstream log;
  // A stand-in plot_case.py that fails as a broken matplotlib would.
  const fs::path fake = fx.tmp.path() / "fake_plot";
  fs::create_directories(fake);
  // It says what it made on stdout first, then why it failed on stderr, its last line, which the
  // comparison quotes (stdout to a file is buffered unless compare asks for it unbuffered).
  std::ofstream(fake / "plot_case.py") << "import sys\nprint('wrote surface.png')\n"
                                          "print('ImportError: no matplotlib here', file=sys.stderr)\nsys.exit(1)\n";
  // HYDROJUMP_PLOT_DIR names it while the comparison runs (and PYTHONUNBUFFERED is unset, as in a plain
  // shell), restored however the comparison ends.
  struct PlotDirFor {
    std::optional<std::string> saved, saved_unbuffered;
    explicit PlotDirFor(const fs::path& dir) {
      if (const char* old = std::getenv("HYDROJUMP_PLOT_DIR")) saved = old;
      if (const char* old = std::getenv("PYTHONUNBUFFERED")) saved_unbuffered = old;
      ::setenv("HYDROJUMP_PLOT_DIR", dir.c_str(), 1);
      ::unsetenv("PYTHONUNBUFFERED");
    }
    ~PlotDirFor() {
      if (saved) ::setenv("HYDROJUMP_PLOT_DIR", saved->c_str(), 1);
      else ::unsetenv("HYDROJUMP_PLOT_DIR");
      if (saved_unbuffered) ::setenv("PYTHONUNBUFFERED", saved_unbuffered->c_str(), 1);
    }
  };
  const CaseComparison c = [&] {
    const PlotDirFor plot_dir(fake);
    return compare_case_directory(fx.run(), options, log);
  }();
  INFO(log.str());
  const std::string plot_log = (fx.run() / "figures" / "plot.log").string();
  CHECK(c.figures_problem == "plot_case.py failed (it exited with code 1): ImportError: no matplotlib here (log: " +
                                plot_log + ")");
  CHECK(fs::exists(plot_log));
  CHECK(fs::exists(fx.run() / "comparison.json"));
  CHECK(fs::exists(fx.run() / "csv" / "eta.csv"));
  CHECK_THAT(util::read_text_file(fx.run() / "report.md"), Catch::Contains("Figures unavailable: ") &&
                                                               Catch::Contains("(log: " + plot_log + ")"));

  // The real script on those tables with one column renamed: every other figure, exit status 1, and a
  // last line naming the figure, the file and the column.
  REQUIRE(std::system("/usr/bin/python3 -c 'import matplotlib' > /dev/null 2>&1") == 0);
  const fs::path csv = fx.run() / "csv";
  std::string lon = util::read_text_file(csv / "longitudinal.csv");
  lon.replace(lon.find("surface_std_m"), 13, "surface_sd_mm");
  std::ofstream(csv / "longitudinal.csv") << lon;
  const fs::path figs = fx.tmp.path() / "figs";
  const std::string script = std::string(HYDROJUMP_SOURCE_DIR) + "/compare/plot/plot_case.py";
  const std::string cmd = "/usr/bin/python3 -s '" + script + "' '" + csv.string() + "' '" + figs.string() + "' > '" +
                          (fx.tmp.path() / "plot.out").string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  const std::string out = util::read_text_file(fx.tmp.path() / "plot.out");
  INFO(out);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 1);
  CHECK_THAT(out, Catch::Contains("plot_case.py: 1 of 7 figures not made: surface.png (" + (csv / "longitudinal.csv").string() +
                                  " has no column 'surface_std_m')"));
  CHECK_FALSE(fs::exists(figs / "surface.png"));
  for (const char* f : {"profiles.png", "eta.png", "toe_frames.png", "snapshot_sph.png", "snapshot_vof.png"})
    CHECK(fs::exists(figs / f));
}

TEST_CASE("A missing VOF result is reported as missing and is not a crash", "[compare][case]") {
  RunFixture fx;
  fx.write_sph(0.01, {7.0, 8.0});
  CompareOptions options;
  options.plots = false;
  std::ostringstream log;
  const CaseComparison c = compare_case_directory(fx.run(), options, log);
  CHECK(c.sph.available);
  CHECK_FALSE(c.vof.available);
  CHECK_THAT(c.vof.status, Catch::StartsWith("missing"));
  CHECK(std::isnan(c.surface.rms_m));
  std::ifstream json(fx.run() / "comparison.json");
  std::stringstream js;
  js << json.rdbuf();
  CHECK_THAT(js.str(), Catch::Contains("\"available\": false"));
}

TEST_CASE("SPH output outside the averaging window is reported as missing", "[compare][case]") {
  RunFixture fx;
  fx.write_sph(0.01, {1.0, 2.0});
  CompareOptions options;
  options.plots = false;
  std::ostringstream log;
  const CaseComparison c = compare_case_directory(fx.run(), options, log);
  CHECK_FALSE(c.sph.available);
  CHECK_THAT(c.sph.status, Catch::Contains("averaging window"));
}

TEST_CASE("A window holding fewer than two output times, or stations coarser than y1, are refused", "[compare][case]") {
  RunFixture fx;
  fx.write_sph(0.01, {6.5, 8.0});
  CompareOptions options;
  options.plots = false;
  std::ostringstream log;
  // One output time (8.0 s; the case writes every 0.1 s): no time mean, deviation or trend.
  options.window_start_s = 8.0;
  options.window_end_s = 8.05;
  CHECK_THROWS_WITH(compare_case_directory(fx.run(), options, log),
                    Catch::Contains("the averaging window [8, 8.05] s holds 1 output time(s) (one every 0.1 s)"));
  // A window beyond any run of the case (0.1 s x 100,000 outputs = 10,000 s) is refused, not counted
  // into an overflow.
  options.window_start_s = 0.0;
  options.window_end_s = 1e18;
  CHECK_THROWS_WITH(compare_case_directory(fx.run(), options, log),
                    Catch::Contains("the averaging window [0, 1e+18] s ends after 10000 s, the latest time a run of "
                                    "this case can reach (at most 100000 outputs, one every 0.1 s)"));
  CHECK(cases::outputs_in_window(0.0, 1e18, 0.1) == 1000000000000000L);  // capped, positive
  options.window_start_s = 6.5;
  options.window_end_s = 8.0;
  options.station_spacing_m = 0.5;
  CHECK_THROWS_WITH(compare_case_directory(fx.run(), options, log),
                    Catch::Contains("--station-spacing 0.5 m is coarser than the inflow depth y1 = 0.0254 m"));
}

TEST_CASE("An SPH series given with --sph-pvd is checked against the case when a case record lies beside it",
          "[compare][case]") {
  RunFixture fx;
  fx.write_sph(0.01, {6.5, 8.0});
  // The same series in another directory, made (its case.toml says) with another particle spacing.
  const fs::path other = fx.tmp.path() / "other";
  fs::copy(fx.run() / "sph", other, fs::copy_options::recursive);
  std::string text = util::read_text_file(other / "case.toml");
  const std::string key = "particle_spacing_m = ";
  REQUIRE(text.find(key) != std::string::npos);
  text.replace(text.find(key), key.size(), key + "0.02 # ");
  std::ofstream(other / "case.toml") << text;
  CompareOptions options;
  options.plots = false;
  options.sph_pvd = other / "particles.pvd";
  std::ostringstream log;
  const CaseComparison refused = compare_case_directory(fx.run(), options, log);
  CHECK_FALSE(refused.sph.available);
  CHECK_THAT(refused.sph.status, Catch::Contains("was made with other settings than") &&
                                     Catch::Contains("particle_spacing_m = 0.02"));
  // Without a record beside it (another program's results) it is taken as it is.
  fs::remove(other / "case.toml");
  CHECK(compare_case_directory(fx.run(), options, log).sph.available);
}

TEST_CASE("A directory without case.toml gives a clear error", "[compare][case]") {
  TempDir tmp("norun");
  std::ostringstream log;
  CHECK_THROWS_WITH(compare_case_directory(tmp.path(), {}, log), Catch::Contains("case.toml"));
}

TEST_CASE("base64 encoding", "[compare][report]") {
  CHECK(base64_encode("") == "");
  CHECK(base64_encode("f") == "Zg==");
  CHECK(base64_encode("fo") == "Zm8=");
  CHECK(base64_encode("foobar") == "Zm9vYmFy");
}

TEST_CASE("The plot scripts are found from the source tree", "[compare][report]") {
  const fs::path dir = plot_script_dir();
  CHECK(fs::exists(dir / "plot_case.py"));
  CHECK(fs::exists(dir / "plot_eta_bars.py"));
}

// Results that end inside the window (a run stopped early or still running) are compared, but the
// status says that the averages cover part of the window only (run A's window is 6-10 s).
TEST_CASE("Results that end before the window's end are flagged as covering part of the window", "[compare][case]") {
  CompareOptions options;
  options.plots = false;
  {
    RunFixture fx;
    fx.write_sph(0.01, {6.5, 7.0, 7.5});
    std::ostringstream log;
    const CaseComparison c = compare_case_directory(fx.run(), options, log);
    REQUIRE(c.sph.available);
    CHECK_THAT(c.sph.status, Catch::StartsWith("ok; PART OF THE WINDOW ONLY: the results end at t = 7.5 s, before the "
                                               "window's end 10 s, so the averages are over the outputs of [6.5, 7.5] s"));
  }
  {
    RunFixture fx;
    fx.write_sph(0.01, {6.0, 8.0, 10.0});
    std::ostringstream log;
    const CaseComparison c = compare_case_directory(fx.run(), options, log);
    REQUIRE(c.sph.available);
    CHECK(c.sph.status == "ok");
  }
}

// A comparison's csv/ and figures/ hold its own files only: what an earlier comparison left there (a
// figure of a method that is now missing, say) does not stay beside the new report.
TEST_CASE("A new comparison replaces the previous one's tables and figures instead of mixing with them",
          "[compare][case]") {
  RunFixture fx;
  fx.write_sph(0.01, {6.0, 8.0, 10.0});
  const fs::path out = fx.run();
  fs::create_directories(out / "figures");
  fs::create_directories(out / "csv");
  std::ofstream(out / "figures" / "surface.png") << "a figure of an earlier comparison";
  std::ofstream(out / "csv" / "snapshot_vof.csv") << "a table of an earlier comparison";
  CompareOptions options;
  options.plots = false;
  std::ostringstream log;
  const CaseComparison c = compare_case_directory(fx.run(), options, log);
  REQUIRE(c.sph.available);
  CHECK(fs::exists(out / "csv" / "eta.csv"));
  CHECK_FALSE(fs::exists(out / "csv" / "snapshot_vof.csv"));
  CHECK_FALSE(fs::exists(out / "figures" / "surface.png"));
  CHECK(util::read_text_file(out / "report.md").find("surface.png") == std::string::npos);
  CHECK_FALSE(fs::exists(out / ".csv.new"));
  CHECK_FALSE(fs::exists(out / ".csv.old"));
  CHECK_FALSE(fs::exists(out / ".figures.old"));
}

TEST_CASE("An unreadable frame is skipped and reported and the other frames are used", "[compare][case]") {
  RunFixture fx;
  fx.write_sph(0.01, {7.0, 8.0, 9.0});
  { std::ofstream broken(fx.run() / "sph" / "output" / "particles_1.vtp"); broken << "not a vtp file"; }
  CompareOptions options;
  options.plots = false;
  std::ostringstream log;
  const CaseComparison c = compare_case_directory(fx.run(), options, log);
  REQUIRE(c.sph.available);
  CHECK(c.sph.stats.times.size() == 2u);
  CHECK_THAT(c.sph.status, Catch::Contains("1 unreadable frame(s) skipped") && Catch::Contains("particles_1.vtp"));
}

TEST_CASE("The VOF water balance is noted from the discharge samples, and a damaged sample file costs the note only",
          "[compare][case]") {
  RunFixture fx;
  // Run A with its outlet holding the tailwater (control = "fixed_depth"): no tailgate log is this run's.
  for (auto& c : fx.study.cases)
    if (c.id == "A") std::get<cases::StillingBasinCase>(c.data).control.mode = hydrojump::cases::TailwaterControlMode::fixed_depth;
  fx.write_vof(176, 30, {"6", "8", "10"});
  const double q = fx.jump.y1 * fx.jump.u1;
  const double thickness = fx.c->resolutions.at("quick").vof_cell_size_bed_m;  // the 2D mesh's span
  auto write_patch = [&](const std::string& name, double flux_m3_s, const std::string& extra_row) {
    const fs::path dir = fx.run() / "vof" / "postProcessing" / name / "0";
    fs::create_directories(dir);
    std::ofstream out(dir / "surfaceFieldValue.dat");
    out << "# Time\tsum(alphaPhi0.water)\tsum(phi)\n";
    for (double t : {6.0, 8.0, 10.0}) out << t << "\t" << flux_m3_s << "\t0\n";
    out << extra_row;
  };
  write_patch("discharge_inlet", -q * thickness, "");
  write_patch("discharge_outlet", 0.9 * q * thickness, "");
  CompareOptions options;
  options.plots = false;
  std::ostringstream log;
  CaseComparison c = compare_case_directory(fx.run(), options, log);
  REQUIRE(c.vof.available);
  auto balance_note = [](const CaseComparison& cc) {
    for (const auto& n : cc.vof.metrics.notes)
      if (n.find("water balance") != std::string::npos) return n;
    return std::string();
  };
  // The synthetic jump does not move: trend 0; the outlet passes 90 %: filling by 10 % of q.
  CHECK(c.vof.metrics.toe_trend_m_per_s == Approx(0.0).margin(1e-9));
  CHECK_THAT(balance_note(c), Catch::Contains("= -10 % of q (filling)") && Catch::Contains("NOT steady"));
  write_patch("discharge_outlet", q * thickness, "9.5 garbage\n");
  c = compare_case_directory(fx.run(), options, log);
  REQUIRE(c.vof.available);
  CHECK(std::isfinite(row(c, "eta").vof));
  CHECK_THAT(balance_note(c), Catch::StartsWith("water balance unavailable") &&
                                  Catch::Contains("discharge_outlet/0/surfaceFieldValue.dat:5"));
  // A tailgate log left in a case run without the control (control = "fixed_depth") is not this
  // run's: no tailgate note, whatever it holds.
  REQUIRE(!fx.c->holds_toe());
  std::ofstream(fx.run() / "vof" / "tailwater_control.csv")
      << "time_s,toe_x_m,toe_outputs,water_volume_m2,volume_target_m2,outlet_mean_velocity_m_s\n8,0.3,5,0.3,0.3,0.4\n";
  c = compare_case_directory(fx.run(), options, log);
  for (const auto& n : c.vof.metrics.notes) CHECK_THAT(n, !Catch::Contains("tailgate"));
}
