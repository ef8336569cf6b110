// The resolved case text: a case at one resolution, every setting after inheritance and the rules,
// written as the TOML the solvers read back (case.toml), and the measured data copied beside it.
#include <sstream>
#include <string>

#include "cases/spec.hpp"
#include "cases/spec_reader.hpp"
#include "util/atomic_file.hpp"
#include "util/fingerprint.hpp"
#include "util/number_text.hpp"
#include "cases/spec_table_reader.hpp"

namespace hydrojump::cases {
using spec_detail::toml_number;

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", ch);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

// Writes "key = value" lines of a flat TOML table.
class TomlWriter {
 public:
  void header(const std::string& h) { out_ << "\n" << h << "\n"; }
  void num(const std::string& k, double v) { out_ << k << " = " << toml_number(v) << "\n"; }
  void integer(const std::string& k, long v) { out_ << k << " = " << v << "\n"; }
  void str(const std::string& k, const std::string& v) { out_ << k << " = " << quoted(v) << "\n"; }
  // An option (cases/options.hpp) by its name.
  template <class E>
    requires std::is_enum_v<E>
  void str(const std::string& k, E v) { str(k, std::string(option_name(v))); }
  void opt(const std::string& k, const std::optional<double>& v) {
    if (v) num(k, *v);
  }
  void strings(const std::string& k, const std::vector<std::string>& v) {
    out_ << k << " = [";
    for (std::size_t i = 0; i < v.size(); ++i) out_ << (i ? ", " : "") << quoted(v[i]);
    out_ << "]\n";
  }
  void numbers(const std::string& k, const std::vector<double>& v) {
    out_ << k << " = [";
    for (std::size_t i = 0; i < v.size(); ++i) out_ << (i ? ", " : "") << toml_number(v[i]);
    out_ << "]\n";
  }
  void comment(const std::string& c) { out_ << "# " << c << "\n"; }
  std::string text() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

void write_sph(TomlWriter& w, const SphSettings& s) {
  w.str("kernel", s.kernel);
  w.str("viscosity", s.viscosity);
  // Only the parameters of the chosen models (read_sph rejects the others).
  if (s.viscosity == cases::Viscosity::artificial) {
    if (s.artificial_viscosity_nu_m2_s > 0.0) w.num("artificial_viscosity_nu_m2_s", s.artificial_viscosity_nu_m2_s);
    else w.num("artificial_viscosity_alpha", s.artificial_viscosity_alpha);
    w.num("artificial_viscosity_wall_factor", s.artificial_viscosity_wall_factor);
  } else {
    if (s.sps_mixing_length_m > 0.0) {
      if (s.sps_mixing_length_per_sequent_depth > 0.0)
        w.comment("from sps_mixing_length_per_sequent_depth = " + toml_number(s.sps_mixing_length_per_sequent_depth) +
                  " (l = c_l y2*)");
      w.num("sps_mixing_length_m", s.sps_mixing_length_m);
      w.str("sps_wall_distance", s.sps_wall_distance);
    } else {
      w.num("sps_smagorinsky_constant", s.sps_smagorinsky_constant);
    }
    w.num("sps_blin_constant", s.sps_blin_constant);
    w.str("viscous_wall_condition", s.viscous_wall_condition);
  }
  w.str("boundary", s.boundary);
  w.str("density_diffusion", s.density_diffusion);
  if (s.density_diffusion != cases::DensityDiffusion::none) w.num("density_diffusion_coefficient", s.density_diffusion_coefficient);
  if (s.sound_speed_m_s > 0.0) {
    w.num("sound_speed_m_s", s.sound_speed_m_s);
  } else {
    w.num("sound_speed_coefficient", s.sound_speed_coefficient);
    w.num("sound_speed_min_flow_ratio", s.sound_speed_min_flow_ratio);
  }
  w.num("cfl_number", s.cfl_number);
  w.num("coef_h", s.coef_h);
  w.str("time_integrator", s.time_integrator);
  if (s.time_integrator == cases::TimeIntegrator::verlet) w.integer("verlet_euler_interval", s.verlet_euler_interval);
  w.integer("boundary_layers", s.boundary_layers);
  w.integer("open_boundary_layers", s.open_boundary_layers);
  w.str("inflow_condition", s.inflow_condition);
  if (s.inflow_condition == cases::InflowCondition::piston) {
    w.num("sluice_opening_m", s.sluice_opening_m);
    w.num("reservoir_length_m", s.reservoir_length_m);
    w.num("piston_level_gain_per_s", s.piston_level_gain_per_s);
  }
  w.str("outflow_condition", s.outflow_condition);
  if (s.outflow_condition == cases::OutflowCondition::tailgate) w.num("tailgate_height_m", s.tailgate_height_m);
  w.str("outflow_level_reference", s.outflow_level_reference);
  if (s.outflow_level_reference == cases::OutflowLevelReference::downstream_section) w.num("outflow_level_time_s", s.outflow_level_time_s);
  w.str("particle_shifting", s.particle_shifting);
  if (s.particle_shifting != cases::ParticleShifting::none) {
    w.num("particle_shifting_coefficient", s.particle_shifting_coefficient);
    w.num("particle_shifting_surface_threshold", s.particle_shifting_surface_threshold);
    w.str("particle_shifting_correction", s.particle_shifting_correction);
  }
  w.num("max_density_variation", s.max_density_variation);
  w.num("checkpoint_interval_wall_s", s.checkpoint_interval_wall_s);
}

void write_vof(TomlWriter& w, const VofSettings& v) {
  w.str("turbulence_model", v.turbulence_model);
  w.str("turbulence_stabilization", v.turbulence_stabilization);
  w.num("max_courant", v.max_courant);
  w.num("max_alpha_courant", v.max_alpha_courant);
  w.num("max_time_step_s", v.max_time_step_s);
  w.str("mesh_strategy", v.mesh_strategy);
  w.num("surface_refinement_band_m", v.surface_refinement_band_m);
  if (v.tailwater_control_interval_s > 0.0) w.num("tailwater_control_interval_s", v.tailwater_control_interval_s);
}

}  // namespace

void write_resolved_case(const Study& study, const Case& c, const std::string& resolution,
                         const std::filesystem::path& out_file) {
  // The measured data travel with the case: copied beside it first (so the case file never names a
  // file that is not there) and named relative to it, so the run directory can be moved and its
  // text does not depend on where the spec was read from.
  if (const auto* d = c.dam_break(); d != nullptr && !d->measured_front_file.empty()) {
    const std::filesystem::path copy = out_file.parent_path() / kResolvedFrontFileName;
    std::error_code ec;
    if (!std::filesystem::equivalent(d->measured_front_file, copy, ec))
      util::write_file_atomically(copy, util::read_text_file(d->measured_front_file));
  }
  util::write_file_atomically(out_file, resolved_case_text(study, c, resolution));
}

std::string resolved_case_text(const Study& study, const Case& c, const std::string& resolution) {
  const Resolution& r = c.resolution(resolution);
  TomlWriter w;
  w.comment("Resolved by hydrojump from " + study.source_file.string() + ": case \"" + c.id +
            "\" at resolution \"" + resolution + "\", every default made explicit.");
  w.header("[study]");
  w.str("name", study.name);
  w.str("description", study.description);
  w.strings("citations", study.citations);
  w.header("[fluid]");
  w.num("density_kg_m3", study.fluid.density_kg_m3);
  w.num("kinematic_viscosity_m2_s", study.fluid.kinematic_viscosity_m2_s);
  w.num("gravity_m_s2", study.fluid.gravity_m_s2);
  w.header("[sph]");
  write_sph(w, c.sph);
  w.header("[vof]");
  write_vof(w, c.vof);
  w.header("[resolution." + r.name + "]");
  w.num("particle_spacing_m", r.particle_spacing_m);
  w.num("vof_cell_size_bed_m", r.vof_cell_size_bed_m);
  w.num("vof_cell_size_bulk_m", r.vof_cell_size_bulk_m);
  w.header("[[case]]");
  w.str("id", c.id);
  w.str("kind", c.kind);
  w.str("description", c.description);
  w.header("[case.run]");
  w.num("end_time_s", c.run.end_time_s);
  w.num("output_interval_s", c.run.output_interval_s);
  w.num("average_start_s", c.run.average_start_s);
  w.num("average_end_s", c.run.average_end_s);
  if (const auto* b = c.stilling_basin()) {
    w.header("[case.bed]");
    w.str("profile", b->bed.profile);
    if (b->bed.profile == cases::BedShape::sinusoidal) {
      w.num("wavelength_m", b->bed.wavelength_m);
      w.num("height_m", b->bed.height_m);
      w.num("reach_start_m", b->bed.reach_start_m);
      w.num("reach_end_m", b->bed.reach_end_m);
    }
    w.header("[case.inflow]");
    w.num("depth_m", b->inflow_depth_m);
    w.num("velocity_m_s", b->inflow_velocity_m_s);
    w.opt("discharge_m2_s", b->stated_discharge_m2_s);
    w.opt("froude", b->stated_froude);
    w.header("[case.tailwater]");
    if (b->tailwater_rule == TailwaterRule::belanger) w.comment("from rule = \"belanger\" (y2* of the inflow)");
    w.num("depth_m", b->tailwater_depth_m);
    w.str("control", b->control.mode);
    if (b->control.holds_toe()) {
      w.num("volume_hold_time_s", b->control.volume_hold_time_s);
      w.num("toe_hold_time_s", b->control.toe_hold_time_s);
      w.num("toe_hold_gain", b->control.toe_hold_gain);
    }
    w.header("[case.domain]");
    w.num("upstream_length_m", b->upstream_length_m);
    w.num("basin_length_m", b->basin_length_m);
    w.num("downstream_length_m", b->downstream_length_m);
    w.num("air_height_m", b->air_height_m);
    w.opt("initial_toe_x_m", b->initial_toe_x_m);
    const auto& m = b->measured;
    w.header("[case.measured]");
    w.opt("sequent_depth_m", m.sequent_depth_m);
    w.opt("jump_length_m", m.jump_length_m);
    w.opt("roller_length_m", m.roller_length_m);
    w.opt("eta_percent", m.eta_percent);
    w.opt("eta_smooth_percent", m.eta_smooth_percent);
    w.opt("published_sph_eta_percent", m.published_sph_eta_percent);
    if (!m.source.empty()) w.str("source", m.source);
    if (!m.note.empty()) w.str("note", m.note);
  } else if (const auto* d = c.dam_break()) {
    w.header("[case.column]");
    w.num("width_m", d->column_width_m);
    w.num("height_m", d->column_height_m);
    w.header("[case.tank]");
    w.num("length_m", d->tank_length_m);
    w.num("height_m", d->tank_height_m);
    w.header("[case.gate]");
    w.str("type", d->gate);
    if (d->gate == GateOpening::lifted) w.num("lift_speed_m_s", d->gate_lift_speed_m_s);
    if (!d->gauges_x_m.empty()) {
      w.header("[case.gauges]");
      w.numbers("x_m", d->gauges_x_m);
    }
    if (!d->measured_front_file.empty()) {
      w.header("[case.measured]");
      w.str("front_file", kResolvedFrontFileName);  // the copy write_resolved_case puts beside it
    }
  } else if (const auto* s = c.still_water()) {
    w.header("[case.tank]");
    w.num("length_m", s->tank_length_m);
    w.num("height_m", s->tank_height_m);
    w.header("[case.water]");
    w.num("depth_m", s->water_depth_m);
  } else if (const auto* p = c.poiseuille()) {
    w.header("[case.channel]");
    w.num("width_m", p->channel_width_m);
    w.num("length_m", p->channel_length_m);
    w.num("body_force_m_s2", p->body_force_m_s2);
  }
  for (const auto& s : c.sections) {
    w.header("[[case.sections]]");
    w.str("name", s.name);
    w.num("x_m", s.x_m);
    w.str("role", s.role);
  }
  return w.text();
}

}  // namespace hydrojump::cases
