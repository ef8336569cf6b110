#include "reference/mesh_plan.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "reference/foam_dictionary.hpp"

namespace hydrojump::reference {

namespace {

constexpr double max_growth_per_cell = 1.2;   // geometric transition between cell sizes

// A corrugated bed acts on the jump through the pressure on its corrugations (form drag), which the
// staircase bed gives only where it has the corrugation's shape: with bed-size cells a quick mesh had
// 1-3 steps across the corrugation height T and a quarter to a half of the bed force the laboratory's
// y2 needs. So the cells from the troughs to the crests are at most T/8 high (8 steps), graded back to
// the bed size by the inflow surface; at resolutions fine enough for 8 cells across T nothing changes.
constexpr int min_cells_across_corrugation = 8;

// A band of uniform cells of about `h`; at least `min_cells`.
GridBand uniform_band(double begin, double end, double h, int min_cells = 1) {
  const int n = std::max(min_cells, static_cast<int>(std::lround((end - begin) / h)));
  return GridBand{begin, end, n, 1.0};
}

// Bands from `begin` up to `end`: fine cells `h_fine` grow geometrically (at most 20 % per cell) to
// `h_bulk`, then uniform `h_bulk`. Without room for the transition the fine size continues to `end`.
void append_transition_and_bulk(std::vector<GridBand>& bands, double begin, double end, double h_fine,
                                double h_bulk) {
  const double room = end - begin;
  if (room <= 1e-12) return;
  const double ratio = h_bulk / h_fine;
  if (ratio <= 1.0 + 1e-9) {
    bands.push_back(uniform_band(begin, end, h_fine));
    return;
  }
  // Cells h q, h q^2, ..., h q^n = h_bulk with q <= 1.2.
  const int n = std::max(1, static_cast<int>(std::ceil(std::log(ratio) / std::log(max_growth_per_cell) - 1e-9)));
  const double q = std::pow(ratio, 1.0 / n);
  const double length = h_fine * q * (std::pow(q, n) - 1.0) / (q - 1.0);
  if (length + h_bulk > room) {
    bands.push_back(uniform_band(begin, end, h_fine));
    return;
  }
  bands.push_back(GridBand{begin, begin + length, n, std::pow(q, n - 1)});
  bands.push_back(uniform_band(begin + length, end, h_bulk));
}

void require_positive(double value, const std::string& what, const cases::Case& c) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument("case \"" + c.id + "\": " + what + " must be > 0 for the VOF mesh");
  }
}

// One band [begin, end] whose cells grow geometrically from about `first` to at most `last`, by at
// most 20 % per cell: the fewest cells that can do it. The ratio q of neighbouring cells solves
// first (q^n - 1) / (q - 1) = end - begin for n cells; n grows until q <= 1.2 and first q^(n-1) <= last.
GridBand graded_band(double begin, double end, double first, double last) {
  const double length = end - begin;
  const int most = std::max(1, static_cast<int>(std::ceil(length / first)));
  for (int n = 1; n < most; ++n) {
    // The series' sum grows with q: bisect on [1e-3, 1.2] for the q that fills the band.
    auto sum = [&](double q) { return std::abs(q - 1.0) < 1e-12 ? first * n : first * (std::pow(q, n) - 1.0) / (q - 1.0); };
    if (sum(max_growth_per_cell) < length) continue;
    double lo = 1e-3, hi = max_growth_per_cell;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      (sum(mid) < length ? lo : hi) = mid;
    }
    const double q = 0.5 * (lo + hi);
    if (first * std::pow(q, n - 1) <= last * (1.0 + 1e-9)) return GridBand{begin, end, n, std::pow(q, n - 1)};
  }
  return uniform_band(begin, end, first);
}

}  // namespace

std::vector<double> band_faces(const std::vector<GridBand>& bands) {
  std::vector<double> faces;
  for (const GridBand& b : bands) {
    if (faces.empty()) faces.push_back(b.begin_m);
    const double length = b.end_m - b.begin_m;
    if (std::abs(b.expansion - 1.0) < 1e-12 || b.cells == 1) {
      for (int i = 1; i <= b.cells; ++i) faces.push_back(b.begin_m + length * i / b.cells);
    } else {
      const double q = std::pow(b.expansion, 1.0 / (b.cells - 1));
      const double first = length * (q - 1.0) / (std::pow(q, b.cells) - 1.0);
      double z = b.begin_m, h = first;
      for (int i = 1; i < b.cells; ++i) {
        z += h;
        h *= q;
        faces.push_back(z);
      }
      faces.push_back(b.end_m);
    }
  }
  return faces;
}

