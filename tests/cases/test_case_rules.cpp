// The rules that give a stilling basin's case-dependent settings from its own inputs
// (cases/case_rules.hpp), against hand-computed values, and how the reader applies them: one model and
// one run rule for every case of a study.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "cases/case_rules.hpp"
#include "cases/spec_reader.hpp"
#include "tests/temp_dir.hpp"

using namespace hydrojump::cases;

namespace {

const std::string source_dir = HYDROJUMP_SOURCE_DIR;

// Run A's inflow and domain (Ead & Rajaratnam 2002): y1 = 25.4 mm, U1 = 2.00 m/s, L = 1.76 m.
StillingBasinCase run_a_basin() {
  StillingBasinCase b;
  b.inflow_depth_m = 0.0254;
  b.inflow_velocity_m_s = 2.0;
  b.tailwater_depth_m = 0.104;
  b.upstream_length_m = 0.2;
  b.basin_length_m = 1.36;
  b.downstream_length_m = 0.2;
  return b;
}

// A one-basin study with the given study-level tables, the case's [case.run] optional.
std::string basin_study(const std::string& study_tables, const std::string& case_tables) {
  return "[study]\nname = \"rules\"\n" + study_tables +
         "\n[resolution.quick]\nparticle_spacing_m = 0.005\nvof_cell_size_bed_m = 0.005\nvof_cell_size_bulk_m = 0.01\n"
         "\n[[case]]\nid = \"A\"\nkind = \"stilling_basin\"\n" + case_tables +
         "[case.bed]\nprofile = \"smooth\"\n[case.inflow]\ndepth_m = 0.0254\nvelocity_m_s = 2.0\n"
         "[case.tailwater]\ndepth_m = 0.104\n[case.domain]\nupstream_length_m = 0.2\nbasin_length_m = 1.36\n"
         "downstream_length_m = 0.2\nair_height_m = 0.1\n";
}

std::string rejection(const std::string& text) {
  try {
    parse_study(text, "rules.toml", ".");
  } catch (const SpecError& e) {
    return e.what();
  }
  FAIL("the spec was accepted");
  return {};
}

const std::string laminar_rule = "[sph]\nviscosity = \"laminar_sps\"\nsps_mixing_length_per_sequent_depth = 0.1\n";
const std::string explicit_run = "[case.run]\nend_time_s = 4.0\naverage_start_s = 2.0\n";

}  // namespace

// Fr1 = 2 / sqrt(9.81 * 0.0254) = 4.0066; y2* = 0.0254 (sqrt(1 + 8 Fr1^2) - 1) / 2 = 0.13178 m (by hand).
TEST_CASE("The mixing-length rule gives l = c_l y2* from the inflow alone", "[cases][rules]") {
  const auto b = run_a_basin();
  CHECK(mixing_length_from_sequent_depth(0.1, b, 9.81) == Approx(0.013178).epsilon(1e-3));
  CHECK(mixing_length_from_sequent_depth(0.2, b, 9.81) == Approx(0.026356).epsilon(1e-3));
  // The tailwater (the measured y2 of a corrugated run) does not enter.
  auto other = b;
  other.tailwater_depth_m = 0.3;
  CHECK(mixing_length_from_sequent_depth(0.1, other, 9.81) == mixing_length_from_sequent_depth(0.1, b, 9.81));
}

// T_s = 2 L / sqrt(g y): 2 / sqrt(9.81 * 0.1) = 2.01928 s; run A: 3.52 / sqrt(9.81 * 0.13178) = 3.0959 s.
TEST_CASE("The run rule counts sloshing periods of the whole domain at Belanger's depth", "[cases][rules]") {
  CHECK(sloshing_period_s(1.0, 0.1, 9.81) == Approx(2.01928).epsilon(1e-5));
  RunRule rule;  // 2 periods of start-up, 1 of window, outputs every 0.1 s
  const RunSettings run = run_from_sloshing_periods(rule, run_a_basin(), 9.81);
  CHECK(run.output_interval_s == 0.1);
  CHECK(run.average_start_s == Approx(6.2));  // 6.19 s rounded up to an output
  CHECK(run.end_time_s == Approx(9.3));       // + 3.10 s
  CHECK(run.average_end_s == run.end_time_s);
  rule.start_up_sloshing_periods = 3.0;
  rule.window_sloshing_periods = 0.5;
  rule.output_interval_s = 0.5;
  const RunSettings longer = run_from_sloshing_periods(rule, run_a_basin(), 9.81);
  CHECK(longer.average_start_s == Approx(9.5));  // 9.29 s up to a whole 0.5 s
  CHECK(longer.end_time_s == Approx(11.5));      // + 1.55 s up to 2 outputs
}

