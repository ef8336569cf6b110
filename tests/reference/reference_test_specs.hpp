// Small inline study specs shared by the reference tests (so they do not depend on cases/ead2002.toml).
#pragma once

#include <string>

#include "cases/spec_reader.hpp"

namespace hydrojump::reference::testing {

// A short corrugated stilling basin (4 wavelengths of S = 68 mm, T = 13 mm; y1 = 25.4 mm, U1 = 2 m/s,
// tailwater 60 mm held at the outlet: control = "fixed_depth") with three explicit sections.
// `extra_vof` is appended to the [vof] table.
inline std::string basin_spec(const std::string& extra_vof = "", double end_time_s = 0.02,
                              double output_interval_s = 0.01, const std::string& profile = "sinusoidal",
                              double cell_bed_m = 0.005, double cell_bulk_m = 0.01,
                              double air_height_m = 0.04) {
  std::string bed = profile == "sinusoidal"
                        ? "profile = \"sinusoidal\"\nwavelength_m = 0.068\nheight_m = 0.013\n"
                        : "profile = \"smooth\"\n";
  return "[study]\nname = \"reference_test\"\ndescription = \"test\"\n"
         "[fluid]\ndensity_kg_m3 = 1000.0\nkinematic_viscosity_m2_s = 1.0e-6\ngravity_m_s2 = 9.81\n"
         "[vof]\nmax_courant = 0.7\nmax_alpha_courant = 0.6\nmax_time_step_s = 0.002\n" + extra_vof +
         "\n[resolution.quick]\nparticle_spacing_m = 0.005\nvof_cell_size_bed_m = " + std::to_string(cell_bed_m) +
         "\nvof_cell_size_bulk_m = " + std::to_string(cell_bulk_m) +
         "\n[[case]]\nid = \"basin\"\nkind = \"stilling_basin\"\ndescription = \"short corrugated basin\"\n"
         "[case.run]\nend_time_s = " + std::to_string(end_time_s) +
         "\noutput_interval_s = " + std::to_string(output_interval_s) +
         "\naverage_start_s = 0.0\naverage_end_s = " + std::to_string(end_time_s) + "\n"
         "[case.bed]\n" + bed +
         "[case.inflow]\ndepth_m = 0.0254\nvelocity_m_s = 2.0\n"
         "[case.tailwater]\ndepth_m = 0.06\ncontrol = \"fixed_depth\"\n"
         "[case.domain]\nupstream_length_m = 0.1\nbasin_length_m = 0.272\ndownstream_length_m = 0.1\n"
         "air_height_m = " + std::to_string(air_height_m) + "\n"
         "[[case.sections]]\nname = \"up\"\nx_m = 0.05\nrole = \"upstream\"\n"
         "[[case.sections]]\nname = \"mid\"\nx_m = 0.271\n"
         "[[case.sections]]\nname = \"down\"\nx_m = 0.42\nrole = \"downstream\"\n";
}

// `spec` (a basin_spec) under [case.tailwater] control = "hold_toe", with `extra_tailwater` (e.g.
// toe_hold_time_s) added to that table.
inline std::string with_hold_toe(std::string spec, const std::string& extra_tailwater = "") {
  const std::string fixed = "control = \"fixed_depth\"\n";
  spec.replace(spec.find(fixed), fixed.size(), "control = \"hold_toe\"\n" + extra_tailwater);
  return spec;
}

// basin_spec on a smooth bed, to 0.02 s with outputs every 0.01 s, under the "hold_toe" tailwater
// control with a leg per output and the volume held over 0.02 s; `extra_tailwater` adds
// [case.tailwater] keys (e.g. toe_hold_time_s).
inline std::string tiny_hold_toe_spec(const std::string& extra_tailwater = "") {
  return with_hold_toe(basin_spec("tailwater_control_interval_s = 0.01\n", 0.02, 0.01, "smooth"),
                       "volume_hold_time_s = 0.02\n" + extra_tailwater + "\n");
}

// A small dam break: column 0.1 m x 0.2 m in a tank 0.4 m x 0.3 m, cells of 1 cm, two gauges.
inline std::string dam_break_spec(const std::string& gate = "type = \"instant\"") {
  return "[study]\nname = \"reference_dam\"\ndescription = \"test\"\n"
         "[fluid]\ndensity_kg_m3 = 1000.0\nkinematic_viscosity_m2_s = 1.0e-6\ngravity_m_s2 = 9.81\n"
         "[vof]\nturbulence_model = \"laminar\"\n"
         "[resolution.quick]\nparticle_spacing_m = 0.01\nvof_cell_size_bed_m = 0.01\nvof_cell_size_bulk_m = 0.02\n"
         "[[case]]\nid = \"dam\"\nkind = \"dam_break\"\ndescription = \"small dam break\"\n"
         "[case.run]\nend_time_s = 0.02\noutput_interval_s = 0.01\naverage_start_s = 0.0\naverage_end_s = 0.02\n"
         "[case.column]\nwidth_m = 0.1\nheight_m = 0.2\n"
         "[case.tank]\nlength_m = 0.4\nheight_m = 0.3\n"
         "[case.gate]\n" + gate + "\n"
         "[case.gauges]\nx_m = [0.05, 0.3]\n";
}

inline cases::Study parse(const std::string& text) {
  return cases::parse_study(text, "<reference test>", std::filesystem::temp_directory_path());
}

}  // namespace hydrojump::reference::testing
