#include "sph/particles.hpp"

#include <limits>

#include "sph/parallel.hpp"

namespace hydrojump::sph {

Eigen::Index ParticleSet::fluid_count() const {
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < size(); ++i) n += is_fluid(i) ? 1 : 0;
  return n;
}

double ParticleSet::water_mass() const {
  constexpr auto fluid = static_cast<std::uint8_t>(ParticleType::fluid);
  constexpr auto outflow = static_cast<std::uint8_t>(ParticleType::outflow);
  double m = 0.0;
  for (Eigen::Index i = 0; i < size(); ++i)
    if (type[i] == fluid || type[i] == outflow) m += mass[i];
  return m;
}

void ParticleSet::retire(Eigen::Index i) {
  type[i] = static_cast<std::uint8_t>(ParticleType::retired);
  mass[i] = 0.0;
  u[i] = w[i] = u_old[i] = w_old[i] = 0.0;
  ax[i] = az[i] = drho[i] = 0.0;
}

void ParticleSet::for_each_real_array(const std::function<void(Vector&)>& f) {
  for (Vector* v : {&x, &z, &u, &w, &rho, &mass, &ghost_dx, &ghost_dz, &wall_u, &wall_w, &x_old, &z_old, &u_old, &w_old,
                    &rho_old, &p, &ax, &az, &drho, &tau_xx, &tau_xz, &tau_zz, &x_search, &z_search})
    f(*v);
}

void ParticleSet::for_each_real_array(const std::function<void(const Vector&)>& f) const {
  const_cast<ParticleSet*>(this)->for_each_real_array([&](Vector& v) { f(v); });
}

void ParticleSet::resize(Eigen::Index n) {
  const Eigen::Index old = size();
  for_each_real_array([&](Vector& v) {
    v.conservativeResize(n);
    if (n > old) v.tail(n - old).setZero();
  });
  id.conservativeResize(n);
  type.conservativeResize(n);
  if (n > old) {
    id.tail(n - old).setZero();
    type.tail(n - old).setZero();
  }
  if (n != old) {
    x_search.setConstant(std::numeric_limits<double>::quiet_NaN());
    z_search.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
}

void ParticleSet::assign(Eigen::Index i, ParticleType t, double px, double pz, double density,
                         double particle_mass, std::int64_t particle_id) {
  u[i] = w[i] = u_old[i] = w_old[i] = wall_u[i] = wall_w[i] = 0.0;
  x[i] = px;
  z[i] = pz;
  rho[i] = density;
  rho_old[i] = density;
  x_old[i] = px;
  z_old[i] = pz;
  mass[i] = particle_mass;
  id[i] = particle_id;
  type[i] = static_cast<std::uint8_t>(t);
}

void ParticleSet::permute(const std::vector<int>& order) {
  const Eigen::Index n = size();
  Vector tmp(n);
  for_each_real_array([&](Vector& v) {
#pragma omp parallel for schedule(static) if (use_threads(n))
    for (Eigen::Index k = 0; k < n; ++k) tmp[k] = v[order[k]];
    v.swap(tmp);
  });
  IdVector id_tmp(n);
  TypeVector type_tmp(n);
#pragma omp parallel for schedule(static) if (use_threads(n))
  for (Eigen::Index k = 0; k < n; ++k) {
    id_tmp[k] = id[order[k]];
    type_tmp[k] = type[order[k]];
  }
  id.swap(id_tmp);
  type.swap(type_tmp);
}

}  // namespace hydrojump::sph
