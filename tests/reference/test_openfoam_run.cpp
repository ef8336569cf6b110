// Generated cases run by OpenFOAM v1912 itself (installed here and in CI): every dictionary parses,
// meshing and checkMesh pass, tiny cases run a few time steps serially and with MPI, results are
// consistent with the spec (inflow discharge, upstream depth), resume works, and body_fitted is
// refused exactly when the self-test shows the known defect.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <unistd.h>

#include "util/fingerprint.hpp"
#include "cases/spec_reader.hpp"
#include "reference/case_writer.hpp"
#include "reference/cli.hpp"
#include "reference/line_samples.hpp"
#include "reference/runner.hpp"
#include "reference/tailwater_control.hpp"
#include "reference_test_specs.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace hydrojump;
using reference::testing::basin_spec;
using reference::testing::dam_break_spec;
using reference::testing::with_hold_toe;
using reference::testing::tiny_hold_toe_spec;
using reference::testing::parse;
using hydrojump::testing::TempDir;

namespace {

void require_openfoam() {
  try {
    reference::check_openfoam(false);
  } catch (const std::exception& e) {
    FAIL("OpenFOAM v1912 is required by these tests (apt-get install openfoam): " << e.what());
  }
}

// Writes the case into dir (a directory not there yet, inside a test's TempDir) and returns dir.
fs::path generate(const std::string& spec_text, const fs::path& dir) {
  const cases::Study study = parse(spec_text);
  reference::write_vof_case(study, study.cases.front(), "quick", dir);
  return dir;
}

// Rows of a whitespace-separated numeric file (comment lines starting with '#' skipped).
std::vector<std::vector<double>> rows_of(const fs::path& file) {
  std::vector<std::vector<double>> rows;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::vector<double> row;
    double v;
    while (ss >> v) row.push_back(v);
    if (!row.empty()) rows.push_back(row);
  }
  return rows;
}

// Water depth along a sampled vertical line: the integral of alpha.water over the line.
double water_depth(const fs::path& alpha_xy) {
  return reference::water_depth(reference::read_line_sample(alpha_xy));
}

// The numbers of a field file's internalField (a compressed OpenFOAM field; vectors flattened).
std::vector<double> internal_field(const fs::path& gz_file) {
  const TempDir tmp("field");
  const fs::path plain = tmp.path() / "field";
  const std::string command = "gzip -dc '" + gz_file.string() + "' > '" + plain.string() + "'";
  REQUIRE(std::system(command.c_str()) == 0);
  const std::string text = util::read_text_file(plain);
  const auto begin = text.find("internalField");
  const auto end = text.find("boundaryField", begin);
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  std::string body = text.substr(begin, end - begin);
  const auto open = body.find('(');
  REQUIRE(open != std::string::npos);  // a nonuniform field
  body = body.substr(open);
  for (char& ch : body) {
    if (ch == '(' || ch == ')' || ch == ';') ch = ' ';
  }
  std::istringstream in(body);
  std::vector<double> values;
  double v;
  while (in >> v) values.push_back(v);
  return values;
}

// Sends SIGINT (Ctrl-C) to this process once `file` holds `text` (within 60 s), as a user watching the
// run would: the runner's handler, installed while it runs, turns it into a stop request.
class InterruptWhen {
 public:
  InterruptWhen(fs::path file, std::string text)
      : thread_([file = std::move(file), text = std::move(text), this]() {
          const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
          while (!cancelled_ && std::chrono::steady_clock::now() < deadline) {
            if (fs::exists(file) && util::read_text_file(file).find(text) != std::string::npos) {
              sent_ = true;
              ::kill(::getpid(), SIGINT);
              return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
          }
        }) {}
  ~InterruptWhen() {
    cancelled_ = true;
    thread_.join();
  }
  InterruptWhen(const InterruptWhen&) = delete;
  InterruptWhen& operator=(const InterruptWhen&) = delete;
  bool sent() const { return sent_; }

 private:
  std::atomic<bool> cancelled_{false}, sent_{false};
  std::thread thread_;
};

long checkmesh_cells(const fs::path& dir) {
  const std::string log = util::read_text_file(dir / "log.checkMesh");
  const auto pos = log.find("    cells:");
  if (pos == std::string::npos) return -1;
  return std::stol(log.substr(pos + 10));
}

}  // namespace

TEST_CASE("every generated dictionary is read by OpenFOAM's foamDictionary", "[reference][openfoam]") {
  require_openfoam();
  for (const std::string& spec : {basin_spec(), dam_break_spec()}) {
    const cases::Study study = parse(spec);
    const TempDir tmp("openfoam-parse");
    const fs::path dir = generate(spec, tmp.path() / "case");
    const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
    for (const auto& [path, dict] : vof.files) {
      INFO(path);
      const std::string command = "foamDictionary -keywords '" + (dir / path).string() + "' > /dev/null 2>&1";
      CHECK(std::system(command.c_str()) == 0);
    }
  }
}

