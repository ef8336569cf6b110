// Wall function: the turbulent wall shear stress of the log law, applied to the fluid particles next
// to a wall whose viscous terms see free slip (Launder & Spalding 1974, "The numerical computation of
// turbulent flows", Comput. Methods Appl. Mech. Eng. 3:269-289; in SPH as a wall force on the first
// particle layer, Violeau & Issa 2007, Int. J. Numer. Meth. Fluids 53:277-304).
//
// A no-slip wall resolved by particles a few millimetres apart puts the wall's whole velocity jump
// into the first particle gap, where a mixing length cannot represent the turbulent boundary layer;
// free slip takes the wall shear out altogether. The wall function keeps mDBC's slip velocity for the
// laminar and SPS terms and adds the shear stress tau_w = rho u_tau^2 that the log law gives for the
// particle's tangential velocity u_t (relative to the wall) at its distance d from the wall surface:
//
//   u_t / u_tau = ln(E d u_tau / nu) / kappa     (log layer, y+ = d u_tau / nu >= 11.53)
//   u_t / u_tau = d u_tau / nu                   (viscous sublayer, y+ < 11.53)
//
// kappa = 0.41, E = 9.8 (hydraulically smooth wall); the two laws meet at y+ = 11.53. In 2D each particle
// of the first layer (0 < d < dx) carries a wall length dx and a volume dx^2, so the stress acts as
//
//   a = -u_tau^2 / dx  t,    t = the unit tangential velocity relative to the wall,
//
// with d taken no closer to the wall than dx/4 (a particle pushed into the wall layer keeps the stress
// of a particle dx/4 away instead of the sublayer's unbounded one).
//
// Usage:
//   | spec key                   | value           | needs                                    |
//   |----------------------------|-----------------|------------------------------------------|
//   | sph.viscous_wall_condition | "wall_function" | viscosity = "laminar_sps", boundary = "mdbc" |
// Example (spec): `[sph]  viscosity = "laminar_sps"  boundary = "mdbc"  viscous_wall_condition = "wall_function"`
#pragma once

#include <algorithm>
#include <cmath>

namespace hydrojump::sph {

inline constexpr double kVonKarman = 0.41;
inline constexpr double kLogLawE = 9.8;
inline constexpr double kSublayerEdgeYPlus = 11.53;  // y+ = ln(E y+) / kappa

// u_tau of a flow with tangential speed u_t (m/s, >= 0) at distance d (m, > 0) from a smooth wall,
// kinematic viscosity nu (m^2/s): the sublayer's sqrt(nu u_t / d) where that gives y+ < 11.53, else
// the log law's root by Newton's method on g(u) = u ln(E d u / nu) / kappa - u_t.
inline double friction_velocity(double u_t, double d, double nu) {
  if (!(u_t > 0.0)) return 0.0;
  const double laminar = std::sqrt(nu * u_t / d);
  if (d * laminar / nu < kSublayerEdgeYPlus) return laminar;
  double u = laminar;  // y+ >= 11.53 here, so ln(E y+) > 0 and g is increasing from this start
  for (int k = 0; k < 50; ++k) {
    const double log_term = std::log(kLogLawE * d * u / nu);
    const double step = (u * log_term / kVonKarman - u_t) / ((log_term + 1.0) / kVonKarman);
    u -= step;
    if (std::abs(step) <= 1e-13 * u) break;
  }
  return u;
}

struct WallShearAcceleration {
  double ax = 0.0, az = 0.0;
};

// The wall shear's acceleration of a fluid particle with velocity (rel_u, rel_w) relative to the wall,
// at distance d from the wall surface along the unit wall normal (nx, nz) (pointing into the fluid),
// particle spacing dx: -u_tau^2 / dx t for 0 < d < dx (the first layer), zero farther out.
inline WallShearAcceleration wall_shear_acceleration(double rel_u, double rel_w, double nx, double nz, double d,
                                                     double dx, double nu) {
  if (!(d < dx)) return {};
  const double vn = rel_u * nx + rel_w * nz;
  const double tu = rel_u - vn * nx, tw = rel_w - vn * nz;  // tangential velocity
  const double u_t = std::hypot(tu, tw);
  if (!(u_t > 0.0)) return {};
  const double u_tau = friction_velocity(u_t, std::max(d, 0.25 * dx), nu);
  const double scale = -u_tau * u_tau / (dx * u_t);
  return {scale * tu, scale * tw};
}

}  // namespace hydrojump::sph
