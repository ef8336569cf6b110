// Validation records (compare/record.hpp) and the document made from them (compare/validation_doc.hpp):
// a record reads back exactly as written, bad records are refused by file and key, a compared case
// directory gives one record per finished method with that method's values, and the document's
// differences are the hand-computed ones.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "util/fingerprint.hpp"
#include "cases/spec_reader.hpp"
#include "compare/record.hpp"
#include "compare/validation_doc.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using namespace hydrojump::compare;

namespace {

ValidationRecord sample_record(const std::string& method, double y2) {
  ValidationRecord r;
  r.study = "mini";
  r.case_id = "A";
  r.description = "a \"quoted\" description";
  r.method = method;
  r.resolution = "quick";
  r.run_key = "0123456789abcdef";
  r.hydrojump_version = "0.1.0+test";
  r.recorded_on = "2026-11-29";
  r.command = "hydrojump study mini.toml --cases A --resolution quick --methods " + method;
  r.tailwater_control = "hold_toe";
  r.wall_time_s = 1234.5;
  r.legs = 2;
  r.threads = 2;
  r.machine = "Test CPU @ 2.0GHz, 2 cores";
  r.window_start_s = 6.2;
  r.window_end_s = 9.3;
  r.metrics = {{"sequent_depth", "m", "predicted", y2, 0.104, std::nullopt, 0.1317813053},
               {"eta", "%", "predicted", 45.448, 48.43, 47.08, 39.2188},
               {"toe_mean_of_frames", "m", "imposed", 0.21628, std::nullopt, std::nullopt, std::nullopt}};
  r.profiles = {{"x_2y2", 0.408, {0.0, 0.01, 1.0 / 3.0}, {1.5, -0.25, 0.1}}};
  r.surface_x_m = {0.1, 0.2};
  r.surface_mean_m = {0.0254, 0.1085};
  return r;
}

// A wall time as the document writes it, rounded to the minute: "29 min", "1 h 02 min".
std::string minutes_text(double seconds) {
  const long m = (std::lround(seconds) + 30) / 60;
  return m >= 60 ? std::to_string(m / 60) + " h " + (m % 60 < 10 ? "0" : "") + std::to_string(m % 60) + " min"
                 : std::to_string(m) + " min";
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

}  // namespace

TEST_CASE("A validation record reads back exactly as written", "[compare][record]") {
  const ValidationRecord r = sample_record("sph", 0.108535);
  const ValidationRecord back = parse_record(record_text(r), "A/sph-quick.toml");
  CHECK(back.study == r.study);
  CHECK(back.description == r.description);
  CHECK(back.run_key == r.run_key);
  CHECK(back.command == r.command);
  CHECK(*back.wall_time_s == 1234.5);
  CHECK(*back.legs == 2);
  CHECK(back.machine == r.machine);
  CHECK(*back.threads == 2);
  CHECK(back.window_start_s == 6.2);
  REQUIRE(back.metrics.size() == 3);
  CHECK(back.metrics[0].value == 0.108535);
  CHECK(*back.metrics[0].smooth_theory == 0.1317813053);
  CHECK_FALSE(back.metrics[0].published_sph);
  CHECK(back.metric("toe_mean_of_frames")->status == "imposed");
  REQUIRE(back.profiles.size() == 1);
  CHECK(back.profiles[0].z_m[2] == 1.0 / 3.0);  // exact: the shortest text that reads back
  CHECK(back.surface_mean_m == r.surface_mean_m);
  // The same record gives the same text.
  CHECK(record_text(back) == record_text(r));
}

TEST_CASE("A damaged validation record is refused by file and key", "[compare][record]") {
  const std::string good = record_text(sample_record("sph", 0.11));
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const auto refusal = [](const std::string& text) {
    try {
      parse_record(text, "rec.toml");
    } catch (const RecordError& e) {
      return std::string(e.what());
    }
    FAIL("the record was accepted");
    return std::string();
  };
  CHECK_THAT(refusal(replaced("format = 1", "format = 7")), Catch::Contains("rec.toml: format is not 1"));
  CHECK_THAT(refusal(replaced("run_key = ", "key = ")), Catch::Contains("rec.toml: run_key is missing"));
  CHECK_THAT(refusal(replaced("method = \"sph\"", "method = \"lbm\"")), Catch::Contains("method = \"lbm\" is not"));
  CHECK_THAT(refusal(replaced("window_s = [6.2, 9.3]", "window_s = [9.3, 6.2]")), Catch::Contains("rec.toml: window_s"));
  CHECK_THAT(refusal(replaced("value = 0.11", "value = \"high\"")), Catch::Contains("metrics.sequent_depth: value"));
  CHECK_THAT(refusal(replaced("legs = 2", "legs = 0")), Catch::Contains("rec.toml: legs = 0 must be at least 1"));
  CHECK_THAT(refusal(good + "\n[[[\n"), Catch::Contains("rec.toml:") && Catch::Contains("not a valid record"));
}

TEST_CASE("A compared case directory gives one record per finished method with that method's values",
          "[compare][record]") {
  const hydrojump::testing::TempDir tmp("record_case");
  // Run A_smooth of the test fixture: a 10 s run averaged over 6-10 s, the toe held.
  const auto study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  const fs::path dir = tmp.path() / "A_smooth";
  fs::create_directories(dir / "sph");
  hydrojump::cases::write_resolved_case(study, *study.find_case("A_smooth"), "quick", dir / "sph" / "case.toml");
  write(dir / "sph.stamp", "feedfacefeedface");
  write(dir / "sph.stage.toml", "wall_time_s = 600.0\nlegs = 3\nthreads = 2\nmachine = \"Some CPU, 2 cores\"\n");
  // The VOF stage did not finish (no stamp): no VOF record.
  write(dir / "csv" / "metrics.csv",
        "quantity,unit,sph,vof,experiment,published_sph,smooth_theory,status\n"
        "sequent_depth,m,0.1331,0.1286,nan,nan,0.131781,predicted\n"
        "toe_std,m,0.041,nan,nan,nan,nan,predicted\n"
        // SPH gave no roller length, which has an inputs-only value (kept as nan beside it), nor a jump
        // length, which has none (left out).
        "roller_length,m,nan,0.2,nan,nan,0.301256,predicted\n"
        "jump_length,m,nan,0.5,nan,nan,nan,predicted\n");
  write(dir / "csv" / "profiles.csv", "method,section,x_m,z_m,u_mean_m_s,u_std_m_s,w_mean_m_s,wet_fraction\n"
                                      "sph,up,0.1,0,1.99,0.03,0.0,1\nsph,up,0.1,0.01,1.98,0.03,0.0,1\n"
                                      "vof,up,0.1,0,1.5,0.03,0.0,1\nsph,down,1.0,0,0.4,0.1,0.0,1\n");
  write(dir / "csv" / "longitudinal.csv", "method,x_m,z_bed_m,surface_mean_m\nsph,0.1,0,0.026\nvof,0.1,0,0.027\n");
  const auto records = records_from_case_dir(dir, {"2026-11-29", "cmd"});
  REQUIRE(records.size() == 1);
  const ValidationRecord& r = records[0];
  CHECK(r.method == "sph");
  CHECK(r.study == "ead2002");
  CHECK(r.case_id == "A_smooth");
  CHECK(r.bed == "smooth");
  CHECK(r.basin_start_m == 0.2);
  CHECK(r.resolution == "quick");
  CHECK(r.run_key == "feedfacefeedface");
  CHECK(r.window_start_s == 6.0);
  CHECK(r.window_end_s == 10.0);
  CHECK(*r.wall_time_s == 600.0);
  CHECK(*r.legs == 3);
  CHECK(r.machine == "Some CPU, 2 cores");
  CHECK(r.tailwater_control == "hold_toe");
  CHECK(r.metric("sequent_depth")->value == 0.1331);
  CHECK(*r.metric("sequent_depth")->smooth_theory == 0.131781);
  CHECK_FALSE(r.metric("sequent_depth")->experiment);
  CHECK(r.metric("toe_std")->value == 0.041);
  REQUIRE(r.metric("roller_length"));
  CHECK(std::isnan(r.metric("roller_length")->value));
  CHECK(*r.metric("roller_length")->smooth_theory == 0.301256);
  CHECK_FALSE(r.metric("jump_length"));
  // ... and reads back so.
  const ValidationRecord back = parse_record(record_text(r), "A_smooth/sph-quick.toml");
  CHECK(std::isnan(back.metric("roller_length")->value));
  CHECK(*back.metric("roller_length")->smooth_theory == 0.301256);
  REQUIRE(r.profiles.size() == 2);
  CHECK(r.profiles[0].u_mean_m_s == std::vector<double>{1.99, 1.98});
  CHECK(r.surface_mean_m == std::vector<double>{0.026});
  // A directory with no comparison is refused by name.
  CHECK_THROWS_WITH(records_from_case_dir(tmp.path() / "none", {}), Catch::Contains("has no finished comparison"));

  // The imported comparison: the study report's tables from the records.
  const fs::path imported = tmp.path() / "imported";
  write_imported_comparison(imported, {sample_record("sph", 0.11), sample_record("vof", 0.12)});
  const std::string metrics = hydrojump::util::read_text_file(imported / "csv" / "metrics.csv");
  CHECK_THAT(metrics, Catch::Contains("sequent_depth,m,0.11,0.12,0.104,nan,0.1317813053,predicted"));
  CHECK_THAT(hydrojump::util::read_text_file(imported / "csv" / "eta.csv"),
             Catch::Contains("A,39.2188,48.43,47.08,45.448,45.448,nan,nan"));
}

TEST_CASE("The validation document gives the hand-computed differences and is the same for the same records",
          "[compare][record]") {
  const std::vector<ValidationRecord> records = {sample_record("sph", 0.108535), sample_record("vof", 0.113782)};
  const std::string md = validation_markdown(records, "validation/records");
  // y2: 0.108535 / 0.104 - 1 = +4.36 %; eta: 45.448 - 48.43 = -2.98 points; SPH - VOF: 0.108535 / 0.113782 - 1 = -4.6 %.
  CHECK_THAT(md, Catch::Contains("| A | SPH | quick | predicted | 0.1085 | 0.104 | +4.4 % | 0.1318 |"));
  CHECK_THAT(md, Catch::Contains("| 45.45 | 48.43 | -2.98 | 47.08 | 39.22 |"));  // eta, lab, difference, Bo et al., eta*
  CHECK_THAT(md, Catch::Contains("| A | quick | 0.1085 | 0.1138 | -4.6 % |"));
  CHECK_THAT(md, Catch::Contains("21 min (2 threads, in 2 legs)"));
  CHECK_THAT(md, Catch::Contains("`hydrojump study mini.toml --cases A --resolution quick --methods vof`"));
  CHECK(validation_markdown(records, "validation/records") == md);
  CHECK_THAT(validation_markdown({}, "validation/records"), Catch::Contains("No records yet."));
}

TEST_CASE("The README headline table goes between its markers and a document without them is refused", "[compare][record]") {
  const std::vector<ValidationRecord> records = {sample_record("sph", 0.108535)};
  const std::string block = headline_markdown(records);
  // y2 against the lab: 0.108535 / 0.104 - 1 = +4.4 %; eta 45.448 - 48.43 = -2.98 points; no VOF record.
  CHECK_THAT(block, Catch::Contains("| A | quick | +4.4 % of lab / not run | -2.98 / not run |"));
  // Both methods of a case share its row: SPH - VOF on y2 = 0.108535 / 0.113782 - 1 = -4.6 %.
  const std::string both = headline_markdown({sample_record("sph", 0.108535), sample_record("vof", 0.113782)});
  CHECK_THAT(both, Catch::Contains("| A | quick | +4.4 % of lab / +9.4 % of lab |") && Catch::Contains("| -4.6 % |"));
  CHECK(std::count(both.begin(), both.end(), '\n') == 3);
  const std::string doc = "intro\n<!-- validation-table:start -->\nold table\n<!-- validation-table:end -->\nafter\n";
  const std::string updated = with_headline(doc, block, "README.md");
  CHECK(updated == "intro\n<!-- validation-table:start -->\n" + block + "<!-- validation-table:end -->\nafter\n");
  CHECK(with_headline(updated, block, "README.md") == updated);
  CHECK_THROWS_WITH(with_headline("no markers\n", block, "README.md"), Catch::Contains("README.md: has no"));
}

TEST_CASE("The validation document names each record's jump structure from the jet height and the wall-jet profile",
          "[compare][record]") {
  auto with = [](double jet, double deviation) {
    ValidationRecord r = sample_record("sph", 0.108535);
    r.metrics.push_back({"jet_height", "", "predicted", jet, std::nullopt, std::nullopt, std::nullopt});
    if (std::isfinite(deviation))
      r.metrics.push_back({"wall_jet_deviation", "", "predicted", deviation, std::nullopt, std::nullopt, std::nullopt});
    return validation_markdown({r}, "validation/records");
  };
  CHECK_THAT(with(0.12, 0.08), Catch::Contains("| classic (0.12, 0.08) |"));
  CHECK_THAT(with(0.12, 0.23), Catch::Contains("| wall jet, profile off (0.12, 0.23) |"));
  CHECK_THAT(with(0.85, std::nan("")), Catch::Contains("| surface jet (0.85) |"));
  CHECK_THAT(with(0.12, std::nan("")), Catch::Contains("| wall jet (0.12) |"));
}

TEST_CASE("The validation document says at which resolution each method first gives a classic jump and marks the "
          "others exploratory",
          "[compare][record]") {
  auto with = [](const std::string& method, const std::string& resolution, double jet, double deviation) {
    ValidationRecord r = sample_record(method, 0.108535);
    r.resolution = resolution;
    r.metrics.push_back({"jet_height", "", "predicted", jet, std::nullopt, std::nullopt, std::nullopt});
    r.metrics.push_back({"wall_jet_deviation", "", "predicted", deviation, std::nullopt, std::nullopt, std::nullopt});
    return r;
  };
  // SPH classic at both resolutions; VOF a wall jet off Verhoff's profile at quick (0.23 > 0.15), classic
  // at default; records given finest first, the table's columns in the order of refinement.
  const std::vector<ValidationRecord> records = {with("sph", "default", 0.05, 0.09), with("sph", "quick", 0.10, 0.12),
                                                 with("vof", "default", 0.20, 0.10), with("vof", "quick", 0.20, 0.23)};
  const std::string md = validation_markdown(records, "validation/records");
  CHECK_THAT(md, Catch::Contains("| case | method | quick | default | first classic |"));
  CHECK_THAT(md, Catch::Contains("| A | SPH | classic | classic | quick |"));
  CHECK_THAT(md, Catch::Contains("| A | VOF | wall jet, profile off | classic | default |"));
  CHECK_THAT(md, Catch::Contains("Classic at the coarsest resolution run: SPH 1 of 1 cases; VOF 0 of 1 cases."));
  // The quick VOF row is exploratory, in the targets (y2 +4.4 % and eta -2.98 points are met) and in the
  // README's headline; the classic rows are not.
  CHECK_THAT(md, Catch::Contains("| A | VOF | quick | met (2); exploratory: wall jet, profile off |"));
  CHECK_THAT(md, Catch::Contains("| A | SPH | quick | met (2) |"));
  CHECK_THAT(headline_markdown(records), Catch::Contains("| met (2) | met (2); exploratory: wall jet, profile off |"));
  // A method that never gives a classic jump, and a surface jet; a stale record is named so.
  ValidationRecord surface = with("vof", "quick", 0.86, std::nan(""));
  surface.stale = true;
  const std::string none = validation_markdown({surface}, "validation/records");
  CHECK_THAT(none, Catch::Contains("| A | VOF | surface jet (stale) | none yet |"));
  CHECK_THAT(none, Catch::Contains("exploratory: surface jet"));
}

TEST_CASE("Cases not run are listed with a wall time scaled from a measured record of the same method",
          "[compare][record]") {
  const auto study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  ValidationRecord a = sample_record("sph", 0.108535);
  a.study = study.name;
  a.wall_time_s = 1800.0;
  const std::string md = not_run_markdown(study, {a}, "quick");
  // A's SPH has a record and is not listed; A_smooth's SPH is, scaled from A by water area x T x U1 / dx.
  CHECK_THAT(md, !Catch::Contains("| A | SPH |"));
  const auto& ca = *std::find_if(study.cases.begin(), study.cases.end(), [](const auto& c) { return c.id == "A"; });
  const auto& cs = *std::find_if(study.cases.begin(), study.cases.end(), [](const auto& c) { return c.id == "A_smooth"; });
  auto work = [](const hydrojump::cases::Case& c) {
    const auto& b = *c.stilling_basin();
    const double dx = c.resolutions.at("quick").particle_spacing_m;
    return (b.upstream_length_m + b.basin_length_m + b.downstream_length_m) * b.tailwater_depth_m / (dx * dx) *
           c.run.end_time_s * b.inflow_velocity_m_s / dx;
  };
  const long minutes = std::lround(1800.0 * work(cs) / work(ca) / 60.0);
  INFO(md);
  CHECK_THAT(md, Catch::Contains("| A_smooth | SPH |") && Catch::Contains(std::to_string(minutes) + " min on 2 threads |"));
  // No VOF record: its rows have no estimate.
  CHECK_THAT(md, Catch::Contains("| A | VOF |") && Catch::Contains("s | — |"));
  // The whole study: A's measured 30 min plus every other basin scaled from it.
  double estimated_s = 0.0;
  for (const auto& c : study.cases)
    if (c.id != "A" && c.stilling_basin() && c.resolutions.count("quick")) estimated_s += 1800.0 * work(c) / work(ca);
  const std::string estimate = minutes_text(estimated_s);
  CHECK_THAT(md, Catch::Contains("SPH 30 min measured + ~" + estimate + " estimated; VOF 0 min measured + unknown estimated."));
}

TEST_CASE("The whole study's stages, measured or estimated, are scheduled two at a time as the study runs them",
          "[compare][record]") {
  const auto study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  ValidationRecord a = sample_record("sph", 0.108535), v = sample_record("vof", 0.108535);
  a.study = v.study = study.name;
  a.wall_time_s = 1800.0;
  v.wall_time_s = 600.0;
  const auto& ca = *std::find_if(study.cases.begin(), study.cases.end(), [](const auto& c) { return c.id == "A"; });
  // Each basin's stage times by hand: A's measured ones, the others scaled by size x T x U1 / dx.
  auto work = [](const hydrojump::cases::Case& c, bool sph) {
    const auto& b = *c.stilling_basin();
    const auto& r = c.resolutions.at("quick");
    const double length = b.upstream_length_m + b.basin_length_m + b.downstream_length_m;
    const double size = sph ? length * b.tailwater_depth_m / (r.particle_spacing_m * r.particle_spacing_m)
                            : length * (b.tailwater_depth_m + b.air_height_m) / (r.vof_cell_size_bed_m * r.vof_cell_size_bulk_m);
    return size * c.run.end_time_s * b.inflow_velocity_m_s / (sph ? r.particle_spacing_m : r.vof_cell_size_bed_m);
  };
  std::vector<std::pair<double, double>> stages;  // (the case's SPH work, seconds), in spec order
  for (const auto& c : study.cases) {
    if (!c.stilling_basin() || !c.resolutions.count("quick")) continue;
    stages.push_back({work(c, true), c.id == "A" ? 1800.0 : 1800.0 * work(c, true) / work(ca, true)});
    stages.push_back({work(c, true), c.id == "A" ? 600.0 : 600.0 * work(c, false) / work(ca, false)});
  }
  // The largest case's first (stable), each to the worker free first.
  std::stable_sort(stages.begin(), stages.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  double free_at[2] = {0.0, 0.0};
  for (const auto& st : stages) *std::min_element(free_at, free_at + 2) += st.second;
  const std::string expected = minutes_text(std::max(free_at[0], free_at[1]));
  const std::string md = not_run_markdown(study, {a, v}, "quick");
  INFO(md);
  CHECK_THAT(md, Catch::Contains("these stage times take ~" + expected + " (list schedule"));
  // Without a VOF record the VOF stages have no time: no schedule.
  CHECK_THAT(not_run_markdown(study, {a}, "quick"), !Catch::Contains("list schedule"));
  // Every basin recorded with both methods (each record's time as the estimate above gave it): nothing
  // is listed as not run, and the same schedule is given as measured.
  std::vector<ValidationRecord> all;
  double sph_s = 0.0, vof_s = 0.0;
  for (const auto& c : study.cases) {
    if (!c.stilling_basin() || !c.resolutions.count("quick")) continue;
    for (ValidationRecord r : {a, v}) {
      r.case_id = c.id;
      const bool sph = r.method == "sph";
      r.wall_time_s = c.id == "A" ? *r.wall_time_s : *r.wall_time_s * work(c, sph) / work(ca, sph);
      (sph ? sph_s : vof_s) += *r.wall_time_s;
      all.push_back(r);
    }
  }
  const std::string every = not_run_markdown(study, all, "quick");
  INFO(every);
  CHECK_THAT(every, Catch::Contains("## Every case run at `quick`") && !Catch::Contains("## Not run"));
  CHECK_THAT(every, Catch::Contains("SPH " + minutes_text(sph_s) + ", VOF " + minutes_text(vof_s) + "."));
  CHECK_THAT(every, Catch::Contains("these stage times take ~" + expected + " (list schedule of the measured times"));
}

TEST_CASE("Cases not run at a finer resolution are estimated from a record at another resolution",
          "[compare][record]") {
  const auto study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  ValidationRecord a = sample_record("sph", 0.108535);  // A at quick, 30 min on 2 threads
  a.study = study.name;
  a.wall_time_s = 1800.0;
  const auto& ca = *std::find_if(study.cases.begin(), study.cases.end(), [](const auto& c) { return c.id == "A"; });
  // SPH work ~ water area / dx^2 x T U1 / dx: A at default costs (dx_quick / dx_default)^3 of A at quick.
  const double dx_quick = ca.resolutions.at("quick").particle_spacing_m, dx_default = ca.resolutions.at("default").particle_spacing_m;
  const long minutes = std::lround(30.0 * std::pow(dx_quick / dx_default, 3));
  const std::string md = not_run_markdown(study, {a}, "default");
  INFO(md);
  CHECK_THAT(md, Catch::Contains("## Not run at `default`") && Catch::Contains("A (SPH, at `quick`)"));
  CHECK_THAT(md, Catch::Contains("| A | SPH |") && Catch::Contains("~" + std::to_string(minutes) + " min on 2 threads |"));
  // A record at the resolution itself is the reference when there is one.
  ValidationRecord d = a;
  d.resolution = "default";
  d.case_id = "A_smooth";
  CHECK_THAT(not_run_markdown(study, {a, d}, "default"), Catch::Contains("A_smooth (SPH)") && !Catch::Contains("at `quick`"));
}

TEST_CASE("A stale record is marked in every table and its case is listed as not run", "[compare][record]") {
  const auto study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  ValidationRecord a = sample_record("sph", 0.108535);
  a.study = study.name;
  a.stale = true;
  CHECK_THAT(validation_markdown({a}, "validation/records"), Catch::Contains("| A | SPH | quick (stale) |"));
  CHECK_THAT(headline_markdown({a}), Catch::Contains("| A | quick | +4.4 % of lab (stale) / not run |"));
  CHECK_THAT(not_run_markdown(study, {a}, "quick"), Catch::Contains("| A | SPH |"));
  a.stale = false;
  CHECK_THAT(not_run_markdown(study, {a}, "quick"), !Catch::Contains("| A | SPH |"));
}

TEST_CASE("The targets are judged from a record's numbers, and a run not steady over its window is flagged",
          "[compare][record]") {
  // y2 0.108535 against the lab's 0.104: +4.4 % (within 10 %); eta 45.448 against 48.43: -2.98 points
  // (within 3): both met. y2 0.12: +15.4 %, missed.
  CHECK_THAT(headline_markdown({sample_record("sph", 0.108535)}), Catch::Contains("| met (2) | not run |"));
  CHECK_THAT(headline_markdown({sample_record("sph", 0.12)}), Catch::Contains("| missed 1 of 2: y2 +15.4 % | not run |"));
  // The run's water balance still filling by 4.3 % of q over the window: not steady, whatever the targets.
  ValidationRecord r = sample_record("sph", 0.108535);
  r.metrics.push_back({"water_imbalance", "%", "check", -4.3, std::nullopt, std::nullopt, std::nullopt});
  r.metrics.push_back({"steady", "", "check", 0.0, std::nullopt, std::nullopt, std::nullopt});
  CHECK_THAT(headline_markdown({r}), Catch::Contains("| met (2); NOT steady (outflow − inflow -4.3 % of q) | not run |"));
  // Balanced water but not steady (the toe drifting): the flag does not blame the balance.
  r.metrics[r.metrics.size() - 2].value = 0.5;
  CHECK_THAT(headline_markdown({r}), Catch::Contains("| met (2); NOT steady (the toe drifting, lost or the window not reached) |"));
  r.metrics.back().value = 1.0;
  CHECK_THAT(headline_markdown({r}), Catch::Contains("| met (2) | not run |"));
}

TEST_CASE("A failed run is kept as a record with what stopped it, beside the other method's finished one",
          "[compare][record]") {
  const hydrojump::testing::TempDir tmp("record_failed");
  const auto study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  const fs::path dir = tmp.path() / "A_smooth";
  for (const char* method : {"sph", "vof"}) {
    fs::create_directories(dir / method);
    hydrojump::cases::write_resolved_case(study, *study.find_case("A_smooth"), "quick", dir / method / "case.toml");
  }
  // SPH failed (no stamp; the study's sph.failed), VOF finished and was compared.
  write(dir / "sph.failed", "run_key = \"0badc0de0badc0de\"\nfailure = \"the SPH run went unstable at t = 0.73 s\"\n"
                            "wall_time_s = 95.5\nlegs = 2\nthreads = 1\nmachine = \"Some CPU, 2 cores\"\n");
  write(dir / "vof.stamp", "feedfacefeedface");
  write(dir / "csv" / "metrics.csv", "quantity,unit,sph,vof,experiment,published_sph,smooth_theory,status\n"
                                     "sequent_depth,m,nan,0.1286,nan,nan,0.131781,predicted\n");
  auto records = records_from_case_dir(dir, {"2026-12-01", "cmd"});
  REQUIRE(records.size() == 2);
  const ValidationRecord& failed = records[0];
  CHECK(failed.method == "sph");
  CHECK(failed.failed());
  CHECK(failed.failure == "the SPH run went unstable at t = 0.73 s");
  CHECK(failed.run_key == "0badc0de0badc0de");
  CHECK(*failed.wall_time_s == 95.5);
  CHECK(*failed.legs == 2);
  CHECK(failed.case_id == "A_smooth");
  CHECK(failed.window_end_s == 10.0);
  CHECK(failed.metrics.empty());
  CHECK(failed.surface_x_m.empty());
  CHECK_FALSE(records[1].failed());
  CHECK(records[1].metric("sequent_depth")->value == 0.1286);
  // It reads back as failed; a finished record's text has no failure key.
  const ValidationRecord back = parse_record(record_text(failed), "A_smooth/sph-quick.toml");
  CHECK(back.failure == failed.failure);
  CHECK(record_text(back) == record_text(failed));
  CHECK_THAT(record_text(records[1]), !Catch::Contains("failure"));

  // A stage that failed and then finished: its stamp wins over a leftover sph.failed.
  write(dir / "sph.stamp", "0123012301230123");
  write(dir / "csv" / "metrics.csv", "quantity,unit,sph,vof,experiment,published_sph,smooth_theory,status\n"
                                     "sequent_depth,m,0.1331,0.1286,nan,nan,0.131781,predicted\n");
  records = records_from_case_dir(dir, {"2026-12-01", "cmd"});
  REQUIRE(records.size() == 2);
  CHECK_FALSE(records[0].failed());
  CHECK(records[0].run_key == "0123012301230123");

  // Both failed, nothing compared: the failed records alone.
  fs::remove(dir / "sph.stamp");
  fs::remove(dir / "vof.stamp");
  fs::remove_all(dir / "csv");
  write(dir / "vof.failed", "run_key = \"1111222233334444\"\nfailure = \"exit status 1: interFoam: floating point exception\"\n");
  records = records_from_case_dir(dir, {"2026-12-01", "cmd"});
  REQUIRE(records.size() == 2);
  CHECK(records[1].failure == "exit status 1: interFoam: floating point exception");
  CHECK_FALSE(records[1].wall_time_s);
  // A damaged or empty failure file is no record.
  write(dir / "sph.failed", "run_key = \"0badc0de0badc0de\"\n");
  write(dir / "vof.failed", "[[[");
  CHECK_THROWS_WITH(records_from_case_dir(dir, {}), Catch::Contains("no failed run"));
}

TEST_CASE("A failed run's record is in the targets and records tables, not in the numbers, and its case is not 'not run'",
          "[compare][record]") {
  const auto study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  ValidationRecord failed = sample_record("sph", 0.0);
  failed.study = study.name;
  failed.metrics.clear();
  failed.profiles.clear();
  failed.surface_x_m.clear();
  failed.surface_mean_m.clear();
  failed.failure = "the SPH run went unstable: |rho/rho0 - 1| = 0.52";
  failed.wall_time_s = 60.0;
  ValidationRecord vof = sample_record("vof", 0.113782);
  vof.study = study.name;
  const std::string md = validation_markdown({failed, vof}, "validation/records");
  INFO(md);
  CHECK_THAT(md, Catch::Contains("| A | SPH | quick | FAILED: the SPH run went unstable: \\|rho/rho0 - 1\\| = 0.52 |"));
  CHECK_THAT(md, Catch::Contains("| A | SPH | quick | `A/sph-quick.toml` |"));
  CHECK_THAT(md, !Catch::Contains("| A | SPH | quick | predicted |"));  // no row of numbers
  CHECK_THAT(md, !Catch::Contains("### SPH against VOF"));                // no pair to set side by side
  CHECK_THAT(md, Catch::Contains("| A | VOF | quick | predicted | 0.1138 |"));
  CHECK_THAT(headline_markdown({failed, vof}), Catch::Contains("| A | quick | failed / +9.4 % of lab | — / -2.98 |") &&
                                                 Catch::Contains("| — | failed | met (2) |"));
  // It ran: not listed as not run, and its partial wall time is no reference for the estimates.
  const std::string not_run = not_run_markdown(study, {failed, vof}, "quick");
  INFO(not_run);
  CHECK_THAT(not_run, !Catch::Contains("| A | SPH |"));
  CHECK_THAT(not_run, Catch::Contains("| A_smooth | SPH |"));
  CHECK_THAT(not_run, !Catch::Contains("A (SPH)"));
}