TEST_CASE("a tiny corrugated basin meshes, passes checkMesh, runs and resumes", "[reference][openfoam]") {
  require_openfoam();
  const std::string spec = basin_spec("", 0.02, 0.01);
  const cases::Study study = parse(spec);
  const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
  const TempDir tmp("openfoam-basin");
  const fs::path dir = generate(spec, tmp.path() / "case");
  std::ostringstream out;
  reference::run_vof_case(dir, reference::RunOptions{}, out);
  INFO(out.str());
  CHECK_THAT(util::read_text_file(dir / "log.checkMesh"), Catch::Contains("Mesh OK."));
  CHECK(checkmesh_cells(dir) == vof.mesh.cell_count());
  CHECK(fs::exists(dir / "0.02"));
  CHECK_THAT(out.str(), Catch::Contains("reached t = 0.02"));
  // The progress lines carry the basin's water balance: the inflow q = 0.0508 m^2/s.
  CHECK_THAT(out.str(), Catch::Contains(", q_in 0.0508, q_out ") && Catch::Contains("m2/s (last 0.02 s)"));

  // The inlet carries q = y1 U1 per unit width (sum of the water flux / spanwise thickness).
  const auto inlet = rows_of(dir / "postProcessing/discharge_inlet/0/surfaceFieldValue.dat");
  REQUIRE(!inlet.empty());
  CHECK(std::abs(inlet.back()[1]) / vof.mesh.thickness_m == Approx(0.0254 * 2.0).epsilon(1e-5));
  // The water flux through the top is sampled too (nothing leaves there in 0.02 s).
  const auto top = rows_of(dir / "postProcessing/discharge_atmosphere/0/surfaceFieldValue.dat");
  REQUIRE(top.size() == 2);
  CHECK(std::abs(top.back()[1]) < 1e-9);
  // Upstream of the basin the supercritical layer keeps its depth y1 (within half a cell).
  const double depth_up = water_depth(dir / "postProcessing/sections/0.02/up_alpha.water.xy");
  CHECK(depth_up == Approx(0.0254).margin(0.0025));
  CHECK(fs::exists(dir / "postProcessing/freeSurface/0.02/alpha_0.5.vtp"));

  // Without --resume existing results are not overwritten.
  CHECK_THROWS_WITH(reference::run_vof_case(dir, reference::RunOptions{}, out),
                    Catch::Contains("already holds results") && Catch::Contains("--resume"));

  // A time directory half-written by a killed run is moved aside; the run continues before it.
  {
    std::ofstream truncate(dir / "0.02/alpha.water.gz", std::ios::trunc | std::ios::binary);
    truncate << "\x1f\x8b";
  }
  reference::RunOptions resume;
  resume.resume = true;
  // The run recorded its case; a case.toml whose settings were edited since would describe other
  // results than the dictionaries the run uses: resuming is refused, naming the line. (A reworded
  // description is not another run.)
  const std::string case_text = util::read_text_file(dir / "case.toml");
  CHECK(util::read_text_file(dir / "results_case.toml") == case_text);
  {
    std::string edited = case_text;
    const std::string key = "max_courant = ";
    REQUIRE(edited.find(key) != std::string::npos);
    edited.replace(edited.find(key), key.size(), key + "0.25 # edited ");
    std::ofstream(dir / "case.toml") << edited;
  }
  std::ostringstream refused;
  CHECK_THROWS_WITH(reference::run_vof_case(dir, resume, refused),
                    Catch::Contains("holds results made with other settings") && Catch::Contains("max_courant = 0.25 # edited"));
  { std::ofstream(dir / "case.toml") << case_text; }
  std::ostringstream out2;
  reference::run_vof_case(dir, resume, out2);
  CHECK_THAT(out2.str(), Catch::Contains("Resuming from t = 0.01"));
  CHECK(fs::exists(dir / "0.02.incomplete"));
  CHECK(fs::file_size(dir / "0.02/alpha.water.gz") > 100);
  CHECK_THAT(util::read_text_file(dir / "log.interFoam"), Catch::Contains("resumed by hydrojump"));

  // --end-time extends the finished run (system/controlDict's endTime rewritten, the rest kept); an end
  // time not after the latest time directory is refused, and so is one past what a case may run.
  reference::RunOptions extend = resume;
  extend.end_time_s = 1e308;
  CHECK_THROWS_WITH(reference::run_vof_case(dir, extend, refused), Catch::Contains("--end-time 1e+308 s is out of range"));
  extend.end_time_s = 0.02;
  CHECK_THROWS_WITH(reference::run_vof_case(dir, extend, refused),
                    Catch::Contains("--end-time 0.02 s: must be after the latest time 0.02 s"));
  extend.end_time_s = 0.03;
  std::ostringstream out3;
  reference::run_vof_case(dir, extend, out3);
  CHECK_THAT(out3.str(), Catch::Contains("End time 0.03 s (was 0.02 s") && Catch::Contains("to t = 0.03 s") &&
                             Catch::Contains("reached t = 0.03"));
  CHECK(fs::exists(dir / "0.03"));
  const std::string control = util::read_text_file(dir / "system/controlDict");
  CHECK_THAT(control, Catch::Contains("endTime         0.03;") && Catch::Contains("// endTime = run.end_time_s"));
}

TEST_CASE("a run resumed between two output times first runs to the next one: later outputs stay on the grid",
          "[reference][openfoam]") {
  require_openfoam();
  // Output every 0.01 s; the first run ends between two outputs, at 0.015 s (where a stop on Ctrl-C
  // also leaves a run).
  const TempDir tmp("openfoam-aligned");
  const fs::path dir = generate(basin_spec("", 0.02, 0.01), tmp.path() / "case");
  reference::RunOptions first;
  first.end_time_s = 0.015;
  std::ostringstream out1;
  reference::run_vof_case(dir, first, out1);
  INFO(out1.str());
  // interFoam writes no time that is not a write time, not even its end time: a closing leg writes it.
  CHECK_THAT(out1.str(), Catch::Contains("The end time 0.015 s lies between two output times"));
  CHECK(fs::exists(dir / "0.01/alpha.water.gz"));
  REQUIRE(fs::exists(dir / "0.015/alpha.water.gz"));
  CHECK(fs::exists(dir / "postProcessing/sections/0.015/up_alpha.water.xy"));
  const std::string case_control = util::read_text_file(dir / "system/controlDict");

  // A runner killed during an aligning leg leaves the case's controlDict aside: the next run puts it
  // back before reading it.
  fs::copy_file(dir / "system/controlDict", dir / "system/controlDict.hydrojump-original");
  { std::ofstream(dir / "system/controlDict") << "// the aligning leg's dictionary\n"; }

  reference::RunOptions resume;
  resume.resume = true;
  resume.end_time_s = 0.035;
  std::ostringstream out2;
  reference::run_vof_case(dir, resume, out2);
  INFO(out2.str());
  CHECK_THAT(out2.str(), Catch::Contains("system/controlDict restored") &&
                             Catch::Contains("Aligning with the output times: t = 0.015 s") &&
                             Catch::Contains("first runs to t = 0.02 s") && Catch::Contains("reached t = 0.035"));
  // Counting from 0.015 s, interFoam alone would write 0.025 s and not the end time. With the legs, the
  // fields and the sampled sections land on the grid 0.02, 0.03 s, and on the end time 0.035 s.
  for (const char* t : {"0.02", "0.03", "0.035"}) {
    INFO(t);
    CHECK(fs::exists(dir / t / "alpha.water.gz"));
  }
  CHECK_FALSE(fs::exists(dir / "0.025"));
  CHECK(fs::exists(dir / "postProcessing/sections/0.02/up_alpha.water.xy"));
  CHECK(fs::exists(dir / "postProcessing/sections/0.03/up_alpha.water.xy"));
  CHECK_FALSE(fs::exists(dir / "postProcessing/sections/0.025"));
  // The case's controlDict is back, only its endTime changed by --end-time.
  CHECK_FALSE(fs::exists(dir / "system/controlDict.hydrojump-original"));
  std::string expected = case_control;
  const std::string end_entry = "endTime         0.015;";
  REQUIRE(expected.find(end_entry) != std::string::npos);
  expected.replace(expected.find(end_entry), end_entry.size(), "endTime         0.035;");
  CHECK(util::read_text_file(dir / "system/controlDict") == expected);
}

