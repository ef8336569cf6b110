#include "sph/open_boundaries.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace hydrojump::sph {
namespace {

constexpr auto inflow_code = static_cast<std::uint8_t>(ParticleType::inflow);
constexpr auto outflow_code = static_cast<std::uint8_t>(ParticleType::outflow);
constexpr auto fluid_code = static_cast<std::uint8_t>(ParticleType::fluid);

// A buffer particle moves horizontally at the buffer's velocity u_b: x += u_b dt, v = (u_b, 0), and
// its integrator state follows (the integrators leave buffer particles alone).
void move_with_buffer(ParticleSet& particles, Eigen::Index i, double u_b, double dt) {
  particles.x[i] += u_b * dt;
  particles.u[i] = particles.u_old[i] = u_b;
  particles.w[i] = particles.w_old[i] = 0.0;
  particles.x_old[i] = particles.x[i];
  particles.z_old[i] = particles.z[i];
}

}  // namespace

int buffer_layers(double support, double dx, int requested) {
  const int needed = static_cast<int>(std::ceil(support / dx - 1e-9)) + 1;
  if (requested == 0) return needed;
  if (requested < needed) {
    throw std::invalid_argument("open-boundary buffer of " + std::to_string(requested) +
                                " layers is thinner than the kernel support (" + std::to_string(support) +
                                " m = " + std::to_string(support / dx) + " dx): use at least " +
                                std::to_string(needed) + " layers");
  }
  return requested;
}

void remove_particles(ParticleSet& particles, const std::vector<char>& remove) {
  const Eigen::Index n = particles.size();
  Eigen::Index kept = 0;
  std::vector<Eigen::Index> keep;
  keep.reserve(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!remove[static_cast<std::size_t>(i)]) keep.push_back(i);
  }
  kept = static_cast<Eigen::Index>(keep.size());
  if (kept == n) return;
  // Gathering forwards is safe in place: keep[k] >= k.
  particles.for_each_real_array([&](Vector& v) {
    for (Eigen::Index k = 0; k < kept; ++k) v[k] = v[keep[static_cast<std::size_t>(k)]];
  });
  for (Eigen::Index k = 0; k < kept; ++k) {
    particles.id[k] = particles.id[keep[static_cast<std::size_t>(k)]];
    particles.type[k] = particles.type[keep[static_cast<std::size_t>(k)]];
  }
  particles.resize(kept);
}

Eigen::Index remove_retired(ParticleSet& particles) {
  constexpr auto retired = static_cast<std::uint8_t>(ParticleType::retired);
  std::vector<char> remove(static_cast<std::size_t>(particles.size()), 0);
  Eigen::Index count = 0;
  for (Eigen::Index i = 0; i < particles.size(); ++i) {
    if (particles.type[i] != retired) continue;
    remove[static_cast<std::size_t>(i)] = 1;
    ++count;
  }
  if (count > 0) remove_particles(particles, remove);
  return count;
}

InflowBuffer::InflowBuffer(const cases::InflowBoundary& inflow, double bed_z, const BufferParameters& params)
    : x_in_(inflow.x_m),
      bed_z_(bed_z),
      dx_(params.dx),
      gravity_(params.gravity),
      layers_(buffer_layers(params.support, params.dx, params.layers)),
      eos_(params.eos) {
  if (!(dx_ > 0.0) || !(inflow.depth_m > 0.0) || !(inflow.velocity_m_s > 0.0)) {
    throw std::invalid_argument("inflow buffer: depth, velocity and particle spacing must be positive");
  }
  rows_ = cases::inflow_buffer_rows(inflow.depth_m, dx_);
  if (rows_ < 2) {
    throw std::invalid_argument("inflow buffer: the inflow depth " + std::to_string(inflow.depth_m) +
                                " m is resolved by fewer than 2 particle rows at dx = " + std::to_string(dx_) +
                                " m");
  }
  surface_z_ = bed_z_ + rows_ * dx_;
  // U_b = q / (N dx): the buffer carries exactly the spec's discharge.
  velocity_ = inflow.depth_m * inflow.velocity_m_s / (rows_ * dx_);
  mass_ = eos_.rho0 * dx_ * dx_;
}

