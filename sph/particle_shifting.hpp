// Particle shifting: a small displacement of each fluid particle down the gradient of the particle
// concentration, which keeps the particle distribution uniform where the flow stretches it, so that
// voids and clumps (the tensile instability of WCSPH in low-pressure vortices) do not form.
//
// Fickian shifting (Lind, Xu, Stansby & Rogers 2012, J. Comput. Phys. 231:1499-1523) with the
// velocity-scaled diffusion coefficient of Skillen, Lind, Stansby & Rogers (2013, Comput. Methods
// Appl. Mech. Engrg. 265:163-173), as DualSPHysics applies it to WCSPH (Mokos, Rogers & Stansby
// 2017, J. Hydraul. Res. 55:143-162):
//   delta r_i = -A h |v_i| dt f_i grad C_i,      grad C_i = sum_j V_j grad_i W_ij
// over every neighbour j (fluid, wall and open-boundary buffer particles, so a particle next to a
// wall is not pushed into it). grad C points towards more particles: into the water at the free
// surface, where the kernel is truncated, so there -grad C would push particles out of the water.
// Particles there are not shifted. They are found by the divergence of position
//   div r_i = -sum_j V_j (r_i - r_j) . grad_i W_ij          (= 2 in the bulk of a 2D fluid)
// being below a threshold TFS (DualSPHysics' ShiftTFS, 1.5 in 2D), and the shift fades in below the
// surface with DualSPHysics' ramp
//   f_i = 0 where div r_i < TFS,   f_i = (div r_i - TFS) / (2 - TFS) elsewhere,
// so the rows just under the surface are not pulled up at full strength. Each displacement is
// capped at 0.1 dx (DualSPHysics caps each component at 0.1 dp; here the length, keeping the
// direction). With the CFL condition dt <= 0.2 h / c0 and |v| <= 0.1 c0 (Mach 0.1), |v| dt <= 0.02 h,
// so |delta r| <= 0.02 A f h^2 |grad C|: a few percent of h per step.
//
// Under a flowing free surface the ramp is not enough: the rows just below it (TFS <= div r < 2) still
// have truncated kernels, so their grad C points down, every step pushes them up by A h |v| dt f |grad C|,
// and the water column swells without gaining mass. Measured (TFS 1.5): in run A at quick
// the tailwater's particles stood 21 % higher than their volume sum V_i / w and, the SPH pressure
// gradient being short by about that factor, the bed pressure was 1.42 rho0 g h; in run E at `default`
// a "+22 % sequent depth" was this swelling (surface 0.380 m over 0.311 m of water).
// Correction "taylor_volume" (below) removes it.
//
// A shifted particle keeps its velocity and density (correction "none", as in DualSPHysics), so it
// carries them a little across the flow: per step an error delta r . grad(phi), which does not average
// out where grad C has a steady direction (under the free surface, across a shear layer). Correction
// "taylor" moves them with the particle by a first-order Taylor expansion (Xu, Stansby & Laurence
// 2009, J. Comput. Phys. 228:6703-6725; Lind et al. 2012):
//   phi_i <- phi_i + delta r_i . grad phi_i,   grad phi_i = sum_j V_j (phi_j - phi_i) grad_i W_ij
// for phi = u, w, rho, with j over the fluid and open-boundary buffer particles (wall particles carry
// mDBC's ghost values, not the flow's, and are left out: near a wall the sum is one-sided and
// underestimates the gradient, which errs towards no correction).
//
// The swelling above is a decoupling of density and particle spacing: the shift spreads the particles
// but their density (from the continuity equation) does not see it, and with a stiff equation of state
// the swollen state costs almost no pressure. Correction "taylor_volume" keeps them coupled: particle
// i's volume m_i / rho_i follows the divergence of the shift field, as it would for a displacement by
// a velocity (the continuity equation for constant-mass particles moved by delta r),
//   rho_i <- rho_i (1 - div(delta r)_i),   div(delta r)_i = sum_j V_j (delta r_j - delta r_i) . grad_i W_ij
// (walls and buffers do not shift), besides the Taylor correction; a swollen layer then loses density
// and pressure, and gravity closes it again. Known limit: this form is not volume-neutral. Summed over
// the particles, sum_i V_i div(delta r)_i ~ -2 sum_i V_i delta r_i . grad C_i = 2 sum_i V_i D_i |grad C_i|^2
// >= 0 (D_i = A h |v_i| dt f_i, below the cap), so where shifting keeps smoothing disorder the
// densities can drift low. In run A at quick the tailwater's bed pressure still averaged
// 0.95 rho0 g h over 6-10 s (1.02 without shifting, 1.42 with correction "none").
//
// Usage:
//   | sph.particle_shifting                | "none" (default) | "fickian": the shifting above      |
//   | sph.particle_shifting_coefficient    | A, in (0, 10], default 2 (Skillen et al.: 1-6)         |
//   | sph.particle_shifting_surface_threshold | TFS: div r below which a particle is at the free |
//   |                                      | surface and not shifted, in [0, 1.9], default 1.5      |
//   | sph.particle_shifting_correction     | "none" (default) | "taylor": u, w, rho moved with the shift |
//   |                                      | | "taylor_volume": and rho follows the particle volume |
// These three are only allowed with "fickian"; shifting needs time_integrator = "symplectic"
// (the shift is applied after the corrector, with grad C from the corrector's interaction).
// Example (spec): `[case.sph]  particle_shifting = "fickian"   particle_shifting_coefficient = 2`
#pragma once

#include <string>
#include <vector>

#include "cases/options.hpp"
#include "sph/cell_list.hpp"
#include "sph/particles.hpp"

namespace hydrojump::sph {

struct SolverSettings;

using cases::ParticleShifting;    // sph.particle_shifting (cases/options.hpp)
using cases::ShiftingCorrection;  // sph.particle_shifting_correction

// grad C and div r of every fluid particle (zero for the others), at the current positions; the
// particle arrays must be in the order of `cells`. With correction "taylor" also the gradients of
// u, w and rho (d/dx, d/dz; empty otherwise). The solver keeps one from step to step, so its arrays,
// and the shift scratch that shift_particles fills for correction "taylor_volume", are reused.
struct ConcentrationGradients {
  std::vector<double> grad_x, grad_z, div_r;
  std::vector<double> du_dx, du_dz, dw_dx, dw_dz, drho_dx, drho_dz;
  std::vector<double> shift_x, shift_z, shift_div;  // "taylor_volume": delta r and div(delta r)
};
void concentration_gradients(const ParticleSet& ps, const CellList& cells, const SolverSettings& s,
                             ConcentrationGradients& out);

// What one shift did (for diagnostics and tests).
struct ShiftSummary {
  Eigen::Index shifted = 0;        // fluid particles moved
  Eigen::Index at_surface = 0;     // fluid particles left alone at the free surface
  Eigen::Index capped = 0;         // fluid particles whose displacement was capped at 0.1 dx
  double max_displacement = 0.0;   // largest |delta r| (m)
};

// r_i += -A h |v_i| dt f_i grad C_i (length at most 0.1 dx) for every fluid particle with div r_i at or
// above the surface threshold; with correction "taylor" also phi_i += delta r_i . grad phi_i, with
// "taylor_volume" besides rho_i -= rho_i div(delta r)_i, which needs `cells` (the list the gradients
// were gathered with) and uses g's shift scratch.
ShiftSummary shift_particles(ParticleSet& ps, ConcentrationGradients& g, const SolverSettings& s, double dt,
                             const CellList* cells = nullptr);

}  // namespace hydrojump::sph
