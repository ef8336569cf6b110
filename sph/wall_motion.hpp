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
// Usage
//   | quantity           | from                                                     |
//   |--------------------|----------------------------------------------------------|
//   | velocity, interval | cases::CaseGeometry::moving_walls (dam break, gate.type  |
//   |                    | = "lifted": up at gate.lift_speed_m_s until it clears)   |
// Example: [case.gate] type = "lifted", lift_speed_m_s = 5.2 (cases/dam_break.toml).
#pragma once

#include "sph/particles.hpp"

namespace hydrojump::sph {

struct WallMotion {
  double u_m_s = 0.0, w_m_s = 0.0;   // velocity while moving
  double start_s = 0.0, end_s = 0.0; // the motion's interval [start, end)

  bool any() const { return (u_m_s != 0.0 || w_m_s != 0.0) && end_s > start_s; }
  // Length of [t0, t1] inside [start, end).
  double moving_time(double t0, double t1) const;
};

// Moves every moving_wall particle from its position at t0 to that at t1 (t1 >= t0) and sets its
// velocity to the wall-normal part of v(t1).
void move_walls(ParticleSet& particles, const WallMotion& motion, double t0, double t1);

}  // namespace hydrojump::sph