int MeshPlan::columns() const {
  int n = 0;
  for (const GridBand& b : x_bands) n += b.cells;
  return n;
}

int MeshPlan::rows() const {
  int n = 0;
  for (const GridBand& b : z_bands) n += b.cells;
  return n;
}

long MeshPlan::background_cells() const { return static_cast<long>(columns()) * rows(); }

long MeshPlan::removed_cell_count() const {
  if (removed.empty()) return 0;
  const std::vector<double> x = band_faces(x_bands);
  long n = 0;
  for (const RemovedColumns& r : removed) {
    for (std::size_t i = 0; i + 1 < x.size(); ++i) {
      const double xc = 0.5 * (x[i] + x[i + 1]);
      if (xc > r.x_begin_m && xc < r.x_end_m) n += r.removed_cells;
    }
  }
  return n;
}

long MeshPlan::cell_count() const { return background_cells() - removed_cell_count(); }

namespace {

// The cell sizes of resolution `r`: positive, the bulk's no finer than the bed's, and at most max_cells
// cells (memory, and months of run time on a workstation), estimated as the whole domain in cells of the
// bed size (the grading of the bulk only lowers it).
void check_cell_sizes(const cases::Case& c, const cases::CaseGeometry& g, const cases::Resolution& r) {
  const double h = r.vof_cell_size_bed_m;
  const double h_bulk = r.vof_cell_size_bulk_m;
  require_positive(h, "resolution." + r.name + ".vof_cell_size_bed_m", c);
  require_positive(h_bulk, "resolution." + r.name + ".vof_cell_size_bulk_m", c);
  if (h_bulk < h) {
    throw std::invalid_argument("case \"" + c.id + "\": resolution." + r.name +
                                ".vof_cell_size_bulk_m must be >= vof_cell_size_bed_m");
  }
  const double domain_area_m2 = (g.x_max_m - g.x_min_m) * (g.z_max_m - g.z_min_m);
  if (domain_area_m2 / (h * h) > max_cells) {
    const double count = std::min(domain_area_m2 / (h * h), 1e18);
    throw std::invalid_argument("case \"" + c.id + "\": resolution." + r.name + ".vof_cell_size_bed_m = " +
                                foam::format_number(h) + " m gives up to " + foam::format_number(std::round(count)) +
                                " cells: must be at most " + foam::format_number(max_cells) +
                                ", i.e. vof_cell_size_bed_m >= " + foam::format_number(std::sqrt(domain_area_m2 / max_cells)) +
                                " m");
  }
}

// The cartesian cut: in each column the cells whose centres lie below the bed z_b(x), as runs of
// neighbouring columns that lose the same number of cells.
void cut_below_bed(MeshPlan& plan, const cases::CaseGeometry& g) {
  const std::vector<double> x = band_faces(plan.x_bands);
  const std::vector<double> z = band_faces(plan.z_bands);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double zb = g.bed.elevation(0.5 * (x[i] + x[i + 1]));
    int n = 0;
    while (static_cast<std::size_t>(n) + 1 < z.size() && 0.5 * (z[n] + z[n + 1]) < zb) ++n;
    if (n == 0) continue;
    if (!plan.removed.empty() && plan.removed.back().removed_cells == n &&
        std::abs(plan.removed.back().x_end_m - x[i]) < 1e-12) {
      plan.removed.back().x_end_m = x[i + 1];
    } else {
      plan.removed.push_back(RemovedColumns{x[i], x[i + 1], n, z[n]});
    }
  }
}