TEST_CASE("a run started from another run's state (--map-from) takes its fields and starts at t = 0",
          "[reference][openfoam]") {
  require_openfoam();
  const std::string spec = basin_spec("", 0.02, 0.01);
  const TempDir tmp("openfoam-map");
  const fs::path source = generate(spec, tmp.path() / "source");
  const fs::path target = generate(spec, tmp.path() / "target");
  std::ostringstream out;
  reference::RunOptions mapped;
  mapped.map_from = source;
  // A source without results is refused before anything is meshed.
  CHECK_THROWS_WITH(reference::run_vof_case(target, mapped, out),
                    Catch::Contains("--map-from " + source.string()) &&
                        Catch::Contains("no complete time directory after t = 0"));
  CHECK(!fs::exists(target / "log.blockMesh"));
  reference::run_vof_case(source, reference::RunOptions{}, out);

  // The target's mesh equals the source's, so mapFields must reproduce the source's last fields.
  mapped.end_time_s = 0.01;
  std::ostringstream run;
  reference::run_vof_case(target, mapped, run);
  INFO(run.str());
  CHECK_THAT(run.str(), Catch::Contains("Initial state from " + source.string() + " at t = 0.02 s") &&
                            Catch::Contains("mapFields") && Catch::Contains("reached t = 0.01"));
  // The same settings: nothing to say about them.
  CHECK_THAT(run.str(), !Catch::Contains("settings differ"));
  CHECK_THAT(util::read_text_file(target / "log.mapFields"), Catch::Contains("Source time: 0.02"));
  for (const char* field : {"alpha.water.gz", "U.gz", "p_rgh.gz"}) {
    INFO(field);
    const std::vector<double> expected = internal_field(source / "0.02" / field);
    const std::vector<double> got = internal_field(target / "0" / field);
    REQUIRE(got.size() == expected.size());
    double worst = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < got.size(); ++i) {
      worst = std::max(worst, std::abs(got[i] - expected[i]));
      scale = std::max(scale, std::abs(expected[i]));
    }
    CHECK(worst <= 1e-6 * scale);
  }
  // Only the fields the case starts with are kept in 0/ (no fieldAverage means from the source).
  for (const auto& entry : fs::directory_iterator(target / "0")) {
    INFO(entry.path().string());
    CHECK(entry.path().filename().string().find("Mean") == std::string::npos);
  }
  CHECK(fs::exists(target / "0.01/alpha.water.gz"));

  // Refused: a directory that already holds results, the case itself, another case.
  CHECK_THROWS_WITH(reference::run_vof_case(target, mapped, out),
                    Catch::Contains("--map-from starts a new run") && Catch::Contains("up to t = 0.01 s"));
  const fs::path fresh = generate(spec, tmp.path() / "fresh");
  reference::RunOptions self = mapped;
  self.map_from = fresh;
  CHECK_THROWS_WITH(reference::run_vof_case(fresh, self, out), Catch::Contains("that is the case being run"));
  const fs::path dam = generate(dam_break_spec(), tmp.path() / "dam");
  reference::RunOptions other = mapped;
  other.map_from = dam;
  CHECK_THROWS_WITH(reference::run_vof_case(fresh, other, out),
                    Catch::Contains("holds case \"dam\", not \"basin\""));
}