TEST_CASE("A study-level run rule sets the run of every basin without its own run table and a case's own run wins", "[cases][rules]") {
  const Study s = parse_study(basin_study("[run]\nstart_up_sloshing_periods = 2\nwindow_sloshing_periods = 1\n", ""),
                              "rules.toml", ".");
  REQUIRE(s.run_rule);
  CHECK(s.cases[0].run.average_start_s == Approx(6.2));
  CHECK(s.cases[0].run.end_time_s == Approx(9.3));
  const Study own = parse_study(basin_study("[run]\n", explicit_run), "rules.toml", ".");
  CHECK(own.cases[0].run.end_time_s == 4.0);
  CHECK(own.cases[0].run.average_start_s == 2.0);
  // Without a rule, [case.run] is required and named.
  CHECK_THAT(rejection(basin_study("", "")), Catch::Contains("case \"A\": run is missing: the table [run] is required"));
  CHECK_THAT(rejection(basin_study("[run]\nstart_up_sloshing_periods = 0.2\n", "")),
             Catch::Contains("rules.toml:4: run.start_up_sloshing_periods = 0.2 is out of range"));
  CHECK_THAT(rejection(basin_study("[run]\nwindow_sloshing_periods = 0\n", "")),
             Catch::Contains("run.window_sloshing_periods = 0 is out of range"));
  CHECK_THAT(rejection(basin_study("[run]\nend_time_s = 10\n", "")), Catch::Contains("run.end_time_s"));
}

// T_s = 2 (1.76 m) / sqrt(9.81 * 0.13178) = 3.0959 s, T_x = 0.65 T_s = 2.0123 s (by hand).
TEST_CASE("The toe-control rule gives T_x = c_x T_s per basin and a case's own toe_hold_time_s wins", "[cases][rules]") {
  CHECK(toe_hold_time_from_sloshing_periods(0.65, run_a_basin(), 9.81) == Approx(2.0123).epsilon(1e-4));
  const Study s = parse_study(basin_study("[run]\ntoe_hold_sloshing_periods = 0.65\n", ""), "rules.toml", ".");
  CHECK(s.cases[0].stilling_basin()->control.toe_hold_time_s == Approx(2.0123).epsilon(1e-4));
  // The resolved case carries the number, and reads back the same (the rule no longer applies to it).
  const Study again = parse_study(resolved_case_text(s, s.cases[0], "quick"), "case.toml", ".");
  CHECK(again.cases[0].stilling_basin()->control.toe_hold_time_s == Approx(2.0123).epsilon(1e-4));
  std::string own_text = basin_study("[run]\ntoe_hold_sloshing_periods = 0.65\n", "");
  own_text.replace(own_text.find("depth_m = 0.104"), 15, "depth_m = 0.104\ntoe_hold_time_s = 4.0");
  CHECK(parse_study(own_text, "rules.toml", ".").cases[0].stilling_basin()->control.toe_hold_time_s == 4.0);
  // Without the rule: the key's default.
  CHECK(parse_study(basin_study("[run]\n", ""), "rules.toml", ".").cases[0].stilling_basin()->control.toe_hold_time_s == 5.0);
  CHECK_THAT(rejection(basin_study("[run]\ntoe_hold_sloshing_periods = 0\n", "")),
             Catch::Contains("run.toe_hold_sloshing_periods = 0 is out of range"));
  // A derived T_x beyond the key's range, (0, 1000] s: a 10.4-m domain, T_s = 18.29 s, 99 periods: 1811 s.
  std::string long_basin = basin_study("[run]\ntoe_hold_sloshing_periods = 99\n", "");
  long_basin.replace(long_basin.find("basin_length_m = 1.36"), 21, "basin_length_m = 10.0");
  CHECK_THAT(rejection(long_basin), Catch::Contains("case \"A\"") && Catch::Contains("tailwater.toe_hold_time_s = 1811") &&
                                        Catch::Contains("is out of range: must be > 0 and <= 1000 s"));
}

TEST_CASE("The run rule is refused for a case that has no sloshing period", "[cases][rules]") {
  const std::string spec = "[study]\nname = \"rules\"\n[run]\n"
                           "[resolution.quick]\nparticle_spacing_m = 0.001\nvof_cell_size_bed_m = 0.001\nvof_cell_size_bulk_m = 0.001\n"
                           "[[case]]\nid = \"p\"\nkind = \"poiseuille\"\n"
                           "[case.channel]\nwidth_m = 0.02\nlength_m = 0.01\nbody_force_m_s2 = 0.02\n";
  CHECK_THAT(rejection(spec), Catch::Contains("case \"p\": run is missing: the study's [run] rule sets the run of "
                                              "stilling basins only"));
}

