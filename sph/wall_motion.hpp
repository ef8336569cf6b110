// Prescribed wall motion: moving_wall particles (particles.hpp) translate at a constant velocity
// over a time interval and rest outside it, e.g. a dam-break gate lifted at a finite speed (the
// experiments' gates are pulled up in a few hundredths of a second; releasing the column at once,
// as an "instant" gate does, makes the simulated surge lead the measured one).
//
//   v(t) = v_wall  for t_start <= t < t_end,   0 otherwise
//   x(t1) - x(t0) = v_wall |[t0, t1] n [t_start, t_end]|       (exact for this piecewise-constant v)
//
// The walls move by the whole displacement, but the particle velocity u, w the fluid sees is the
// wall-normal part (v(t) . n) n (n along the particle's ghost offset): the wall slides freely past the
// fluid. A gate pulled up along its own face pushes nothing and drags nothing (with the full velocity
// the artificial viscosity between fluid and wall dragged the column up the rising gate and slowed
// the surge by 20 %); a piston pushing along its normal moves the water with its full speed. The
// continuity equation and the boundary conditions use that velocity: DBC takes the fluid velocity
// relative to the wall's, mDBC mirrors the ghost-node velocity through it (v_b = 2 v_wall - v_ghost).
//
// A piston that holds a reservoir's level (sph.inflow_condition = "piston", piston_inflow.hpp) sets
// its speed at the start of every step from the water in front of it (proportional control):
//
//   u_p = max(0, U_p0 + K (H_r - H)),   H = sum_{fluid i, x_i < x_end} (m_i / rho_i) / (x_end - x_face),
//
// U_p0 = q / H_r the speed that feeds q at the level H_r, K = sph.piston_level_gain_per_s, x_end the
// reservoir's downstream end (the gate's upstream face), x_face the piston face (a wall particle plus
// half its ghost offset). The reservoir balance L dH/dt = u_p H - Q(H) then relaxes with the time
// scale L / (K H_r + dQ/dH - U_p0) (about 1.2 s for run A at K = 10/s) instead of drifting away, and
// the gate passes Q(H_r), q if the jet contracts as assumed. The speed depends only on the state at
// the step's start, so a resumed run continues exactly. K = 0: the constant speed U_p0.
//
// Usage
//   | quantity           | from                                                     |
//   |--------------------|----------------------------------------------------------|
//   | velocity, interval | cases::CaseGeometry::moving_walls (dam break, gate.type  |
//   |                    | = "lifted": up at gate.lift_speed_m_s until it clears)   |
//   | level control      | the piston of cases::add_piston_reservoir (H_r, x_end),  |
//   |                    | sph.piston_level_gain_per_s (K, default 10 1/s)          |
// Example: [case.gate] type = "lifted", lift_speed_m_s = 5.2 (cases/dam_break.toml).
#pragma once

#include "sph/particles.hpp"

namespace hydrojump::sph {

struct WallMotion {
  double u_m_s = 0.0, w_m_s = 0.0;   // velocity while moving (U_p0 for a level-holding piston)
  double start_s = 0.0, end_s = 0.0; // the motion's interval [start, end)
  double held_level_m = 0.0;         // H_r (0: no level control)
  double reservoir_end_x_m = 0.0;    // x_end
  double level_gain_per_s = 0.0;     // K

  bool any() const { return (u_m_s != 0.0 || w_m_s != 0.0) && end_s > start_s; }
  bool holds_level() const { return any() && held_level_m > 0.0 && level_gain_per_s > 0.0; }
  // Length of [t0, t1] inside [start, end).
  double moving_time(double t0, double t1) const;
  // The motion of the next step from the state now: a level-holding piston's speed u_p (above),
  // otherwise this motion unchanged.
  WallMotion for_step(const ParticleSet& particles) const;
};

// The moving wall's face: x of a moving_wall particle plus half its ghost offset (the largest over
// them); -infinity without moving walls.
double moving_face_x(const ParticleSet& particles);

// H: the volume of the fluid upstream of x_end over the length x_end - x_face (m).
double reservoir_level(const ParticleSet& particles, double x_face, double x_end);

// Moves every moving_wall particle from its position at t0 to that at t1 (t1 >= t0) and sets its
// velocity to the wall-normal part of v(t1).
void move_walls(ParticleSet& particles, const WallMotion& motion, double t0, double t1);

}  // namespace hydrojump::sph
