// The OpenFOAM case of a hydrojump case, as a script over its parts (case_parts.hpp): the mesh
// dictionaries, the physical properties, the initial fields, controlDict, the numerics and Allrun;
// and the files written from it.
#include "reference/case_writer.hpp"

#include <stdexcept>

#include "util/atomic_file.hpp"
#include "reference/case_parts.hpp"

namespace hydrojump::reference {

namespace detail {

void add_file(VofCase& vof, const std::string& path, const std::string& cls, const foam::Dictionary& d) {
  const auto slash = path.find('/');
  vof.headers[path] = foam::FileHeader{cls, path.substr(0, slash), path.substr(slash + 1)};
  vof.files[path] = d;
}

}  // namespace detail

std::optional<std::string> vof_unsupported_reason(const cases::Case& c) {
  if (const auto* dam = c.dam_break(); dam && dam->gate != cases::GateOpening::instant) {
    return "case \"" + c.id + "\": gate.type = \"" + std::string(cases::option_name(dam->gate)) +
           "\" cannot be modelled by the OpenFOAM reference (a moving gate needs a moving mesh, not "
           "available on this build): allowed \"instant\"";
  }
  if (!c.stilling_basin() && !c.dam_break() && !c.still_water()) {
    return "case \"" + c.id + "\": kind \"" + c.kind +
           "\" has no OpenFOAM reference (supported: stilling_basin, dam_break, still_water); the "
           "periodic single-phase Poiseuille channel is an SPH verification case";
  }
  return std::nullopt;
}

VofCase build_vof_case(const cases::Study& study, const cases::Case& c, const std::string& resolution) {
  const cases::Resolution& res = c.resolution(resolution);
  const cases::CaseGeometry geo = cases::make_geometry(c, study.fluid);
  if (const auto reason = vof_unsupported_reason(c)) throw std::invalid_argument(*reason);
  try {
    turbulence_fields(c.vof.turbulence_model);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("case \"" + c.id + "\": " + e.what());
  }

  VofCase vof;
  vof.case_id = c.id;
  vof.resolution = resolution;
  vof.mesh = plan_mesh(c, geo, res);
  const std::string provenance =
      "case \"" + c.id + "\" of study \"" + study.name + "\", resolution \"" + resolution + "\"";
  const detail::CaseInputs in{study, c, geo, vof.mesh, provenance, res.vof_cell_size_bed_m, res.vof_cell_size_bulk_m};
  detail::add_mesh_dictionaries(vof, in);
  const detail::FlowScales scales = detail::flow_scales(in);
  detail::add_physical_properties(vof, in);
  detail::add_initial_fields(vof, in, scales);
  detail::add_set_fields_dict(vof, in);
  detail::add_control_dict(vof, in, scales);
  detail::add_numerics(vof, in);
  vof.allrun = detail::allrun_script(vof, in);
  return vof;
}

void write_vof_files(const VofCase& vof, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  for (const auto& [path, dict] : vof.files) {
    util::write_file_atomically(dir / path, foam::format_file(vof.headers.at(path), dict));
  }
  util::write_file_atomically(dir / "Allrun", vof.allrun);
  std::filesystem::permissions(dir / "Allrun",
                               std::filesystem::perms::owner_exec | std::filesystem::perms::group_exec |
                                   std::filesystem::perms::others_exec,
                               std::filesystem::perm_options::add);
}

}  // namespace hydrojump::reference