TEST_CASE("The mixing-length rule resolves per case, and a case's length in metres replaces it", "[cases][rules]") {
  const Study s = parse_study(basin_study(laminar_rule, explicit_run), "rules.toml", ".");
  CHECK(s.cases[0].sph.sps_mixing_length_m == Approx(0.013178).epsilon(1e-3));
  // The resolved case carries the number, and reloads to the same length.
  const hydrojump::testing::TempDir tmp("case_rules");
  write_resolved_case(s, s.cases[0], "quick", tmp.path() / "case.toml");
  const Study again = load_study(tmp.path() / "case.toml");
  CHECK(again.cases[0].sph.sps_mixing_length_m == Approx(s.cases[0].sph.sps_mixing_length_m).epsilon(1e-12));
  // A case's l in metres drops the inherited rule.
  const Study own = parse_study(basin_study(laminar_rule, explicit_run + "[case.sph]\nsps_mixing_length_m = 0.02\n"),
                                "rules.toml", ".");
  CHECK(own.cases[0].sph.sps_mixing_length_m == 0.02);
  CHECK(own.cases[0].sph.sps_mixing_length_per_sequent_depth == 0.0);
  // Refused: both in one table, out of range, with another viscosity, with C_s.
  CHECK_THAT(rejection(basin_study(laminar_rule + "sps_mixing_length_m = 0.02\n", explicit_run)),
             Catch::Contains("sph.sps_mixing_length_per_sequent_depth and sps_mixing_length_m are both given"));
  CHECK_THAT(rejection(basin_study("[sph]\nviscosity = \"laminar_sps\"\nsps_mixing_length_per_sequent_depth = 1.5\n", explicit_run)),
             Catch::Contains("sph.sps_mixing_length_per_sequent_depth = 1.5 is out of range"));
  CHECK_THAT(rejection(basin_study("[sph]\nsps_mixing_length_per_sequent_depth = 0.1\n", explicit_run)),
             Catch::Contains("sph.sps_mixing_length_per_sequent_depth is only used with viscosity = \"laminar_sps\""));
  CHECK_THAT(rejection(basin_study(laminar_rule + "sps_smagorinsky_constant = 0.2\n", explicit_run)),
             Catch::Contains("and sps_smagorinsky_constant are both given"));
}

TEST_CASE("The mixing-length rule is refused for a case that has no sequent depth", "[cases][rules]") {
  const std::string spec = "[study]\nname = \"rules\"\n" + laminar_rule +
                           "[resolution.quick]\nparticle_spacing_m = 0.001\nvof_cell_size_bed_m = 0.001\nvof_cell_size_bulk_m = 0.001\n"
                           "[[case]]\nid = \"p\"\nkind = \"poiseuille\"\n[case.run]\nend_time_s = 1.0\n"
                           "[case.channel]\nwidth_m = 0.02\nlength_m = 0.01\nbody_force_m_s2 = 0.02\n";
  CHECK_THAT(rejection(spec), Catch::Contains("case \"p\": sph inherits sps_mixing_length_per_sequent_depth = 0.1"));
}

// The reference study sets one model per method: no case has its own [case.sph], [case.vof] or [case.run],
// and every case's settings are the study's after the rules.
TEST_CASE("The reference study has one model per method and one run rule", "[cases][rules]") {
  std::ifstream in(source_dir + "/cases/ead2002.toml");
  std::stringstream text;
  text << in.rdbuf();
  for (const char* table : {"\n[case.sph]", "\n[case.vof]", "\n[case.run]"}) {
    INFO(table);
    CHECK(text.str().find(table) == std::string::npos);  // no such table header
  }
  const Study s = load_study(source_dir + "/cases/ead2002.toml");
  REQUIRE(s.run_rule);
  const auto& first = s.cases.front();
  for (const auto& c : s.cases) {
    INFO(c.id);
    const auto* b = c.stilling_basin();
    REQUIRE(b);
    CHECK(c.sph.viscosity == first.sph.viscosity);
    CHECK(c.sph.viscous_wall_condition == first.sph.viscous_wall_condition);
    CHECK(c.sph.max_density_variation == first.sph.max_density_variation);
    CHECK(c.sph.sps_mixing_length_m ==
          Approx(mixing_length_from_sequent_depth(c.sph.sps_mixing_length_per_sequent_depth, *b, 9.81)));
    CHECK(c.vof.turbulence_model == first.vof.turbulence_model);
    CHECK(c.vof.turbulence_stabilization == first.vof.turbulence_stabilization);
    const RunSettings rule = run_from_sloshing_periods(*s.run_rule, *b, 9.81);
    CHECK(c.run.average_start_s == rule.average_start_s);
    CHECK(c.run.end_time_s == rule.end_time_s);
    CHECK_FALSE(b->initial_toe_x_m);
    CHECK(b->control.holds_toe());
  }
}