void InflowBuffer::create(ParticleSet& particles, std::int64_t& next_id) const {
  const Eigen::Index first = particles.size();
  particles.resize(first + static_cast<Eigen::Index>(rows_) * layers_);
  Eigen::Index i = first;
  for (int layer = 0; layer < layers_; ++layer) {
    for (int row = 0; row < rows_; ++row, ++i) {
      const double x = x_in_ - (layer + 0.5) * dx_;
      const double z = bed_z_ + (row + 0.5) * dx_;
      // rho = rho0 (1 + rho0 g (z_s - z)/B)^(1/7)
      const double rho = eos_.hydrostatic_density(gravity_, surface_z_ - z);
      particles.assign(i, ParticleType::inflow, x, z, rho, mass_, next_id++);
      particles.u[i] = particles.u_old[i] = velocity_;
      particles.p[i] = eos_.pressure(rho);
    }
  }
}

// x_k += U_b dt for the buffer; a particle past x_in becomes fluid and a new one enters at
// x_k - layers dx with u = U_b, rho = rho0 (1 + rho0 g (z_s - z)/B)^(1/7). Returns the mass injected,
// one particle mass per conversion (rate rho0 N dx U_b = rho0 q).
double InflowBuffer::advance(ParticleSet& particles, double dt, std::int64_t& next_id) {
  const Eigen::Index n = particles.size();
  const double depth_span = layers_ * dx_;
  std::int64_t converted = 0;
  std::vector<Eigen::Index> refill;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (particles.type[i] != inflow_code) continue;
    move_with_buffer(particles, i, velocity_, dt);
    if (particles.x[i] >= x_in_) {
      // Crossed the inflow section: it becomes fluid; a new buffer particle takes its place upstream.
      particles.type[i] = fluid_code;
      refill.push_back(i);
      ++converted;
    } else {
      const double rho = eos_.hydrostatic_density(gravity_, surface_z_ - particles.z[i]);
      particles.rho[i] = particles.rho_old[i] = rho;
      particles.p[i] = eos_.pressure(rho);
    }
  }
  if (!refill.empty()) {
    particles.resize(n + static_cast<Eigen::Index>(refill.size()));
    Eigen::Index j = n;
    for (const Eigen::Index i : refill) {
      const double z = particles.z[i];
      const double rho = eos_.hydrostatic_density(gravity_, surface_z_ - z);
      particles.assign(j, ParticleType::inflow, particles.x[i] - depth_span, z, rho, mass_, next_id++);
      particles.u[j] = particles.u_old[j] = velocity_;
      particles.p[j] = eos_.pressure(rho);
      ++j;
    }
  }
  totals_.particles_in += converted;
  const double mass = static_cast<double>(converted) * mass_;
  totals_.mass_in += mass;
  return mass;
}

OutflowBuffer::OutflowBuffer(const cases::OutflowBoundary& outflow, double bed_z, const BufferParameters& params,
                             double discharge_m2_s)
    : x_out_(outflow.x_m),
      bed_z_(bed_z),
      dx_(params.dx),
      level_z_(bed_z + outflow.tailwater_depth_m),
      gravity_(params.gravity),
      layers_(buffer_layers(params.support, params.dx, params.layers)),
      eos_(params.eos) {
  if (!(outflow.tailwater_depth_m > 0.0)) throw std::invalid_argument("outflow buffer: tailwater depth must be positive");
  absorbing_ = params.outflow == OutflowCondition::absorbing;
  discharge_ = discharge_m2_s;
}

// y_t = depth (and so U_t = q / y_t)
void OutflowBuffer::set_target_depth(double depth_m) {
  if (!(depth_m > 0.0)) throw std::invalid_argument("outflow buffer: the target depth must be positive");
  level_z_ = bed_z_ + depth_m;
}

