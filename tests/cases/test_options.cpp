// The spec's option tables (cases/options.hpp): every name reads back to its value and every value to
// its name, the names quoted in messages are the table's, and the spec reader refuses an unknown name
// with exactly the table's names and reads every known one into its enum.
#include <catch2/catch.hpp>

#include <set>
#include <string>

#include "cases/options.hpp"
#include "cases/spec.hpp"
#include "cases/spec_reader.hpp"

using namespace hydrojump::cases;

namespace {

// A minimal stilling-basin study whose [sph] table sets `key = "value"`.
std::string study_with_sph(const std::string& key, const std::string& value) {
  return R"(
[study]
name = "mini"
[sph]
)" + key + " = \"" + value + R"("
[resolution.quick]
particle_spacing_m = 0.005
vof_cell_size_bed_m = 0.005
vof_cell_size_bulk_m = 0.01
[[case]]
id = "A"
kind = "stilling_basin"
[case.run]
end_time_s = 10.0
average_start_s = 6.0
[case.bed]
profile = "smooth"
[case.inflow]
depth_m = 0.0254
velocity_m_s = 2.0
[case.tailwater]
depth_m = 0.104
[case.domain]
upstream_length_m = 0.2
basin_length_m = 1.36
downstream_length_m = 0.2
air_height_m = 0.1
)";
}

template <class E>
void check_table() {
  std::set<std::string> names;
  std::set<int> values;
  for (const auto& v : OptionTable<E>::values) {
    CHECK(names.insert(std::string(v.name)).second);
    CHECK(values.insert(static_cast<int>(v.value)).second);
    CHECK(parse_option<E>(v.name) == v.value);
    CHECK(option_name(v.value) == v.name);
    CHECK(option_from_name<E>("key", v.name) == v.value);
  }
  CHECK_FALSE(parse_option<E>("no_such_option").has_value());
  CHECK_FALSE(parse_option<E>("").has_value());
  CHECK_THROWS_WITH(option_from_name<E>("sph.key", "no_such_option"),
                    "sph.key = \"no_such_option\" is not allowed: use " + allowed_option_names<E>());
}

// The spec reader, given [sph] key = <every name of E's table> and one unknown name.
template <class E>
void check_spec_key(const std::string& key, E SphSettings::*field) {
  for (const auto& v : OptionTable<E>::values) {
    INFO(key << " = " << v.name);
    try {
      const Study study = parse_study(study_with_sph(key, std::string(v.name)), "spec.toml", ".");
      CHECK(study.cases.at(0).sph.*field == v.value);
    } catch (const SpecError& e) {
      // Some combinations are refused for another reason (e.g. a tailgate with a level reference);
      // never for the name itself.
      CHECK_THAT(std::string(e.what()), !Catch::Contains("is not a known option"));
    }
  }
  std::string listed;
  for (const auto& v : OptionTable<E>::values) listed += (listed.empty() ? "\"" : ", \"") + std::string(v.name) + "\"";
  try {
    parse_study(study_with_sph(key, "no_such_option"), "spec.toml", ".");
    FAIL("sph." << key << " = \"no_such_option\" was accepted");
  } catch (const SpecError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains(key + " = \"no_such_option\" is not a known option: allowed values are " + listed));
  }
}

}  // namespace

TEST_CASE("options: every table's names and values are unique and read back", "[cases][options]") {
  check_table<KernelType>();
  check_table<Viscosity>();
  check_table<SpsWallDistance>();
  check_table<ViscousWallCondition>();
  check_table<BoundaryMethod>();
  check_table<DensityDiffusion>();
  check_table<TimeIntegrator>();
  check_table<InflowCondition>();
  check_table<OutflowCondition>();
  check_table<OutflowLevelReference>();
  check_table<ParticleShifting>();
  check_table<ShiftingCorrection>();
  check_table<TurbulenceModel>();
  check_table<TurbulenceStabilization>();
  check_table<MeshStrategy>();
  check_table<BedShape>();
  check_table<TailwaterControlMode>();
  check_table<TailwaterRule>();
  check_table<GateOpening>();
  check_table<SectionRole>();
}

TEST_CASE("options: messages quote the names as a list", "[cases][options]") {
  CHECK(allowed_option_names<Viscosity>() == "\"artificial\" or \"laminar_sps\"");
  CHECK(allowed_option_names<ShiftingCorrection>() == "\"none\", \"taylor\" or \"taylor_volume\"");
  CHECK(allowed_option_names<TurbulenceModel>() == "\"laminar\", \"kOmegaSST\", \"kEpsilon\" or \"RNGkEpsilon\"");
}

TEST_CASE("options: the spec reader reads every [sph] option's names from its table", "[cases][options]") {
  check_spec_key("kernel", &SphSettings::kernel);
  check_spec_key("viscosity", &SphSettings::viscosity);
  check_spec_key("boundary", &SphSettings::boundary);
  check_spec_key("density_diffusion", &SphSettings::density_diffusion);
  check_spec_key("time_integrator", &SphSettings::time_integrator);
  check_spec_key("inflow_condition", &SphSettings::inflow_condition);
  check_spec_key("outflow_condition", &SphSettings::outflow_condition);
  check_spec_key("outflow_level_reference", &SphSettings::outflow_level_reference);
  check_spec_key("particle_shifting", &SphSettings::particle_shifting);
}

TEST_CASE("options: a case's bed profile, tailwater control and rule are read from their tables", "[cases][options]") {
  const std::string base = study_with_sph("kernel", "wendland_c2");
  const Study smooth = parse_study(base, "spec.toml", ".");
  CHECK(smooth.cases.at(0).stilling_basin()->bed.profile == BedShape::smooth);
  CHECK(smooth.cases.at(0).stilling_basin()->control.mode == TailwaterControlMode::hold_toe);
  CHECK(smooth.cases.at(0).stilling_basin()->tailwater_rule == TailwaterRule::given);
  const auto rejection = [&](const std::string& from, const std::string& to) {
    std::string text = base;
    text.replace(text.find(from), from.size(), to);
    try {
      parse_study(text, "spec.toml", ".");
    } catch (const SpecError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(rejection("profile = \"smooth\"", "profile = \"wavy\""),
             Catch::Contains("profile = \"wavy\" is not a known option: allowed values are \"smooth\", \"sinusoidal\""));
  CHECK_THAT(rejection("profile = \"smooth\"\n", ""),
             Catch::Contains("profile") && Catch::Contains("is missing (required; one of \"smooth\", \"sinusoidal\")"));
  CHECK_THAT(rejection("depth_m = 0.104", "depth_m = 0.104\ncontrol = \"gate\""),
             Catch::Contains("allowed values are \"hold_toe\", \"fixed_depth\""));
  CHECK_THAT(rejection("depth_m = 0.104", "depth_m = 0.104\nrule = \"sequent\""),
             Catch::Contains("allowed values are \"given\", \"belanger\""));
}