// The columns of a stilling basin: the columns of a uniform grid inlet to outlet up to the first of
// its lines one tailwater depth y2 past the last section, then growing by at most 20 % per cell to the
// bulk size h_bulk up to the outlet:
//   [x_min, x_g]       h_x             the inflow, the jump and every section (x_s the last one)
//   [x_g, x_max]       h_x -> h_bulk   the gradually varied tailwater flow to the outlet
// with h_x = (x_max - x_min) / round((x_max - x_min) / h) and x_g = x_min + ceil((x_s + y2 - x_min) / h_x) h_x.
// The fine columns keep the uniform grid's lines, so the bed's staircase under the jump is the uniform
// grid's: a column size fitted to [x_min, x_s + y2] instead shifts the staircase against the
// corrugations by up to 0.7 cells across the basin, and moved run C's y2 by 1.6 %. Past the sections
// the flow is subcritical and slowly varied, and the toe is held by the outlet (its level steered,
// tailwater_control.hpp), so what these columns carry to the jump is the discharge and the level, not
// their detail. Without room for the transition the columns stay uniform up to the outlet.
std::vector<GridBand> basin_columns(const cases::CaseGeometry& g, const cases::StillingBasinCase& basin, double h,
                                    double h_bulk) {
  const GridBand uniform = uniform_band(g.x_min_m, g.x_max_m, h, 4);
  if (g.sections.empty()) return {uniform};
  double x_last = g.x_min_m;
  for (const cases::Section& s : g.sections) x_last = std::max(x_last, s.x_m);
  const double length = uniform.end_m - uniform.begin_m;
  const double h_x = length / uniform.cells;
  const int fine = static_cast<int>(std::ceil((x_last + basin.tailwater_depth_m - g.x_min_m) / h_x - 1e-9));
  if (fine < 4 || fine >= uniform.cells) return {uniform};
  // The uniform grid's line `fine` as band_faces computes it (the lines before it agree to rounding).
  const double x_grade = g.x_min_m + length * fine / uniform.cells;
  std::vector<GridBand> bands{GridBand{g.x_min_m, x_grade, fine, 1.0}};
  append_transition_and_bulk(bands, x_grade, g.x_max_m, h_x, h_bulk);
  return bands;
}

// A stilling basin: a grid line on the upstream floor and at the inflow surface y1, bed-size cells up
// to the highest expected surface plus a band, then graded to the bulk size; cut below the bed, or
// (body_fitted) the lowest row on the bed.
void plan_basin(MeshPlan& plan, const cases::Case& c, const cases::StillingBasinCase& basin,
                const cases::CaseGeometry& g, const cases::Resolution& r) {
  const double h = r.vof_cell_size_bed_m;
  const double h_bulk = r.vof_cell_size_bulk_m;
  const cases::MeshStrategy strategy = plan.strategy;
  if (g.inflows.empty() || g.outflows.empty()) {
    throw std::logic_error("case \"" + c.id + "\": stilling-basin geometry without inflow/outflow");
  }
  const cases::InflowBoundary& in = g.inflows.front();
  const double y1 = in.depth_m;
  if (y1 < 2.0 * h) {
    throw std::invalid_argument(
        "case \"" + c.id + "\": resolution." + r.name + ".vof_cell_size_bed_m = " +
        foam::format_number(h) + " m leaves fewer than 2 cells across the inflow depth y1 = " +
        foam::format_number(y1) + " m: must be <= y1/2");
  }
  plan.x_bands = basin_columns(g, basin, h, h_bulk);
  plan.z_floor_m = g.bed.elevation(in.x_m);
  plan.z_inflow_top_m = plan.z_floor_m + y1;
  const double z_low = std::min(g.z_min_m, g.bed.lowest_elevation());
  // Highest expected surface: the initial water surface (y1, a jump's roller up to the tailwater) and
  // the tailwater level at the outlet.
  double z_surface = plan.z_inflow_top_m;
  for (double z : g.initial_water.surface_z_m) z_surface = std::max(z_surface, z);
  for (const auto& out : g.outflows) {
    z_surface = std::max(z_surface, g.bed.elevation(out.x_m) + out.tailwater_depth_m);
  }
  const double band = c.vof.surface_refinement_band_m > 0.0
                          ? c.vof.surface_refinement_band_m
                          : std::max(0.25 * basin.tailwater_depth_m, 3.0 * h);
  plan.z_fine_top_m = std::min(z_surface + band, g.z_max_m);
  const bool has_troughs = z_low < plan.z_floor_m - 1e-9;
  GridBand floor_band{z_low, plan.z_floor_m, 0, 1.0};
  GridBand inflow_band = uniform_band(plan.z_floor_m, plan.z_inflow_top_m, h, 2);
  if (has_troughs) {
    floor_band = uniform_band(z_low, plan.z_floor_m, h);
    // The staircase bed: at least min_cells_across_corrugation rows from troughs to crests, graded
    // back to h by the inflow surface (a grid line stays on it).
    const double h_corrugation = (plan.z_floor_m - z_low) / min_cells_across_corrugation;
    if (strategy == cases::MeshStrategy::cartesian_cut && h_corrugation < h) {
      floor_band = uniform_band(z_low, plan.z_floor_m, h_corrugation);
      inflow_band = graded_band(plan.z_floor_m, plan.z_inflow_top_m, h_corrugation * max_growth_per_cell, h);
    }
  }
  if (strategy == cases::MeshStrategy::body_fitted) {
    // The lowest band follows the bed from z_b(x) up to the inflow surface.
    plan.z_bands.push_back(
        GridBand{z_low, plan.z_inflow_top_m, floor_band.cells + inflow_band.cells, 1.0});
  } else {
    if (has_troughs) plan.z_bands.push_back(floor_band);
    plan.z_bands.push_back(inflow_band);
  }
  if (plan.z_fine_top_m > plan.z_inflow_top_m + 0.5 * h) {
    plan.z_bands.push_back(uniform_band(plan.z_inflow_top_m, plan.z_fine_top_m, h));
  } else {
    plan.z_fine_top_m = plan.z_inflow_top_m;
  }
  append_transition_and_bulk(plan.z_bands, plan.z_fine_top_m, g.z_max_m, h, h_bulk);

  if (strategy == cases::MeshStrategy::body_fitted) {
    plan.bed_vertices = g.bed.polyline(g.x_min_m, g.x_max_m, 0.05 * h);
    plan.x_bands.clear();
    for (std::size_t i = 0; i + 1 < plan.bed_vertices.size(); ++i) {
      plan.x_bands.push_back(uniform_band(plan.bed_vertices[i].x(), plan.bed_vertices[i + 1].x(), h));
    }
  } else if (has_troughs) {
    cut_below_bed(plan, g);
  }
}

