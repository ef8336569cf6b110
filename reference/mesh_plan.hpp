// The 2D mesh of an OpenFOAM case planned from the case geometry and the chosen resolution, before any
// file is written: where the grid lines are, how many cells each block has, and which cells the
// staircase ("cartesian_cut") strategy removes below the bed.
//
// Coordinates: the spec's (x, z) become OpenFOAM's (x, y) with gravity along -y, as in OpenFOAM's
// tutorials; OpenFOAM's z is the one-cell-thick spanwise direction (front and back patches `empty`).
//
// Vertical cell sizes (both strategies), bottom to top:
//   [z_lowest, z_floor]      corrugation troughs up to the upstream floor (cut or body-fitted)   h_bed
//                            (cartesian_cut: at most T/8, T the corrugation height)
//   [z_floor,  z_inflow]     the supercritical inflow layer y1 (a grid line at its surface)        h_bed
//                            (cartesian_cut on corrugations: graded from T/8 to h_bed, <= 20 %/cell)
//   [z_inflow, z_fine_top]   up to the highest expected surface plus the refinement band          h_bed
//   [z_fine_top, z_bulk]     geometric transition (ratio <= 1.2 per cell) to the bulk size
//   [z_bulk, z_max]          the air above                                                         h_bulk
// with h_bed = vof_cell_size_bed_m and h_bulk = vof_cell_size_bulk_m of the resolution; the cell sizes
// are adjusted within each band so that every band holds a whole number of cells. Along x, inlet to
// outlet of a stilling basin (cartesian_cut):
//   [x_min, x_g]             every section (x_s the last) and one tailwater depth past it       h_x
//   [x_g, x_max]             geometric transition (ratio <= 1.2 per cell) to the bulk size      h_bulk
// with h_x the size of uniform columns inlet to outlet (h_bed adjusted to a whole number of them) and
// x_g the first of their lines at or past x_s + y2: under the jump the columns are the uniform grid's.
// (body_fitted basins and tanks: uniform h_bed; a tank has a grid line at the dam-break gate).
//
// cartesian_cut: one column of blocks; a cell is removed when its centre lies below the bed
// z_b(x_centre) (a staircase, every face aligned with the axes); the exposed faces join the `bed`
// patch. body_fitted: one block column per segment of the bed polyline, the lowest band following
// the bed (faces not aligned with the axes).
#pragma once

#include <string>
#include <vector>

#include "cases/geometry.hpp"
#include "cases/spec.hpp"

namespace hydrojump::reference {

// A range of the grid along one axis holding `cells` cells; `expansion` is the ratio of the last to
// the first cell (blockMesh's simpleGrading), 1 for uniform.
struct GridBand {
  double begin_m = 0.0;
  double end_m = 0.0;
  int cells = 0;
  double expansion = 1.0;
};

// Cell face coordinates of a sequence of bands (begin of the first band to end of the last).
std::vector<double> band_faces(const std::vector<GridBand>& bands);

// A run of neighbouring cell columns [x_begin, x_end] from which the lowest `removed_cells` cells are
// cut (their centres lie below z_top_m; z_top_m is the top face of the last removed cell).
struct RemovedColumns {
  double x_begin_m = 0.0;
  double x_end_m = 0.0;
  int removed_cells = 0;
  double z_top_m = 0.0;
};

struct MeshPlan {
  cases::MeshStrategy strategy = cases::MeshStrategy::cartesian_cut;  // vof.mesh_strategy
  std::vector<GridBand> x_bands;        // along the channel
  std::vector<GridBand> z_bands;        // vertical, bottom to top
  double thickness_m = 0.0;             // spanwise extent (one cell)
  double z_floor_m = 0.0;               // the upstream floor
  double z_inflow_top_m = 0.0;          // inflow surface (stilling basins), column top (dam break)
  double z_fine_top_m = 0.0;            // top of the fine band
  // cartesian_cut: cells removed below the bed (empty when the bed is flat at the lowest level).
  std::vector<RemovedColumns> removed;
  // body_fitted: bed vertices (x, z_b) bounding the block columns, left to right.
  std::vector<Eigen::Vector2d> bed_vertices;

  int columns() const;                  // cells along x
  int rows() const;                     // cells along z
  long background_cells() const;        // columns * rows
  long removed_cell_count() const;
  long cell_count() const;              // cells of the final mesh
};

// The largest mesh plan_mesh accepts (cells of a 2D case).
inline constexpr double max_cells = 1.0e7;

// Plans the mesh of `c` (stilling_basin, dam_break or still_water) at `resolution`.
// Throws std::invalid_argument with a clear message for unsupported kinds or strategies, and for
// cell sizes that leave fewer than 2 cells across the inflow depth.
MeshPlan plan_mesh(const cases::Case& c, const cases::CaseGeometry& geometry,
                   const cases::Resolution& resolution);

}  // namespace hydrojump::reference