TEST_CASE("a run mapped from a run with a lower air layer keeps setFields' air above the source's lid",
          "[reference][openfoam]") {
  require_openfoam();
  // Raising [case.domain] air_height_m (as when splashes leave through the lid) and starting from the
  // old run: the cells above the old lid are outside the source. mapFields used to create p there
  // without values and stop with a floating-point exception while writing it.
  const TempDir tmp("openfoam-map-taller");
  const std::string low = basin_spec("", 0.02, 0.01, "sinusoidal", 0.005, 0.01, 0.04);
  const std::string tall = basin_spec("", 0.02, 0.01, "sinusoidal", 0.005, 0.01, 0.10);
  const fs::path source = generate(low, tmp.path() / "source");
  const fs::path target = generate(tall, tmp.path() / "target");
  std::ostringstream out;
  reference::run_vof_case(source, reference::RunOptions{}, out);
  reference::RunOptions mapped;
  mapped.map_from = source;
  mapped.end_time_s = 0.01;
  std::ostringstream run;
  // With FOAM_SETNAN, OpenFOAM fills newly allocated memory with signalling NaNs, so a cell left
  // without a value fails every time instead of only when the heap happens to hold garbage there.
  ::setenv("FOAM_SETNAN", "true", 1);
  try {
    reference::run_vof_case(target, mapped, run);
  } catch (const std::exception& e) {
    ::unsetenv("FOAM_SETNAN");
    FAIL(e.what());
  }
  ::unsetenv("FOAM_SETNAN");
  INFO(run.str());
  CHECK_THAT(run.str(), Catch::Contains("reached t = 0.01"));
  // Allowed, but said: the one setting that differs, from both sides.
  CHECK_THAT(run.str(), Catch::Contains("note: the source's settings differ from this case's beyond the resolution (2 line(s)") &&
                            Catch::Contains("source: air_height_m = 0.04") && Catch::Contains("this case: air_height_m = 0.1"));
  CHECK_FALSE(fs::exists(target / ".map-source"));
  // 0/ holds the case's initial fields only (p is made by interFoam, not mapped).
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(target / "0")) names.insert(entry.path().filename().string());
  CHECK(names.count("p.gz") == 0);
  CHECK(names.count("alpha.water.gz") == 1);
  // The source's water is carried over and the new air layer is air: the count of water cells
  // (alpha > 0.5) equals the source's, since both meshes share their cells below the old lid.
  const std::vector<double> source_alpha = internal_field(source / "0.02/alpha.water.gz");
  const std::vector<double> target_alpha = internal_field(target / "0/alpha.water.gz");
  REQUIRE(target_alpha.size() > source_alpha.size());
  const auto water_cells = [](const std::vector<double>& alpha) {
    return std::count_if(alpha.begin(), alpha.end(), [](double a) { return a > 0.5; });
  };
  CHECK(water_cells(target_alpha) == water_cells(source_alpha));
  // No cell without a value: the mapped fractions stay within the source's own range (interFoam's
  // MULES lets alpha overshoot [0, 1] slightly).
  const auto [source_min, source_max] = std::minmax_element(source_alpha.begin(), source_alpha.end());
  const auto [target_min, target_max] = std::minmax_element(target_alpha.begin(), target_alpha.end());
  CHECK(*target_min >= std::min(0.0, *source_min) - 1e-9);
  CHECK(*target_max <= std::max(1.0, *source_max) + 1e-9);
}

TEST_CASE("a tiny basin with the tailwater control resets the outlet's Umean after every leg and resumes with it",
          "[reference][openfoam][tailwater]") {
  require_openfoam();
  const std::string spec = tiny_hold_toe_spec("toe_hold_time_s = 5\ntoe_hold_gain = 0.5");
  const cases::Study study = parse(spec);
  const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
  const TempDir tmp("openfoam-tailwater");
  const fs::path dir = generate(spec, tmp.path() / "case");
  std::ostringstream out;
  reference::run_vof_case(dir, reference::RunOptions{}, out);
  INFO(out.str());
  CHECK_THAT(out.str(), Catch::Contains("tailwater control at t = 0.01 s: toe ") &&
                            Catch::Contains("tailwater control at t = 0.02 s: toe ") && Catch::Contains("reached t = 0.02"));
  auto rows = reference::read_tailwater_control_log(dir);
  REQUIRE(rows.size() == 2);
  // The fields are written uncompressed; each leg's end holds the Umean the control set for the next.
  CHECK(!fs::exists(dir / "0.01/U.gz"));
  CHECK(reference::read_outlet_mean_velocity(dir / "0.01/U") == Approx(rows[0].outlet_mean_velocity_m_s).epsilon(1e-8));
  CHECK(reference::read_outlet_mean_velocity(dir / "0.02/U") == Approx(rows[1].outlet_mean_velocity_m_s).epsilon(1e-8));
  // The water volume per unit width: the sampled integral of alpha over the basin / thickness; between
  // the volumes of a basin filled to y1 and to the tailwater (0.06 m) over its 0.472 m.
  const auto check_row = [](const reference::TailwaterControlStep& r) {
    CHECK(r.water_volume_m2 > 0.0254 * 0.472);
    CHECK(r.water_volume_m2 < 0.06 * 0.472);
    // setFields' ramp from y1 at the basin start (0.1 m) to 0.06 m at 0.46 m crosses the line at 1.5 y1 =
    // 0.0381 m at x = 0.1 + 0.36 (0.0381 - 0.0254) / (0.06 - 0.0254) = 0.232 m; in 0.03 s it barely moves.
    CHECK(r.toe_outputs == 1);
    CHECK(r.toe_x_m == Approx(0.232).margin(0.015));
  };
  for (const auto& r : rows) check_row(r);
  // The second step continues from the first's integral I = V* - k_p (y2* - y1) (x_toe - 0.1) (toe
  // target 0.1 m, the basin start; k_p 0.5 set here): V*(n) = I(n-1) + integral term + P(n).
  const auto next_target = [](const reference::TailwaterControlStep& previous, const reference::TailwaterControlStep& r) {
    return previous.volume_target_m2 + (0.06 - 0.0254) / 5.0 * (r.toe_x_m - 0.1) * 0.01 +
           0.5 * (0.06 - 0.0254) * (r.toe_x_m - previous.toe_x_m);
  };
  CHECK(rows[1].volume_target_m2 == Approx(next_target(rows[0], rows[1])).epsilon(1e-9));
  // Resumed to 0.03 s: one more step, from the logged target.
  reference::RunOptions extend;
  extend.resume = true;
  extend.end_time_s = 0.03;
  std::ostringstream out2;
  reference::run_vof_case(dir, extend, out2);
  rows = reference::read_tailwater_control_log(dir);
  REQUIRE(rows.size() == 3);
  CHECK(rows[2].time_s == Approx(0.03));
  check_row(rows[2]);
  CHECK(rows[2].volume_target_m2 == Approx(next_target(rows[1], rows[2])).epsilon(1e-9));
  CHECK(reference::read_outlet_mean_velocity(dir / "0.03/U") == Approx(rows[2].outlet_mean_velocity_m_s).epsilon(1e-8));
  // interFoam ran the second leg with the Umean the first step set: the outlet's water flux over it is that
  // Umean times the outlet's wetted area (the condition's definition), sampled at 0.02 s.
  const auto outlet = rows_of(dir / "postProcessing/discharge_outlet/0.01/surfaceFieldValue.dat");
  REQUIRE(!outlet.empty());
  CHECK(outlet.front()[0] == Approx(0.02));
  const double flux = outlet.front()[1] / vof.mesh.thickness_m;  // m^2/s
  const double wetted = flux / rows[0].outlet_mean_velocity_m_s;  // the outlet's water depth
  CHECK(wetted == Approx(0.06).margin(0.006));  // the tailwater setFields put there, 10 %
  // A fresh start (to the end time 0.03 s now in controlDict) drops the log of the earlier run.
  fs::remove_all(dir / "0.01");
  fs::remove_all(dir / "0.02");
  fs::remove_all(dir / "0.03");
  std::ostringstream out3;
  reference::run_vof_case(dir, reference::RunOptions{}, out3);
  const auto fresh = reference::read_tailwater_control_log(dir);
  REQUIRE(fresh.size() == 3);
  CHECK(fresh[0].time_s == Approx(0.01));
  CHECK(fresh[2].time_s == Approx(0.03));
}

