// system/controlDict of a generated case, with its function objects (written every output_interval_s
// of the spec):
//   sections          `sets`: alpha.water and U along a vertical line at each section (raw text); for
//                     a dam break also `floor`, alpha.water half a cell above the floor (surge front)
//   discharge_<name>  `surfaceFieldValue`: sum of the water flux alphaPhi0.water (and phi) over the
//                     grid faces nearest to x_section (faceZone "section_<name>", made by
//                     system/topoSetDict.sections); divided by the spanwise thickness (one cell,
//                     MeshPlan::thickness_m) it is the water discharge q in m^2/s
//   discharge_inlet/_outlet  the same on the inlet and outlet patches
//   discharge_atmosphere     the same on the top (water leaving the domain there is lost to the basin)
//   water_volume      `volFieldValue`: the water volume every time step (hold_toe only)
//   freeSurface       `surfaces`: the alpha.water = 0.5 isoSurface (VTK)
//   average           `fieldAverage` of U and alpha.water over the averaging window (stilling basins)
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "reference/case_parts.hpp"
#include "reference/tailwater_control.hpp"

namespace hydrojump::reference::detail {

namespace {

using foam::Dictionary;
using foam::Value;

// A heuristic value (not from the spec) rounded to 3 significant digits for readability.
// Through its decimal text, so that the double is the one nearest to the 3-digit decimal (255 * 1e-6
// is 0.00025499999999999996, which the dictionary then printed).
double round_significant(double x) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  std::ostringstream text;
  text << std::setprecision(3) << x;
  return std::stod(text.str());
}

Dictionary output_control(double interval) {
  Dictionary d;
  d.set("writeControl", foam::word("adjustableRunTime"));
  d.set("writeInterval", interval);
  return d;
}

void merge(Dictionary& into, const Dictionary& from) {
  for (const std::string& k : from.keys()) into.set(k, from.at(k));
}

Value libs(const std::string& lib) { return foam::list({foam::string(lib)}); }

// The top-level entries: times, output, and the time step limits of [vof]. The first time step is
// 0.1 maxCo h / U (then adjusted by interFoam).
Dictionary control_entries(const CaseInputs& in, const FlowScales& s) {
  const cases::Case& c = in.c;
  const bool hold_toe = c.holds_toe();
  Dictionary cd;
  cd.directive("// " + in.provenance);
  cd.directive("// SIGUSR2 (12) makes interFoam write the current time and stop (used by `hydrojump vof` on Ctrl-C).");
  cd.subdict("OptimisationSwitches").set("stopAtWriteNowSignal", 12);
  cd.set("application", foam::word("interFoam"));
  cd.set("startFrom", foam::word("latestTime"));
  cd.set("startTime", 0);
  cd.set("stopAt", foam::word("endTime"));
  cd.directive("// endTime = run.end_time_s; writeInterval = run.output_interval_s");
  cd.set("endTime", c.run.end_time_s);
  cd.directive("// first time step: 0.1 maxCo h / U (then adjusted by interFoam)");
  cd.set("deltaT", std::min(c.vof.max_time_step_s,
                            round_significant(0.1 * c.vof.max_courant * in.cell_size_bed_m / s.u_ref_m_s)));
  cd.set("writeControl", foam::word("adjustable"));
  cd.set("writeInterval", c.run.output_interval_s);
  cd.set("purgeWrite", 0);
  cd.set("writeFormat", foam::word("ascii"));
  cd.set("writePrecision", 8);
  if (hold_toe) {
    cd.directive("// uncompressed: tailwater.control = \"hold_toe\" rewrites the outlet's Umean in the latest U "
                 "between legs (reference/tailwater_control.hpp)");
  }
  cd.set("writeCompression", foam::on_off(!hold_toe));
  cd.set("timeFormat", foam::word("general"));
  cd.set("timePrecision", 8);
  cd.set("runTimeModifiable", foam::yes_no(true));
  cd.directive("// maxCo = vof.max_courant; maxAlphaCo = vof.max_alpha_courant; maxDeltaT = vof.max_time_step_s");
  cd.set("adjustTimeStep", foam::yes_no(true));
  cd.set("maxCo", c.vof.max_courant);
  cd.set("maxAlphaCo", c.vof.max_alpha_courant);
  cd.set("maxDeltaT", c.vof.max_time_step_s);
  return cd;
}

// A straight sampling line from (x0, z0) to (x1, z1) along `axis`, two points per cell of size h over
// its length (at least 10).
Value uniform_line(const std::string& name, const char* axis, double x0, double z0, double x1, double z1,
                   double length_m, double h) {
  Dictionary line;
  line.set("type", foam::word("uniform"));
  line.set("axis", foam::word(axis));
  line.set("start", foam::vector(x0, z0, 0));
  line.set("end", foam::vector(x1, z1, 0));
  line.set("nPoints", std::max(10, static_cast<int>(std::ceil(2.0 * length_m / h)) + 1));
  return foam::named_dict(name, line);
}

// The `sections` function object: vertical lines at the sections, from the bed (inside the lowest
// fluid cell of the staircase) to the top of the domain, and a dam break's floor line along x half a
// cell above the floor. Nothing when there is no line.
std::optional<Dictionary> sections_function(const CaseInputs& in) {
  const cases::CaseGeometry& geo = in.geo;
  const double h = in.cell_size_bed_m;
  const bool dam = in.c.dam_break() != nullptr;
  std::vector<Value> sets;
  for (const cases::Section& s : geo.sections) {
    double zb = geo.bed.elevation(s.x_m);
    for (const RemovedColumns& r : in.plan.removed) {
      if (s.x_m >= r.x_begin_m && s.x_m <= r.x_end_m) zb = std::max(zb, r.z_top_m);
    }
    zb += 0.01 * h;  // inside the lowest fluid cell of the staircase
    const double top = geo.z_max_m - 0.01 * h;
    sets.push_back(uniform_line(s.name, "y", s.x_m, zb, s.x_m, top, top - zb, h));
  }
  if (dam) {
    const double z = 0.5 * in.plan.z_bands.front().end_m / in.plan.z_bands.front().cells;
    sets.push_back(
        uniform_line("floor", "x", geo.x_min_m + 1e-6, z, geo.x_max_m - 1e-6, z, geo.x_max_m - geo.x_min_m, h));
  }
  if (sets.empty()) return std::nullopt;
  Dictionary fo;
  fo.directive(std::string("// vertical lines at the spec's sections (x_m), bed to top: alpha.water and U") +
               (dam ? "; the floor line of a dam break" : ""));
  fo.set("type", foam::word("sets"));
  fo.set("libs", libs("libsampling.so"));
  merge(fo, output_control(in.c.run.output_interval_s));
  fo.set("interpolationScheme", foam::word("cellPoint"));
  fo.set("setFormat", foam::word("raw"));
  fo.set("fields", foam::list({foam::word("alpha.water"), foam::word("U")}));
  fo.set("sets", foam::list(sets));
  return fo;
}

// Water discharge through a face zone or patch: the sum of the face fluxes alphaPhi0.water over its
// faces, divided by the spanwise thickness:  q = sum(alphaPhi0.water) / thickness  (m^2/s).
Dictionary discharge_function(const CaseInputs& in, const std::string& region_type, const std::string& name) {
  Dictionary fo;
  fo.directive("// sum of alphaPhi0.water (m^3/s) / thickness " + n(in.plan.thickness_m) +
               " m = water discharge q (m^2/s)");
  fo.set("type", foam::word("surfaceFieldValue"));
  fo.set("libs", libs("libfieldFunctionObjects.so"));
  merge(fo, output_control(in.c.run.output_interval_s));
  fo.set("log", foam::word("false"));
  fo.set("writeFields", foam::word("false"));
  fo.set("regionType", foam::word(region_type));
  fo.set("name", foam::word(name));
  fo.set("operation", foam::word("sum"));
  fo.set("fields", foam::list({foam::word("alphaPhi0.water"), foam::word("phi")}));
  return fo;
}

// The water volume V = integral of alpha.water (m^3) every time step, for the tailwater control.
Dictionary water_volume_function_object(const CaseInputs& in) {
  Dictionary fo;
  fo.directive("// the water volume (m^3) every time step, / thickness " + n(in.plan.thickness_m) +
               " m = V (m^2) of the tailwater control");
  fo.set("type", foam::word("volFieldValue"));
  fo.set("libs", libs("libfieldFunctionObjects.so"));
  // every time step (writeInterval's default, 1: an entry here would be rewritten by a leg's controlDict
  // when the output interval is 1 s)
  fo.set("writeControl", foam::word("timeStep"));
  fo.set("log", foam::word("false"));
  fo.set("writeFields", foam::word("false"));
  fo.set("regionType", foam::word("all"));
  fo.set("operation", foam::word("volIntegrate"));
  fo.set("fields", foam::list({foam::word("alpha.water")}));
  return fo;
}

// The alpha.water = 0.5 iso-surface (VTK): the free surface, also the tailwater control's toe.
Dictionary free_surface_function_object(const CaseInputs& in) {
  Dictionary iso;
  iso.set("type", foam::word("isoSurface"));
  iso.set("isoField", foam::word("alpha.water"));
  iso.set("isoValue", 0.5);
  iso.set("interpolate", foam::word("true"));
  Dictionary fo;
  fo.set("type", foam::word("surfaces"));
  fo.set("libs", libs("libsampling.so"));
  merge(fo, output_control(in.c.run.output_interval_s));
  fo.set("surfaceFormat", foam::word("vtk"));
  fo.set("interpolationScheme", foam::word("cellPoint"));
  fo.set("fields", foam::list({foam::word("U")}));
  fo.set("surfaces", foam::list({foam::named_dict("alpha_0.5", iso)}));
  return fo;
}

// The time averages of U and alpha.water over [run.average_start_s, run.average_end_s].
Dictionary average_function(const cases::Case& c) {
  Dictionary fo;
  fo.directive("// averaging window = [run.average_start_s, run.average_end_s]");
  fo.set("type", foam::word("fieldAverage"));
  fo.set("libs", libs("libfieldFunctionObjects.so"));
  fo.set("timeStart", c.run.average_start_s);
  fo.set("timeEnd", c.run.average_end_s > 0.0 ? c.run.average_end_s : c.run.end_time_s);
  fo.set("writeControl", foam::word("writeTime"));
  Dictionary mean;
  mean.set("mean", foam::on_off(true));
  mean.set("prime2Mean", foam::on_off(false));
  mean.set("base", foam::word("time"));
  fo.set("fields", foam::list({foam::named_dict("U", mean), foam::named_dict("alpha.water", mean)}));
  return fo;
}

// The `functions` dictionary, in the order of the table at the top of this file.
Dictionary function_objects(const CaseInputs& in) {
  const bool basin = in.c.stilling_basin() != nullptr;
  Dictionary functions;
  if (const auto sections = sections_function(in)) functions.set("sections", *sections);
  if (basin) {
    for (const cases::Section& s : in.geo.sections) {
      functions.set("discharge_" + s.name, discharge_function(in, "faceZone", "section_" + s.name));
    }
    functions.set("discharge_inlet", discharge_function(in, "patch", "inlet"));
    functions.set("discharge_outlet", discharge_function(in, "patch", "outlet"));
    // Water thrown out through the top is lost to the basin: `hydrojump compare` reports it.
    functions.set("discharge_atmosphere", discharge_function(in, "patch", "atmosphere"));
  }
  if (in.c.holds_toe()) functions.set(water_volume_function, water_volume_function_object(in));
  functions.set(free_surface_function, free_surface_function_object(in));
  if (basin) functions.set("average", average_function(in.c));
  return functions;
}

}  // namespace

void add_control_dict(VofCase& vof, const CaseInputs& in, const FlowScales& scales) {
  Dictionary cd = control_entries(in, scales);
  cd.set("functions", function_objects(in));
  add_file(vof, "system/controlDict", "dictionary", cd);
}

}  // namespace hydrojump::reference::detail