// The outlet state of the absorbing condition from the strip's depth h and mean velocity u:
//   R+ = u + 2 sqrt(g h)   (leaving the basin),   R- = U_t - 2 sqrt(g y_t)   (imposed),
//   sqrt(g h_B) = (R+ - R-) / 4,   u_B = (R+ + R-) / 2,   both >= 0.
OutflowBuffer::CharacteristicOutlet OutflowBuffer::characteristic_outlet(double strip_depth_m, double strip_velocity_m_s,
                                                                         double target_depth_m) const {
  const double leaving = strip_velocity_m_s + 2.0 * std::sqrt(gravity_ * std::max(0.0, strip_depth_m));
  const double imposed = discharge_ / target_depth_m - 2.0 * std::sqrt(gravity_ * target_depth_m);
  const double celerity = std::max(0.0, 0.25 * (leaving - imposed));
  return {celerity * celerity / gravity_, std::max(0.0, 0.5 * (leaving + imposed))};
}

// Fluid past x_out joins the buffer; the buffer moves at u_b (hydrostatic_level: the depth-averaged u
// upstream, >= 0; absorbing: u_B of the characteristic outlet) with the hydrostatic density of its
// level (hydrostatic_level: y_t; absorbing: h_B); particles layers dx past x_out, or entering above the
// level (hydrostatic_level: y_t + dx/2; absorbing, spray only: max(h, h_B) + 2 dx), are removed:
// retired (ParticleSet::retire), for the solver to drop at its next neighbour search. Returns the
// mass removed.
double OutflowBuffer::advance(ParticleSet& particles, double dt) {
  const Eigen::Index n = particles.size();
  const double x_end = x_out_ + layers_ * dx_;
  const double strip = layers_ * dx_;
  // Depth-averaged velocity of the fluid strip just upstream of x_out (zero-gradient outflow).
  double momentum = 0.0, mass = 0.0;
  double volume = 0.0;  // of the same strip, for the absorbing condition's depth
  for (Eigen::Index i = 0; i < n; ++i) {
    if (particles.type[i] == fluid_code && particles.x[i] < x_out_ && particles.x[i] >= x_out_ - strip) {
      momentum += particles.mass[i] * particles.u[i];
      mass += particles.mass[i];
      volume += particles.mass[i] / particles.rho[i];
    }
  }
  const double u_strip = mass > 0.0 ? momentum / mass : 0.0;
  double u_out = std::max(0.0, u_strip);
  double level_z = level_z_;  // the level the buffer's pressure refers to
  double spill_z = level_z_ + 0.5 * dx_;
  if (absorbing_ && mass > 0.0) {
    const double strip_depth = volume / strip;  // h, the strip's mean depth
    const CharacteristicOutlet b = characteristic_outlet(strip_depth, u_strip, level_z_ - bed_z_);
    u_out = b.velocity_m_s;
    level_z = bed_z_ + b.depth_m;
    spill_z = bed_z_ + std::max(b.depth_m, strip_depth) + 2.0 * dx_;
  }

  std::int64_t removed = 0;
  double removed_mass = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto t = particles.type[i];
    if (t == fluid_code && particles.x[i] >= x_out_) {
      particles.type[i] = outflow_code;
      // Water arriving above the tailwater level spills: removed at once (level control).
      if (particles.z[i] > spill_z) {
        ++removed;
        removed_mass += particles.mass[i];
        particles.retire(i);
        continue;
      }
    } else if (t != outflow_code) {
      continue;
    }
    move_with_buffer(particles, i, u_out, dt);
    if (particles.x[i] >= x_end) {
      ++removed;
      removed_mass += particles.mass[i];
      particles.retire(i);
      continue;
    }
    // rho = rho0 (1 + rho0 g (z_level - z)/B)^(1/7), never below rho0 above the level
    const double rho = eos_.hydrostatic_density(gravity_, std::max(0.0, level_z - particles.z[i]));
    particles.rho[i] = particles.rho_old[i] = rho;
    particles.p[i] = eos_.pressure(rho);
  }
  totals_.particles_out += removed;
  totals_.mass_out += removed_mass;
  return removed_mass;
}

