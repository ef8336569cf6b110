// Open boundaries of a stilling basin: a supercritical inflow buffer and a tailwater outflow buffer,
// in the buffer-zone style of Tafuni, Domínguez, Vacondio & Crespo (2018, Comput. Methods Appl. Mech.
// Eng. 342:604-624) as used by DualSPHysics' inlet/outlet.
//
// Inflow buffer. A block of particles upstream of the inflow section x_in, `layers` columns deep and
// N = round(y1/dx) rows high, moves at the imposed velocity U_b with the hydrostatic density of its depth:
//
//   u = U_b,  w = 0,  rho = rho0 (1 + rho0 g (z_s - z) / B)^(1/7),   z_s = z_b(x_in) + N dx,
//   U_b = q / (N dx)  with q = y1 U1,      so the discharge is exactly the spec's q even when y1/dx
//                                           is not a whole number (the depth is N dx instead of y1).
//
// A buffer particle that crosses x_in becomes a fluid particle, and a new buffer particle takes its
// place `layers` dx upstream; each conversion injects one particle mass, so the mass inflow rate is
// rho0 N dx U_b = rho0 q.
//
// Outflow buffer. Fluid that crosses the outflow section x_out becomes outflow-buffer particles. They
// move horizontally with the depth-averaged velocity of the fluid just upstream (zero-gradient
// velocity, never negative), carry the hydrostatic density of the tailwater level
//
//   rho = rho0 (1 + rho0 g (z_b(x_out) + y_t - z) / B)^(1/7),
//
// and are removed once they are `layers` dx past x_out. Buffer particles that enter above the
// tailwater level (plus dx/2) are removed at once: together with the imposed hydrostatic pressure this
// holds the outlet level at the tailwater depth y_t (a level controller). This is
// sph.outflow_condition = "hydrostatic_level" (the default). It holds the level firmly but reflects
// the long waves of the start-up, so the basin sloshes.
//
// sph.outflow_condition = "absorbing": the buffer is a characteristic (non-reflecting) outlet of the
// shallow-water equations. With h and u the water depth and mean velocity of the fluid strip just
// upstream of x_out (volume / strip length, mass-weighted u) and U_t = q / y_t the tailwater velocity,
// the outlet state (h_B, u_B) takes the invariant leaving the basin from the strip and the one
// entering it from the tailwater:
//
//   u_B + 2 sqrt(g h_B) = u + 2 sqrt(g h)          (R+, carried out of the basin)
//   u_B - 2 sqrt(g h_B) = U_t - 2 sqrt(g y_t)      (R-, imposed)
//   =>  sqrt(g h_B) = (R+ - R-) / 4,   u_B = (R+ + R-) / 2   (both >= 0).
//
// Buffer particles move at u_B and carry the hydrostatic density of the level z_b + h_B, so waves
// arriving from the basin leave instead of reflecting, and the level relaxes to y_t: a basin above the
// tailwater sees an outlet level below its own and drains. Only particles entering more than 2 dx above
// max(h, h_B) are removed at once (spray). At h = y_t, u = U_t the outlet is the tailwater state itself;
// a target lowered by delta lets out (c_t^2 - U_t^2) delta / (2 c_t) more (c_t = sqrt(g y_t), to first
// order), which the toe-holding control's volume law uses (toe_hold_control.hpp).
//
// The absorbing outlet's Riemann invariants are those of the 1D shallow-water equations (e.g. Stoker
// 1957, Water Waves, ch. 10), imposed as characteristic boundary conditions (Thompson 1987, J. Comput.
// Phys. 68:1-24); the level-holding outlet follows DualSPHysics' outlet with an imposed
// hydrostatic pressure (Tafuni et al. 2018).
//
// Usage
//   | spec key                  | values / range                  | default              | meaning                          |
//   |---------------------------|---------------------------------|----------------------|----------------------------------|
//   | sph.inflow_condition      | "buffer", "piston"              | "buffer"             | this buffer, or piston_inflow.hpp |
//   | sph.outflow_condition     | "hydrostatic_level", "absorbing", "tailgate" | "hydrostatic_level" | above; tailgate.hpp  |
//   | sph.outflow_level_reference | "outlet", "downstream_section" | "outlet"          | where y_t is held; outflow_level_control.hpp |
//   | sph.open_boundary_layers  | 0-50 (0: automatic; else at least ceil(2 sqrt(2) coef_h) + 1) | 0 | buffer depth in columns |
//   | quantity        | from                                          |
//   |-----------------|-----------------------------------------------|
//   | x_in, y1, U1    | CaseGeometry::inflows[0]                      |
//   | x_out, y_t      | CaseGeometry::outflows[0]                     |
//   | layers          | ceil(kernel support / dx) + 1 (at least that) |
// Example (spec): `[sph]  outflow_condition = "absorbing"`
// Example:
//   InflowBuffer inflow(geometry.inflows[0], bed_z, {dx, support, eos, g});
//   inflow.create(particles, next_id);              // once, at start
//   inflow.advance(particles, dt, next_id);         // after every time step
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "cases/geometry.hpp"
#include "sph/equation_of_state.hpp"
#include "sph/outflow_level_control.hpp"
#include "sph/particles.hpp"
#include "sph/settings.hpp"
#include "sph/piston_inflow.hpp"
#include "sph/tailgate.hpp"