// Closed tanks: dam break and still water (floor at z = 0, walls at both ends, open top).
void plan_tank(MeshPlan& plan, const cases::Case& c, const cases::CaseGeometry& g, double h, double h_bulk) {
  const cases::MeshStrategy strategy = plan.strategy;
  if (!c.dam_break() && !c.still_water()) {
    throw std::invalid_argument("case \"" + c.id + "\": kind \"" + c.kind +
                                "\" has no VOF reference (stilling_basin, dam_break, still_water)");
  }
  if (strategy == cases::MeshStrategy::body_fitted) {
    throw std::invalid_argument("case \"" + c.id + "\": vof.mesh_strategy = \"body_fitted\" is only "
                                "meaningful for stilling basins (a tank is already Cartesian): use "
                                "\"cartesian_cut\"");
  }
  double z_water = g.z_min_m;
  for (double z : g.initial_water.surface_z_m) z_water = std::max(z_water, z);
  plan.z_floor_m = g.z_min_m;
  plan.z_inflow_top_m = std::min(z_water, g.z_max_m);
  // A grid line at the dam-break gate so the initial column has a sharp, exact edge.
  const double x_gate = g.dam_gate_x_m;
  if (x_gate > g.x_min_m + h && x_gate < g.x_max_m - h) {
    plan.x_bands.push_back(uniform_band(g.x_min_m, x_gate, h));
    plan.x_bands.push_back(uniform_band(x_gate, g.x_max_m, h));
  } else {
    plan.x_bands.push_back(uniform_band(g.x_min_m, g.x_max_m, h, 4));
  }
  if (plan.z_inflow_top_m > g.z_min_m + 0.5 * h) {
    plan.z_bands.push_back(uniform_band(g.z_min_m, plan.z_inflow_top_m, h, 2));
  } else {
    plan.z_inflow_top_m = g.z_min_m;
  }
  const double band = std::max(c.vof.surface_refinement_band_m, 0.0);
  plan.z_fine_top_m = std::min(plan.z_inflow_top_m + band, g.z_max_m);
  if (plan.z_fine_top_m > plan.z_inflow_top_m + 0.5 * h) {
    plan.z_bands.push_back(uniform_band(plan.z_inflow_top_m, plan.z_fine_top_m, h));
  } else {
    plan.z_fine_top_m = plan.z_inflow_top_m;
  }
  append_transition_and_bulk(plan.z_bands, plan.z_fine_top_m, g.z_max_m, h, h_bulk);
}

}  // namespace

MeshPlan plan_mesh(const cases::Case& c, const cases::CaseGeometry& g, const cases::Resolution& r) {
  check_cell_sizes(c, g, r);
  MeshPlan plan;
  plan.strategy = c.vof.mesh_strategy;
  plan.thickness_m = r.vof_cell_size_bed_m;

  if (const auto* basin = c.stilling_basin()) {
    plan_basin(plan, c, *basin, g, r);
  } else {
    plan_tank(plan, c, g, r.vof_cell_size_bed_m, r.vof_cell_size_bulk_m);
  }
  return plan;
}

}  // namespace hydrojump::reference
