// Section sampling of one output time of either method onto vertical lines ("columns"), independent of
// file formats. Both methods are reduced to the same ColumnSample, so every later step (statistics,
// jump metrics, discrepancies) treats SPH and VOF identically.
//
// Column at x, from the bed z_b(x) to the free surface eta(x):
//   points       z_k = z_b + k (eta - z_b)/(n - 1), k = 0..n-1, n odd (Simpson's rule is exact for
//                cubics, so the integrals below are exact for linear u in a column without voids)
//   depth        h = eta - z_b
//   water        chi(z) = 1 where the fraction c(z) >= 0.5 (SPH kernel sum, VOF alpha), else 0: the
//                voids below the surface (air pockets under a plunging roller; in single-phase SPH
//                empty cavities) carry no water. Velocities interpolated there from the water around
//                them would otherwise count: run B at `default` showed a time-mean q 23 % above the
//                inflow at a section in the roller before this mask. The surface point counts as water,
//                and so do points less than `bed_exemption_m` above the bed (a staircase VOF bed cell
//                that is partly solid has alpha < 0.5 though it is full of water). A column with a void
//                is integrated interval by interval: trapezoidal over water, up to the c = 0.5 crossing
//                (linear in c) over an interval holding a void's edge (Simpson's alternating weights
//                would count a void of m points as (m +- 1/3) dz depending on where it starts).
//   discharge    q = int_{z_b}^{eta} chi u dz
//   water depth  h_w = int chi dz  (void_fraction = 1 - h_w / h)
//   mean vel.    U = q / h   (over the whole depth h, voids included: E and M below use h)
//   max vel.     u_max = max_k u(z_k) over the water points
//   KE coeff.    alpha = int chi u^3 dz / (U^3 h)   (Coriolis coefficient)
//   energy       E = z_b + h + alpha U^2 / (2 g)  (total head above the datum z = 0)
//   mom. coeff.  beta = int chi u^2 dz / (U^2 h)    (Boussinesq coefficient)
//   spec. force  M = h^2/2 + beta q^2 / (g h)   (momentum function per unit width, m^2: the
//                hydrostatic force plus the momentum flux, divided by rho g; Belanger's jump has M1 = M2;
//                h^2/2 counts a void as water, i.e. hydrostatic pressure through it)
//   near-surface velocity u_s = u(eta - 0.1 h)   (sign gives the direction of the surface flow; not
//                masked: in a void it is the velocity interpolated from the water around it)
//
// Free surface:
//   SPH  the kernel-interpolated fluid fraction c(x) = sum_j V_j W(|x - x_j|, h) over fluid AND
//        boundary particles (V_j = m_j / rho_j); the surface is the highest z where c = 0.5, found by a
//        downward scan in steps of h/4 from above the highest particle near x and bisection to 1e-7 m.
//        For a half-space of particles the continuum value of c at the boundary is exactly 1/2.
//        Wet runs (c >= 0.5) thinner than 1.5 dx above the water (droplets, spray) are skipped.
//   VOF  the cells cut by the vertical line, ordered by height; alpha varies linearly between cell
//        centres; the surface is the highest alpha = 0.5 crossing (flat interface: error <= dz/12),
//        skipping runs of cells with alpha >= 0.5 thinner than 1.5 cells (droplets, spray).
//   Check for both: eta_int = z_b + (water depth), the depth being int_{z_b}^{top} c dz for SPH and
//        sum_k alpha_k dz_k over the cells of the column for VOF (on a staircase bed the water between
//        z_b and the lowest cell face shifts the VOF value by up to one bed cell).
// Velocities at the points:
//   SPH  water particles only (type 0 fluid, 2/3 inflow/outflow buffers), weights V_j W; scheme
//        "mls_linear" (default) or "shepard".
//   VOF  cell centres within 1.6 local cell sizes, weights A_j w(r) alpha_j (the water phase),
//        scheme as above; pressure is p_rgh when that is what the case wrote.
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "compare/point_cloud.hpp"