namespace hydrojump::sph {

// Numbers both buffers need.
struct BufferParameters {
  double dx = 0.0;                 // particle spacing (m)
  double support = 0.0;            // kernel support radius (m)
  TaitEquationOfState eos;
  double gravity = 9.81;           // m/s^2
  int layers = 0;                  // 0: ceil(support / dx) + 1; otherwise at least that
  InflowCondition inflow = InflowCondition::buffer;                // inflow buffers, or a piston reservoir
  OutflowCondition outflow = OutflowCondition::hydrostatic_level;  // outflow buffers, or a tailgate
  double tailgate_height = 0.0;    // "tailgate": crest height above the bed (m)
  // Level control at the "downstream" section (outflow_level_control.hpp) instead of at the outlet.
  bool level_at_section = false;
  double level_section_x = 0.0;    // m
  double level_time = 2.0;         // T_c (s)
};

// Running totals of what crossed the open boundaries (kg per metre of width).
struct OpenBoundaryTotals {
  double mass_in = 0.0;
  double mass_out = 0.0;
  std::int64_t particles_in = 0;
  std::int64_t particles_out = 0;
};

class InflowBuffer {
 public:
  // Throws std::invalid_argument when the buffer cannot work (e.g. fewer than 2 rows across y1,
  // or a requested layer count thinner than the kernel support).
  InflowBuffer(const cases::InflowBoundary& inflow, double bed_z, const BufferParameters& params);

  // Appends the buffer particles to `particles`; ids from `next_id` (advanced).
  void create(ParticleSet& particles, std::int64_t& next_id) const;
  // Moves the buffer by U_b dt, imposes velocity and density, converts particles that crossed x_in
  // into fluid and refills the buffer. Returns the mass converted into fluid (kg/m).
  double advance(ParticleSet& particles, double dt, std::int64_t& next_id);

  int rows() const { return rows_; }
  int layers() const { return layers_; }
  double buffer_velocity() const { return velocity_; }    // U_b
  double section_x() const { return x_in_; }
  double particle_mass() const { return mass_; }
  const OpenBoundaryTotals& totals() const { return totals_; }

 private:
  double x_in_, bed_z_, dx_, velocity_, surface_z_, mass_, gravity_;
  int rows_, layers_;
  TaitEquationOfState eos_;
  OpenBoundaryTotals totals_;
};

class OutflowBuffer {
 public:
  // `discharge_m2_s` (the inflow's q) sets U_t = q / y_t for the absorbing condition.
  OutflowBuffer(const cases::OutflowBoundary& outflow, double bed_z, const BufferParameters& params,
                double discharge_m2_s = 0.0);

  // Converts fluid past x_out into buffer particles, imposes their velocity and density, removes
  // those beyond the buffer or above the tailwater level (retires them: ParticleSet::retire; see
  // remove_retired). Returns the mass removed (kg/m).
  double advance(ParticleSet& particles, double dt);

  int layers() const { return layers_; }
  double section_x() const { return x_out_; }
  double level_z() const { return level_z_; }
  // The target depth y_t (m); set_target_depth moves it (and so U_t = q / y_t) for the level controls.
  double target_depth() const { return level_z_ - bed_z_; }
  void set_target_depth(double depth_m);
  const OpenBoundaryTotals& totals() const { return totals_; }