TEST_CASE("the tailwater control resumed between two control times integrates from its last step, and a retried "
          "leg's samples replace the abandoned attempt's",
          "[reference][openfoam][tailwater]") {
  require_openfoam();
  // Outputs every 5 ms, a control step every 10 ms.
  const std::string spec = with_hold_toe(basin_spec("tailwater_control_interval_s = 0.01\n", 0.02, 0.005, "smooth"),
                                         "volume_hold_time_s = 0.02\ntoe_hold_time_s = 5\ntoe_hold_gain = 0.5\n");
  const TempDir tmp("openfoam-tailwater-resume");
  const fs::path dir = generate(spec, tmp.path() / "case");
  std::ostringstream out;
  reference::run_vof_case(dir, reference::RunOptions{}, out);
  INFO(out.str());
  auto rows = reference::read_tailwater_control_log(dir);
  REQUIRE(rows.size() == 2);
  CHECK(rows[1].toe_outputs == 2);
  // V*(n) = I(n-1) + integral term + P(n), I(n-1) = V*(n-1) - P(n-1), P = 0.5 (y2* - y1)(x_toe - 0.1)
  const auto next_target = [](const reference::TailwaterControlStep& previous, const reference::TailwaterControlStep& r) {
    return previous.volume_target_m2 + (0.06 - 0.0254) / 5.0 * (r.toe_x_m - 0.1) * 0.01 +
           0.5 * (0.06 - 0.0254) * (r.toe_x_m - previous.toe_x_m);
  };

  // Killed in the second leg after its output at 0.015 s: the resume starts there, and the step at
  // 0.02 s still covers (0.01, 0.02] s: both outputs' toes and dt = 0.01 s. A surface written by an
  // earlier stop off the output grid (0.0125 s) is not one of them.
  fs::remove_all(dir / "0.02");
  fs::copy(dir / "postProcessing/freeSurface/0.015", dir / "postProcessing/freeSurface/0.0125", fs::copy_options::recursive);
  reference::RunOptions resume;
  resume.resume = true;
  std::ostringstream out2;
  reference::run_vof_case(dir, resume, out2);
  INFO(out2.str());
  rows = reference::read_tailwater_control_log(dir);
  REQUIRE(rows.size() == 2);
  CHECK(rows[1].time_s == Approx(0.02));
  CHECK(rows[1].toe_outputs == 2);
  CHECK(rows[1].volume_target_m2 == Approx(next_target(rows[0], rows[1])).epsilon(1e-9));

  // Killed again before the leg's end, and retried from 0.015 s: OpenFOAM finds the first attempt's
  // volFieldValue.dat there and writes volFieldValue_0.015.dat beside it. The step reads the retry's
  // volume, not the abandoned attempt's (made absurd here to tell them apart).
  const fs::path volume_dir = dir / "postProcessing" / "water_volume" / "0.015";
  std::vector<std::string> lines;
  {
    std::ifstream in(volume_dir / "volFieldValue.dat");
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  REQUIRE(!lines.empty());
  REQUIRE(lines.back()[0] != '#');
  lines.back() = lines.back().substr(0, lines.back().find_first_of(" \t")) + "\t1";
  {
    std::ofstream rewritten(volume_dir / "volFieldValue.dat");
    for (const auto& line : lines) rewritten << line << "\n";
  }
  fs::remove_all(dir / "0.02");
  // The abandoned attempt had also begun a later leg's samples (a start-time directory after 0.015 s):
  // moved aside, not read after the retry's.
  const fs::path later = dir / "postProcessing" / "water_volume" / "0.0175";
  fs::create_directories(later);
  std::ofstream(later / "volFieldValue.dat") << "# Time volIntegrate(alpha.water)\n0.02\t1\n";
  std::ostringstream out3;
  reference::run_vof_case(dir, resume, out3);
  INFO(out3.str());
  CHECK(fs::exists(volume_dir / "volFieldValue_0.015.dat"));
  CHECK_FALSE(fs::exists(later));
  CHECK(fs::exists(later.string() + ".abandoned"));
  rows = reference::read_tailwater_control_log(dir);
  REQUIRE(rows.size() == 2);
  CHECK(rows[1].water_volume_m2 > 0.0254 * 0.472);
  CHECK(rows[1].water_volume_m2 < 0.06 * 0.472);
  CHECK(rows[1].volume_target_m2 == Approx(next_target(rows[0], rows[1])).epsilon(1e-9));
}

TEST_CASE("a tiny basin runs with the k-epsilon turbulence model", "[reference][openfoam]") {
  require_openfoam();
  const std::string spec = basin_spec("turbulence_model = \"kEpsilon\"", 0.02, 0.01);
  const cases::Study study = parse(spec);
  const reference::VofCase vof = reference::build_vof_case(study, study.cases.front(), "quick");
  const TempDir tmp("openfoam-kepsilon");
  const fs::path dir = generate(spec, tmp.path() / "case");
  std::ostringstream out;
  reference::run_vof_case(dir, reference::RunOptions{}, out);
  INFO(out.str());
  CHECK_THAT(out.str(), Catch::Contains("reached t = 0.02"));
  CHECK_THAT(util::read_text_file(dir / "log.interFoam"), Catch::Contains("Selecting RAS turbulence model kEpsilon"));
  CHECK(fs::exists(dir / "0.01/epsilon.gz"));
  const auto inlet = rows_of(dir / "postProcessing/discharge_inlet/0/surfaceFieldValue.dat");
  REQUIRE(!inlet.empty());
  CHECK(std::abs(inlet.back()[1]) / vof.mesh.thickness_m == Approx(0.0254 * 2.0).epsilon(1e-5));
}

TEST_CASE("a tiny basin runs with the multiphase turbulence stabilization", "[reference][openfoam]") {
  require_openfoam();
  const std::string spec =
      basin_spec("turbulence_model = \"RNGkEpsilon\"\nturbulence_stabilization = \"nut_limiter_and_buoyancy\"", 0.02, 0.01);
  const TempDir tmp("openfoam-stabilized");
  const fs::path dir = generate(spec, tmp.path() / "case");
  std::ostringstream out;
  reference::run_vof_case(dir, reference::RunOptions{}, out);
  INFO(out.str());
  CHECK_THAT(out.str(), Catch::Contains("reached t = 0.02"));
  // interFoam read constant/fvOptions (a wrong file class or unknown type would be a warning or an error)
  // and applied both corrections in every step.
  const std::string log = util::read_text_file(dir / "log.interFoam");
  CHECK_THAT(log, Catch::Contains("Selecting finite volume options type multiphaseStabilizedTurbulence"));
  CHECK_THAT(log, Catch::Contains("applying bouyancy production term to k"));  // (sic: OpenFOAM's spelling)
  CHECK_THAT(log, Catch::Contains("correcting nut"));
  CHECK_THAT(log, !Catch::Contains("unexpected class name"));
}

TEST_CASE("an MPI run (--np 2) gives the same result as the serial run", "[reference][openfoam]") {
  require_openfoam();
  const std::string spec = basin_spec("", 0.03, 0.01);
  const TempDir tmp("openfoam-mpi");
  const fs::path serial = generate(spec, tmp.path() / "serial");
  const fs::path parallel = generate(spec, tmp.path() / "parallel");
  std::ostringstream out;
  reference::run_vof_case(serial, reference::RunOptions{}, out);
  reference::RunOptions np2;
  np2.np = 2;
  reference::run_vof_case(parallel, np2, out);
  INFO(out.str());
  CHECK(fs::exists(parallel / "processor1"));
  CHECK(fs::exists(parallel / "0.03/U.gz"));  // reconstructed
  for (const char* section : {"up", "mid", "down"}) {
    INFO(section);
    const std::string file = std::string("postProcessing/sections/0.03/") + section + "_alpha.water.xy";
    const double d_serial = water_depth(serial / file);
    const double d_parallel = water_depth(parallel / file);
    CHECK(d_serial > 0.02);
    CHECK(d_parallel == Approx(d_serial).epsilon(0.01));
  }
  // Resuming a decomposed run continues in parallel from the processor directories. Killed while
  // writing 0.03: rank 1's turbulence field k is cut short (rank 0's 0.03 is whole), and so is the
  // reconstructed U; rank 0 also holds a 0.03.incomplete from an earlier kill. The time 0.03 is
  // incomplete on every rank, moved aside beside the earlier one, and reconstructed again at the end.
  const auto cut_short = [](const fs::path& file) {
    REQUIRE(fs::exists(file));
    const std::string text = util::read_text_file(file);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text.substr(0, text.size() / 2);
  };
  cut_short(parallel / "processor1/0.03" / (fs::exists(parallel / "processor1/0.03/k.gz") ? "k.gz" : "k"));
  cut_short(parallel / "0.03/U.gz");
  fs::create_directories(parallel / "processor0/0.03.incomplete/U");
  // Rank 1 alone had begun a later time; rank 0's 0.02 holds a temporary file of a write cut short
  // (not OpenFOAM's: 0.02 stays the start).
  fs::create_directories(parallel / "processor1/0.04");
  std::ofstream(parallel / "processor0/0.02/.U.tmp.1.1") << "FoamFile {";
  np2.resume = true;
  std::ostringstream out2;
  reference::run_vof_case(parallel, np2, out2);
  INFO(out2.str());
  CHECK_THAT(out2.str(), Catch::Contains("time directory 0.03 (processor*/) is incomplete"));
  CHECK_THAT(out2.str(), Catch::Contains("reconstructed time directory 0.03 is incomplete"));
  CHECK_THAT(out2.str(), Catch::Contains("Resuming from t = 0.02"));
  CHECK_THAT(out2.str(), !Catch::Contains("decomposePar"));
  CHECK(fs::exists(parallel / "processor0/0.03.incomplete.2"));
  CHECK(fs::exists(parallel / "processor1/0.03.incomplete"));
  CHECK(fs::exists(parallel / "processor1/0.04.incomplete"));
  CHECK_FALSE(fs::exists(parallel / "processor1/0.04"));
  CHECK(fs::exists(parallel / "0.03.incomplete"));
  CHECK(fs::exists(parallel / "processor1/0.03/k.gz") != fs::exists(parallel / "processor1/0.03/k"));
  REQUIRE(fs::exists(parallel / "0.03/U.gz"));
  CHECK(std::system(("gzip -t '" + (parallel / "0.03/U.gz").string() + "'").c_str()) == 0);
}

TEST_CASE("an MPI run (--np 2) with the tailwater control resets Umean in every processor's latest U",
          "[reference][openfoam][tailwater]") {
  require_openfoam();
  const std::string spec = tiny_hold_toe_spec();
  const TempDir tmp("openfoam-tailwater-mpi");
  const fs::path dir = generate(spec, tmp.path() / "case");
  reference::RunOptions options;
  options.np = 2;
  std::ostringstream out;
  reference::run_vof_case(dir, options, out);
  INFO(out.str());
  const auto rows = reference::read_tailwater_control_log(dir);
  REQUIRE(rows.size() == 2);
  for (const char* rank : {"processor0", "processor1"}) {
    CHECK(reference::read_outlet_mean_velocity(dir / rank / "0.01/U") == Approx(rows[0].outlet_mean_velocity_m_s).epsilon(1e-8));
    CHECK(reference::read_outlet_mean_velocity(dir / rank / "0.02/U") == Approx(rows[1].outlet_mean_velocity_m_s).epsilon(1e-8));
  }
  // reconstructPar takes the boundary condition from the processors' files.
  CHECK(reference::read_outlet_mean_velocity(dir / "0.02/U") == Approx(rows[1].outlet_mean_velocity_m_s).epsilon(1e-8));
  CHECK(rows[1].toe_outputs == 1);
}

TEST_CASE("an MPI run that stops early has the times written so far reconstructed for compare and ParaView",
          "[reference][openfoam][tailwater]") {
  require_openfoam();
  // The tailwater control stops the run after its first leg: the case's controlDict, edited by hand,
  // compresses the fields it has to rewrite.
  const std::string spec = tiny_hold_toe_spec();
  const TempDir tmp("openfoam-mpi-stopped");
  const fs::path dir = generate(spec, tmp.path() / "case");
  std::string control = util::read_text_file(dir / "system/controlDict");
  const std::string plain = "writeCompression off;";
  REQUIRE(control.find(plain) != std::string::npos);
  control.replace(control.find(plain), plain.size(), "writeCompression on;");
  { std::ofstream(dir / "system/controlDict") << control; }
  reference::RunOptions options;
  options.np = 2;
  std::ostringstream out;
  CHECK_THROWS_WITH(reference::run_vof_case(dir, options, out),
                    Catch::Contains("is compressed") &&
                        Catch::Contains("The times written up to t = 0.01 s were reconstructed into " + dir.string()) &&
                        Catch::Contains("--resume --np 2"));
  INFO(out.str());
  // The first leg's fields are in the case directory, the processors' kept; nothing after it.
  CHECK(fs::exists(dir / "0.01/alpha.water.gz"));
  CHECK(fs::exists(dir / "processor0/0.01/alpha.water.gz"));
  CHECK(fs::exists(dir / "processor1/0.01/alpha.water.gz"));
  CHECK_FALSE(fs::exists(dir / "0.02"));
  CHECK_THAT(util::read_text_file(dir / "log.reconstructPar"), Catch::Contains("Time = 0.01"));
}

TEST_CASE("Ctrl-C while interFoam runs writes the current time and stops, and --resume goes on from it",
          "[reference][openfoam][stop]") {
  require_openfoam();
  const TempDir tmp("openfoam-stop");
  const fs::path dir = generate(basin_spec("", 1.0, 0.25), tmp.path() / "case");
  std::ostringstream out;
  {
    // After a few time steps (the first output is at 0.25 s).
    const InterruptWhen ctrl_c(dir / "log.interFoam", "\nTime = 0.01");
    CHECK_THROWS_WITH(reference::run_vof_case(dir, reference::RunOptions{}, out),
                      Catch::StartsWith("interrupted: interFoam stopped at t = ") &&
                          Catch::Contains("--resume"));
    CHECK(ctrl_c.sent());
  }
  INFO(out.str());
  CHECK_THAT(out.str(), Catch::Contains("Stop requested: interFoam writes the current time and stops"));
  // It wrote the time it had reached, before the first output time (so on request), whole; the lock
  // no longer names a solver.
  const auto written = reference::latest_time(dir);
  REQUIRE(written.has_value());
  CHECK(*written > 0.01);
  CHECK(*written < 0.25);
  CHECK_THAT(util::read_text_file(dir / ".hydrojump.lock"), !Catch::Contains("its solver"));
  // Resumed (to the first output time, to keep the test short) it goes on from there.
  reference::RunOptions resume;
  resume.resume = true;
  resume.end_time_s = 0.25;
  std::ostringstream out2;
  reference::run_vof_case(dir, resume, out2);
  INFO(out2.str());
  CHECK_THAT(out2.str(), Catch::Contains("Resuming from t = ") && Catch::Contains("reached t = 0.25"));
  CHECK(fs::exists(dir / "0.25"));
}

TEST_CASE("Ctrl-C during meshing stops the step and starts nothing after it, and the next run meshes again",
          "[reference][openfoam][stop]") {
  require_openfoam();
  const TempDir tmp("openfoam-stop-mesh");
  const fs::path dir = generate(basin_spec("", 0.02, 0.01), tmp.path() / "case");
  std::ostringstream out;
  {
    const InterruptWhen ctrl_c(dir / "log.blockMesh", "");
    CHECK_THROWS_WITH(reference::run_vof_case(dir, reference::RunOptions{}, out),
                      Catch::StartsWith("interrupted: ") && Catch::Contains("was stopped on request") &&
                          Catch::Contains("Nothing was computed yet: run the same `hydrojump vof` command again"));
    CHECK(ctrl_c.sent());
  }
  INFO(out.str());
  CHECK_FALSE(fs::exists(dir / "log.interFoam"));
  CHECK_FALSE(fs::exists(dir / "log.setFields"));
  std::ostringstream out2;
  reference::run_vof_case(dir, reference::RunOptions{}, out2);
  INFO(out2.str());
  CHECK_THAT(out2.str(), Catch::Contains("blockMesh") && Catch::Contains("reached t = 0.02"));
}

TEST_CASE("processor directories of a decomposition that was cut short are removed and made again",
          "[reference][openfoam][stop]") {
  require_openfoam();
  const TempDir tmp("openfoam-decomposition-cut-short");
  const fs::path dir = generate(basin_spec("", 0.02, 0.01), tmp.path() / "case");
  // decomposePar killed while writing: two ranks begun, a time directory in one of them, and the
  // runner's marker still there.
  fs::create_directories(dir / "processor0/constant/polyMesh");
  fs::create_directories(dir / "processor0/0.01");
  fs::create_directories(dir / "processor1");
  std::ofstream(dir / "processor0/0.01/U") << "FoamFile {";
  std::ofstream(dir / ".decomposing") << "decomposePar started by hydrojump vof\n";
  reference::RunOptions np2;
  np2.np = 2;
  std::ostringstream out;
  reference::run_vof_case(dir, np2, out);
  INFO(out.str());
  CHECK_THAT(out.str(), Catch::Contains("removed 2 processor directories left by a decomposePar that was cut short"));
  CHECK_THAT(out.str(), Catch::Contains("decomposePar") && Catch::Contains("reached t = 0.02"));
  CHECK_FALSE(fs::exists(dir / ".decomposing"));
  CHECK(fs::exists(dir / "processor1/0.02"));
  CHECK(fs::exists(dir / "0.02"));
}

TEST_CASE("body_fitted is refused exactly when the self-test shows the non-orthogonal defect",
          "[reference][openfoam]") {
  require_openfoam();
  const TempDir tmp("openfoam-body-fitted");
  const reference::SelfTestResult st = reference::self_test_non_orthogonal(tmp.path());
  INFO(st.summary());
  REQUIRE(st.axis_aligned_ok);
  const std::string spec = basin_spec("mesh_strategy = \"body_fitted\"\nturbulence_model = \"laminar\"", 0.05, 0.01);
  const fs::path dir = generate(spec, tmp.path() / "case");
  std::ostringstream out;
  if (!st.sheared_ok) {
    CHECK_THROWS_WITH(reference::run_vof_case(dir, reference::RunOptions{}, out),
                      Catch::Contains("body_fitted\" refused") && Catch::Contains("cartesian_cut"));
    CHECK_FALSE(fs::exists(dir / "constant/polyMesh"));  // refused before meshing
    // Forced, the mesh passes checkMesh but the solver diverges; the runner stops it with a diagnosis.
    reference::RunOptions force;
    force.force_body_fitted = true;
    try {
      reference::run_vof_case(dir, force, out);
      FAIL("the body_fitted run was expected to diverge on this build");
    } catch (const reference::OpenFoamError& e) {
      const std::string message = e.what();
      INFO(message);
      CHECK_THAT(util::read_text_file(dir / "log.checkMesh"), Catch::Contains("Mesh OK."));
      CHECK((message.find("blew up") != std::string::npos || message.find("crashed") != std::string::npos ||
             message.find("not a number") != std::string::npos || message.find("collapsed") != std::string::npos));
      CHECK_THAT(message, Catch::Contains("Last lines of log.interFoam"));
    }
  } else {
    reference::run_vof_case(dir, reference::RunOptions{}, out);
    CHECK(fs::exists(dir / "0.05"));
  }
}

TEST_CASE("a tiny dam break runs and samples its gauges and the floor line", "[reference][openfoam]") {
  require_openfoam();
  const TempDir tmp("openfoam-dam");
  const fs::path dir = generate(dam_break_spec(), tmp.path() / "case");
  std::ostringstream out;
  reference::run_vof_case(dir, reference::RunOptions{}, out);
  INFO(out.str());
  CHECK(fs::exists(dir / "0.02"));
  CHECK(fs::exists(dir / "postProcessing/sections/0.02/floor_alpha.water.xy"));
  // The column is still about 0.2 m deep at gauge H1 (x = 0.05 m) after 0.02 s.
  CHECK(water_depth(dir / "postProcessing/sections/0.02/H1_alpha.water.xy") == Approx(0.2).margin(0.01));
}

TEST_CASE("a failing mesh step stops the run with its log", "[reference][openfoam]") {
  require_openfoam();
  const TempDir tmp("openfoam-bad-mesh");
  const fs::path dir = generate(basin_spec(), tmp.path() / "case");
  {
    std::ofstream broken(dir / "system/blockMeshDict", std::ios::app);
    broken << "\nblocks ( hex (0 1 2) (1 1 1) simpleGrading (1 1 1) );\n";
  }
  std::ostringstream out;
  CHECK_THROWS_WITH(reference::run_vof_case(dir, reference::RunOptions{}, out),
                    Catch::Contains("blockMesh failed") && Catch::Contains("log.blockMesh"));
}

TEST_CASE("a missing OpenFOAM installation is reported clearly", "[reference][openfoam]") {
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", "/nonexistent-hydrojump", 1);
  CHECK_THROWS_WITH(reference::check_openfoam(false), Catch::Contains("not on PATH") && Catch::Contains("openfoam"));
  ::setenv("PATH", saved.c_str(), 1);
}

TEST_CASE("the generated Allrun runs the case by hand as an OpenFOAM user would", "[reference][openfoam]") {
  require_openfoam();
  const TempDir tmp("openfoam-allrun");
  const fs::path dir = generate(basin_spec("", 0.02, 0.01), tmp.path() / "case");
  const std::string command = "sh '" + (dir / "Allrun").string() + "' > '" + (dir / "allrun.out").string() + "' 2>&1";
  CHECK(std::system(command.c_str()) == 0);
  INFO(util::read_text_file(dir / "allrun.out"));
  CHECK(fs::exists(dir / "0.02"));
  CHECK_THAT(util::read_text_file(dir / "log.checkMesh"), Catch::Contains("Mesh OK."));
  CHECK(fs::exists(dir / "log.topoSet.2"));  // the section zones, after the cut
  // Run again, it refuses to mesh anew beneath the results it would continue from.
  CHECK(std::system(command.c_str()) != 0);
  CHECK_THAT(util::read_text_file(dir / "allrun.out"), Catch::Contains("holds the results of an earlier run"));
  CHECK(fs::exists(dir / "0.02"));
}