BufferParameters buffer_parameters(const SolverSettings& settings) {
  BufferParameters p;
  p.dx = settings.dx;
  p.support = settings.support();
  p.eos = settings.eos;
  p.gravity = std::abs(settings.body_force_z);
  p.layers = settings.open.layers;
  p.inflow = settings.open.inflow;
  p.outflow = settings.open.outflow;
  p.tailgate_height = settings.open.tailgate_height;
  p.level_at_section = settings.open.level_at_section;
  p.level_section_x = settings.open.level_section_x;
  p.level_time = settings.open.level_time;
  return p;
}

std::int64_t next_particle_id(const ParticleSet& particles) {
  return particles.size() == 0 ? 0 : particles.id.maxCoeff() + 1;
}

OpenBoundaries OpenBoundaries::from_geometry(const cases::CaseGeometry& geometry, const BufferParameters& params) {
  OpenBoundaries out;
  for (const auto& in : geometry.inflows) {
    if (params.inflow == InflowCondition::piston) out.crossings_.emplace_back(in.x_m);
    else out.inflows_.emplace_back(in, geometry.bed.elevation(in.x_m), params);
  }
  const double discharge = cases::inflow_discharge(geometry);
  out.buffer_length_ = buffer_layers(params.support, params.dx, params.layers) * params.dx;
  for (const auto& o : geometry.outflows) {
    if (params.outflow == OutflowCondition::tailgate)
      out.tailgates_.emplace_back(o, geometry.bed.elevation(o.x_m), params.tailgate_height, out.buffer_length_);
    else
      out.outflows_.emplace_back(o, geometry.bed.elevation(o.x_m), params, discharge);
  }
  if (params.level_at_section && !out.outflows_.empty())
    out.level_control_.emplace(params.level_section_x, geometry.outflows.front().tailwater_depth_m, params.level_time,
                               2.0 * params.dx);
  return out;
}

void OpenBoundaries::start(const ParticleSet& particles) {
  for (auto& crossing : crossings_) crossing.start(particles);
}

void OpenBoundaries::forget_removed(const std::vector<double>& x, const std::vector<double>& mass) {
  for (auto& crossing : crossings_)
    for (std::size_t k = 0; k < x.size(); ++k) crossing.forget_removed(x[k], mass[k]);
}

void OpenBoundaries::create(ParticleSet& particles) const {
  std::int64_t next_id = next_particle_id(particles);
  for (const auto& in : inflows_) in.create(particles, next_id);
}

OpenBoundaryTotals OpenBoundaries::advance(ParticleSet& particles, double t, double dt) {
  OpenBoundaryTotals step;
  if (empty()) return step;
  std::int64_t next_id = next_particle_id(particles);
  for (auto& in : inflows_) step.mass_in += in.advance(particles, dt, next_id);
  for (auto& crossing : crossings_) step.mass_in += crossing.advance(particles);
  for (auto& o : outflows_) step.mass_out += o.advance(particles, dt);
  for (auto& gate : tailgates_) step.mass_out += gate.advance(particles);
  if (level_control_) {
    if (const auto depth = level_control_->update(particles, t, dt, outflow_target_depth()))
      set_outflow_target_depth(*depth);
  }
  return step;
}

double OpenBoundaries::outflow_target_depth() const {
  return outflows_.empty() ? 0.0 : outflows_.front().target_depth();
}

void OpenBoundaries::set_outflow_target_depth(double depth_m) {
  for (auto& o : outflows_) o.set_target_depth(depth_m);
}

double OpenBoundaries::mass_in() const {
  double m = 0.0;
  for (const auto& in : inflows_) m += in.totals().mass_in;
  for (const auto& crossing : crossings_) m += crossing.mass_in();
  return m;
}

double OpenBoundaries::mass_out() const {
  double m = 0.0;
  for (const auto& o : outflows_) m += o.totals().mass_out;
  for (const auto& gate : tailgates_) m += gate.mass_removed();
  return m;
}


}  // namespace hydrojump::sph