namespace hydrojump::compare {

inline constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// One SPH output time (structure of arrays). z is the vertical coordinate (VTK's y).
struct ParticleFrame {
  double time_s = 0.0;
  std::vector<double> x, z, u, w, pressure, density;
  std::vector<double> mass;      // empty: m = reference_density * dx^2 for every particle
  std::vector<int> type;         // 0 fluid, 1 boundary, 2 inflow buffer, 3 outflow buffer (sph/particles.hpp)
};

// One VOF output time: cells of the 2D mesh (one cell thick) as centres and axis-aligned bounds.
struct CellFrame {
  double time_s = 0.0;
  std::vector<double> xc, zc, x_lo, x_hi, z_lo, z_hi;
  std::vector<double> alpha, u, w, pressure;
};

struct SphSamplingSettings {
  std::string kernel = "wendland_c2";
  double particle_spacing_m = 0.0;
  double smoothing_length_m = 0.0;     // h = coef_h sqrt(2) dx
  double reference_density_kg_m3 = 1000.0;
  InterpolationScheme scheme = InterpolationScheme::mls_linear;
  double z_ceiling_m = std::numeric_limits<double>::infinity();  // no surface search above (domain top)
};

// Values at one point.
struct PointSample {
  double fraction = 0.0;   // SPH kernel sum of volumes / VOF alpha
  double u = not_a_number, w = not_a_number, pressure = not_a_number;
};

struct ColumnSample {
  double x_m = 0.0;
  double z_bed_m = 0.0;
  double surface_z_m = not_a_number;            // eta; NaN when the column is dry or outside the data
  double surface_from_fraction_m = not_a_number; // the integral check (see above)
  double depth_m = not_a_number;
  std::vector<double> z, u, w, pressure;
  std::vector<double> fraction;                 // c(z_k) (SPH) / alpha(z_k) (VOF); empty: all water
  std::vector<double> water;                    // chi(z_k): 1 water, 0 void (set by integrate_column)
  double bed_exemption_m = 0.0;                 // points this close to the bed count as water
  double void_fraction = not_a_number;          // 1 - h_w / h
  double discharge_m2_s = not_a_number;
  double mean_velocity_m_s = not_a_number;
  double max_velocity_m_s = not_a_number;
  double near_surface_velocity_m_s = not_a_number;
  double energy_coefficient = not_a_number;     // alpha
  double specific_energy_m = not_a_number;      // E
  double momentum_coefficient = not_a_number;   // beta
  double specific_force_m2 = not_a_number;      // M
  bool wet() const { return std::isfinite(surface_z_m) && depth_m > 0.0; }
};

// Common interface of the two methods' samplers. Implementations are immutable after construction
// and safe to call from several threads.
class FrameSampler {
 public:
  virtual ~FrameSampler() = default;
  virtual double time_s() const = 0;
  virtual PointSample sample_point(double x, double z) const = 0;
  // The column at x above the bed z_bed with `n_points` (odd, >= 3) profile points.
  virtual ColumnSample sample_column(double x, double z_bed, int n_points, double gravity) const = 0;
};

std::unique_ptr<FrameSampler> make_sph_sampler(const ParticleFrame& frame,
                                               const SphSamplingSettings& settings);
std::unique_ptr<FrameSampler> make_vof_sampler(const CellFrame& frame, InterpolationScheme scheme);

// Fills the integral quantities of `column` from its z, u profile (z evenly spaced, odd count) and
// its surface: q, U, u_max, u_s, alpha, E, beta, M. Exposed for tests and for hand-built sections.
void integrate_column(ColumnSample& column, double gravity);

// Composite Simpson rule over evenly spaced samples (odd count >= 3).
double simpson(const std::vector<double>& f, double spacing);

}  // namespace hydrojump::compare