  // The absorbing condition's outlet state (h_B, u_B) from the strip's depth h and mean velocity u
  // and the target depth y_t (the formula above).
  struct CharacteristicOutlet {
    double depth_m = 0.0;       // h_B
    double velocity_m_s = 0.0;  // u_B
  };
  CharacteristicOutlet characteristic_outlet(double strip_depth_m, double strip_velocity_m_s, double target_depth_m) const;

 private:
  double x_out_, bed_z_, dx_, level_z_, gravity_;
  double discharge_ = 0.0;         // q (m^2/s): U_t = q / y_t (absorbing condition)
  bool absorbing_ = false;
  int layers_;
  TaitEquationOfState eos_;
  OpenBoundaryTotals totals_;
};

// The open boundaries of a case: its inflow and outflow buffers, or a tailgate in place of the outflow
// buffers (sph.outflow_condition = "tailgate"), and a piston reservoir's gate crossing in place of the
// inflow buffers (sph.inflow_condition = cases::InflowCondition::piston; none for closed cases). Their state
// is derived from the particles (the buffer particles' types and positions), so a run resumed from
// its particles continues exactly; only the running totals start again from zero.
//
// Usage
//   OpenBoundaries open = OpenBoundaries::from_geometry(geometry, buffer_parameters(settings));
//   open.create(particles);        // the generator: the inflow buffers' first particles
//   open.advance(particles, dt);   // the solver: after every completed time step
class OpenBoundaries {
 public:
  OpenBoundaries() = default;  // a closed case
  // One buffer per geometry inflow and outflow, at the bed elevation of its section.
  static OpenBoundaries from_geometry(const cases::CaseGeometry& geometry, const BufferParameters& params);

  bool empty() const { return inflows_.empty() && outflows_.empty() && tailgates_.empty() && crossings_.empty(); }
  // Takes the reference state the piston inflow's bookkeeping needs (the solver, at construction).
  void start(const ParticleSet& particles);
  // Fluid removed at x_i with masses m_i by another rule (density outliers) since the last advance():
  // not inflow (a piston reservoir's crossing counts water leaving upstream of its gate section).
  void forget_removed(const std::vector<double>& x, const std::vector<double>& mass);
  // Appends the inflow buffers' particles, ids from max id + 1.
  void create(ParticleSet& particles) const;
  // Advances every inflow, then every outflow buffer over the step from t to t + dt; new ids from
  // max id + 1; then, with a level control, moves the outflow buffers' target depth at its control
  // instants. Returns what crossed the open boundaries in this step.
  OpenBoundaryTotals advance(ParticleSet& particles, double t, double dt);
  // The outflow buffers' target depth y_t (m; 0 without outflow buffers), and setting it (a resumed
  // run restores the level control's state).
  double outflow_target_depth() const;
  void set_outflow_target_depth(double depth_m);
  // Totals since this object was made (kg per metre of width).
  double mass_in() const;
  double mass_out() const;
  const std::vector<InflowBuffer>& inflows() const { return inflows_; }
  const std::vector<OutflowBuffer>& outflows() const { return outflows_; }
  const std::vector<Tailgate>& tailgates() const { return tailgates_; }
  // Length of the buffer zones beyond the sections (m): layers dx.
  double buffer_length() const { return buffer_length_; }

 private:
  std::vector<InflowBuffer> inflows_;
  std::vector<OutflowBuffer> outflows_;
  std::vector<Tailgate> tailgates_;
  std::vector<GateCrossing> crossings_;   // piston inflows: the water crossing the inflow section
  std::optional<OutflowLevelControl> level_control_;  // sph.outflow_level_reference = "downstream_section"
  double buffer_length_ = 0.0;
};

// Buffer parameters of a run: its particle spacing, kernel support, equation of state and gravity.
BufferParameters buffer_parameters(const SolverSettings& settings);

// The next free particle id: max id + 1 (0 for no particles).
std::int64_t next_particle_id(const ParticleSet& particles);

// Removes the particles whose flag is set, keeping the order of the others.
void remove_particles(ParticleSet& particles, const std::vector<char>& remove);
// Removes the retired particles (ParticleType::retired), keeping the order of the others; returns how many.
Eigen::Index remove_retired(ParticleSet& particles);

// The number of buffer layers for a kernel support: at least ceil(support / dx) + 1.
int buffer_layers(double support, double dx, int requested);

}  // namespace hydrojump::sph
