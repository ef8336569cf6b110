#include "compare/sampling.hpp"

#include <algorithm>
#include <stdexcept>

#include "compare/sph_kernel.hpp"
#include "sph/particles.hpp"

namespace hydrojump::compare {

double simpson(const std::vector<double>& f, double spacing) {
  const std::size_t n = f.size();
  if (n < 3 || n % 2 == 0) throw std::invalid_argument("simpson: need an odd number (>= 3) of samples");
  double s = f.front() + f.back();
  for (std::size_t k = 1; k + 1 < n; ++k) s += (k % 2 == 1 ? 4.0 : 2.0) * f[k];
  return s * spacing / 3.0;
}

// Linear interpolation of a profile f(z) given at increasing z (clamped at the ends).
static double profile_at(const std::vector<double>& z, const std::vector<double>& f, double zq) {
  if (z.empty()) return not_a_number;
  if (zq <= z.front()) return f.front();
  if (zq >= z.back()) return f.back();
  const auto it = std::upper_bound(z.begin(), z.end(), zq);
  const std::size_t k = static_cast<std::size_t>(it - z.begin());
  const double t = (zq - z[k - 1]) / (z[k] - z[k - 1]);
  return f[k - 1] + t * (f[k] - f[k - 1]);
}

// u at height zq from the water points of a profile (chi_k = 1 water, 0 void): linear between two water
// points; from the highest water point at or below zq when the interval holding zq has a void end;
// NaN when there is no water at or below zq.
static double near_surface_velocity(const std::vector<double>& z, const std::vector<double>& u,
                                    const std::vector<double>& chi, double zq) {
  if (z.empty()) return not_a_number;
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(z.begin(), z.end(), zq) - z.begin());
  // zq lies in [z[k-1], z[k]) (k = 0: below the first point, k = n: at or above the last)
  const bool lower_water = k > 0 && chi[k - 1] > 0.0;
  const bool upper_water = k < z.size() && chi[k] > 0.0;
  if (lower_water && upper_water) return profile_at(z, u, zq);
  if (k == 0) return upper_water ? u.front() : not_a_number;
  for (std::size_t j = k; j-- > 0;) {
    if (chi[j] > 0.0) return u[j];
  }
  return not_a_number;
}

void integrate_column(ColumnSample& c, double gravity) {
  if (!c.wet() || c.z.size() < 3) return;
  const double h = c.depth_m;
  const std::size_t n = c.z.size();
  const double dz = h / static_cast<double>(n - 1);
  // chi_k = 0 in a void (c < 0.5), except at the surface point and within bed_exemption_m of the bed
  std::vector<double> chi(n, 1.0);
  bool has_void = false;
  if (c.fraction.size() == n) {
    for (std::size_t k = 0; k + 1 < n; ++k) {
      if (c.z[k] - c.z_bed_m < c.bed_exemption_m || c.fraction[k] >= 0.5) continue;
      chi[k] = 0.0;
      has_void = true;
    }
  }
  // Simpson without voids (exact for cubics). With a void, interval by interval: the trapezoidal rule
  // over water intervals, nothing over void ones, and over an interval with one edge of a void the
  // water part up to the c = 0.5 crossing (linear in c) times f at its water end.
  std::vector<double> wet_part(n - 1, 1.0);  // share of each interval that is water
  if (has_void) {
    for (std::size_t k = 0; k + 1 < n; ++k) {
      if (chi[k] == chi[k + 1]) { wet_part[k] = chi[k]; continue; }
      const double c0 = c.fraction[k], c1 = c.fraction[k + 1];
      double t = std::abs(c1 - c0) > 1e-12 ? (0.5 - c0) / (c1 - c0) : 0.5;  // crossing at z_k + t dz
      if (!(t >= 0.0 && t <= 1.0)) t = 0.5;  // an exempt end (surface, bed) with c < 0.5
      wet_part[k] = chi[k] > 0.0 ? t : 1.0 - t;
    }
  }
  auto integral = [&](const std::vector<double>& f) {
    if (!has_void) return simpson(f, dz);
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < n; ++k) {
      if (chi[k] > 0.0 && chi[k + 1] > 0.0) sum += 0.5 * (f[k] + f[k + 1]);
      else if (chi[k] > 0.0) sum += wet_part[k] * f[k];
      else if (chi[k + 1] > 0.0) sum += wet_part[k] * f[k + 1];
    }
    return sum * dz;
  };
  // (integral() never reads f at a void point, so the powers of u need no mask)
  std::vector<double> u2(n), u3(n);
  double u_max = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    u2[k] = c.u[k] * c.u[k];
    u3[k] = u2[k] * c.u[k];
    if (chi[k] > 0.0) u_max = std::max(u_max, c.u[k]);
  }
  c.water = chi;
  // h_w = int chi dz;  void fraction = 1 - h_w / h
  c.void_fraction = std::clamp(1.0 - integral(chi) / h, 0.0, 1.0);
  // q = int chi u dz
  c.discharge_m2_s = integral(c.u);
  // U = q / h
  c.mean_velocity_m_s = c.discharge_m2_s / h;
  c.max_velocity_m_s = u_max;
  // u_s = u(eta - 0.1 h), from water only: when that height falls on an interval with a void end, the
  // highest water point at or below it (a void's interpolated velocity is not the flow's).
  c.near_surface_velocity_m_s = near_surface_velocity(c.z, c.u, chi, c.surface_z_m - 0.1 * h);
  // alpha = int chi u^3 dz / (U^3 h)
  const double ubar3 = c.mean_velocity_m_s * c.mean_velocity_m_s * c.mean_velocity_m_s;
  c.energy_coefficient = std::abs(ubar3) > 1e-30 ? integral(u3) / (ubar3 * h) : not_a_number;
  // E = z_b + h + alpha U^2 / (2 g);  with U = 0 the kinetic term is 0 whatever alpha is.
  const double kinetic = std::isfinite(c.energy_coefficient)
                             ? c.energy_coefficient * c.mean_velocity_m_s * c.mean_velocity_m_s /
                                   (2.0 * gravity)
                             : 0.0;
  c.specific_energy_m = c.z_bed_m + h + kinetic;
  // beta = int chi u^2 dz / (U^2 h)
  const double ubar2 = c.mean_velocity_m_s * c.mean_velocity_m_s;
  const double u2_integral = integral(u2);
  c.momentum_coefficient = ubar2 > 1e-30 ? u2_integral / (ubar2 * h) : not_a_number;
  // M = h^2/2 + beta q^2/(g h) = h^2/2 + int chi u^2 dz / g  (the same, and defined when U = 0)
  c.specific_force_m2 = 0.5 * h * h + u2_integral / gravity;
}

static void check_points(int n_points) {
  if (n_points < 3 || n_points % 2 == 0)
    throw std::invalid_argument("column sampling: the number of profile points must be odd and >= 3, got " +
                                std::to_string(n_points));
}

// ------------------------------------------------------------------------------------------- SPH --
namespace {

class SphSampler final : public FrameSampler {
 public:
  SphSampler(const ParticleFrame& f, const SphSamplingSettings& s)
      : kernel_(s.kernel, s.smoothing_length_m), scheme_(s.scheme), time_(f.time_s), dx_(s.particle_spacing_m),
        z_ceiling_(s.z_ceiling_m) {
    const std::size_t n = f.x.size();
    if (f.z.size() != n || f.u.size() != n || f.w.size() != n || f.type.size() != n ||
        f.density.size() != n || (!f.pressure.empty() && f.pressure.size() != n) ||
        (!f.mass.empty() && f.mass.size() != n))
      throw std::invalid_argument("SPH frame at t = " + std::to_string(f.time_s) +
                                  " s: particle arrays have different lengths");
    if (!(s.particle_spacing_m > 0.0))
      throw std::invalid_argument("SPH sampling: particle spacing must be > 0");
    volume_.resize(n);
    const double m0 = s.reference_density_kg_m3 * s.particle_spacing_m * s.particle_spacing_m;
    for (std::size_t j = 0; j < n; ++j) {
      const double m = f.mass.empty() ? m0 : f.mass[j];
      // V_j = m_j / rho_j
      volume_[j] = f.density[j] > 0.0 ? m / f.density[j] : 0.0;
    }
    // Water carries the velocity: fluid and the inflow/outflow buffers; walls (fixed and moving) only
    // count in the fluid fraction.
    using sph::ParticleType;
    const auto is = [](int t, ParticleType type) { return t == static_cast<int>(type); };
    fluid_.assign(f.type.begin(), f.type.end());
    for (auto& t : fluid_)
      t = (is(t, ParticleType::fluid) || is(t, ParticleType::inflow) || is(t, ParticleType::outflow)) ? 1 : 0;
    u_ = f.u;
    w_ = f.w;
    p_ = f.pressure.empty() ? std::vector<double>(n, not_a_number) : f.pressure;
    cloud_ = PointCloud2D(f.x, f.z, kernel_.support_radius());
    // Highest particle per x strip of width h, for the start of the surface scan.
    if (n > 0) {
      x0_ = *std::min_element(f.x.begin(), f.x.end());
      const double x1 = *std::max_element(f.x.begin(), f.x.end());
      strip_ = kernel_.smoothing_length();
      strip_top_.assign(static_cast<std::size_t>((x1 - x0_) / strip_) + 1,
                        -std::numeric_limits<double>::infinity());
      for (std::size_t j = 0; j < n; ++j) {
        auto& top = strip_top_[static_cast<std::size_t>((f.x[j] - x0_) / strip_)];
        top = std::max(top, f.z[j]);
      }
    }
  }

  double time_s() const override { return time_; }

  // c(x) = sum_j V_j W(|x - x_j|, h) over all particles
  double fraction(double x, double z) const {
    double c = 0.0;
    cloud_.for_each_within(x, z, kernel_.support_radius(),
                           [&](std::size_t j, double, double, double r) { c += volume_[j] * kernel_(r); });
    return c;
  }

  Stencil stencil(double x, double z) const {
    StencilBuilder b;
    cloud_.for_each_within(x, z, kernel_.support_radius(), [&](std::size_t j, double dx, double dz, double r) {
      if (fluid_[j]) b.add(j, dx, dz, volume_[j] * kernel_(r));
    });
    return b.build(scheme_, kernel_.smoothing_length());
  }

  PointSample sample_point(double x, double z) const override {
    PointSample s;
    s.fraction = fraction(x, z);
    const Stencil st = stencil(x, z);
    if (!st.empty()) {
      s.u = st.apply(u_);
      s.w = st.apply(w_);
      s.pressure = st.apply(p_);
    }
    return s;
  }

  double column_top(double x) const {
    double top = -std::numeric_limits<double>::infinity();
    if (strip_top_.empty()) return top;
    const double r = kernel_.support_radius();
    const long i0 = static_cast<long>(std::floor((x - r - x0_) / strip_));
    const long i1 = static_cast<long>(std::floor((x + r - x0_) / strip_));
    for (long i = std::max(0L, i0); i <= i1 && i < static_cast<long>(strip_top_.size()); ++i)
      top = std::max(top, strip_top_[static_cast<std::size_t>(i)]);
    return std::min(top + r, z_ceiling_);
  }

  ColumnSample sample_column(double x, double z_bed, int n_points, double gravity) const override {
    check_points(n_points);
    ColumnSample c;
    c.x_m = x;
    c.z_bed_m = z_bed;
    const double top = column_top(x);
    if (!(top > z_bed)) return c;
    // Downward scan in steps of h/4 recording the wet runs (c >= 0.5); the surface is the top of the
    // highest run at least 1.5 dx thick (thinner runs are droplets or spray above the water), or of
    // the thickest run if none is; then bisection on [z_wet, z_dry] of that run.
    struct WetRun { double z_dry, z_wet, z_low; };
    std::vector<WetRun> runs;
    const double step = 0.25 * kernel_.smoothing_length();
    double z_prev = top;
    bool wet_prev = false;
    double integral = 0.0;  // int_{z_b}^{top} c dz by the trapezoidal rule on the scan points
    double c_prev = fraction(x, top);
    for (double z = top - step;; z -= step) {
      const double zz = std::max(z, z_bed);
      const double cz = fraction(x, zz);
      integral += 0.5 * (cz + c_prev) * (z_prev - zz);
      const bool wet = cz >= 0.5;
      if (wet && !wet_prev) runs.push_back({z_prev, zz, zz});
      if (wet) runs.back().z_low = zz;
      c_prev = cz;
      z_prev = zz;
      wet_prev = wet;
      if (zz <= z_bed) break;
    }
    c.surface_from_fraction_m = z_bed + integral;
    if (runs.empty()) return c;  // dry column
    const WetRun* chosen = nullptr;
    for (const auto& r : runs)
      if (r.z_wet - r.z_low + step >= 1.5 * dx_) { chosen = &r; break; }
    if (!chosen)
      chosen = &*std::max_element(runs.begin(), runs.end(), [](const WetRun& a, const WetRun& b) {
        return a.z_wet - a.z_low < b.z_wet - b.z_low;
      });
    {
      double lo = chosen->z_wet, hi = chosen->z_dry;  // c(lo) >= 0.5 > c(hi)
      while (hi - lo > 1e-7) {
        const double mid = 0.5 * (lo + hi);
        (fraction(x, mid) >= 0.5 ? lo : hi) = mid;
      }
      c.surface_z_m = 0.5 * (lo + hi);
    }
    c.depth_m = c.surface_z_m - z_bed;
    if (!(c.depth_m > 0.0)) { c.surface_z_m = not_a_number; return c; }
    fill_profile(c, n_points);
    integrate_column(c, gravity);
    return c;
  }

  void fill_profile(ColumnSample& c, int n_points) const {
    const std::size_t n = static_cast<std::size_t>(n_points);
    c.z.resize(n); c.u.resize(n); c.w.resize(n); c.pressure.resize(n); c.fraction.resize(n);
    c.bed_exemption_m = 0.5 * dx_;  // c counts the wall particles: ~1 at a wetted bed, ~1/2 at a dry one
    for (std::size_t k = 0; k < n; ++k) {
      const double z = c.z_bed_m + c.depth_m * static_cast<double>(k) / static_cast<double>(n - 1);
      const Stencil st = stencil(c.x_m, z);
      c.z[k] = z;
      c.fraction[k] = fraction(c.x_m, z);
      c.u[k] = st.empty() ? 0.0 : st.apply(u_);
      c.w[k] = st.empty() ? 0.0 : st.apply(w_);
      c.pressure[k] = st.empty() ? not_a_number : st.apply(p_);
    }
  }

 private:
  SphKernel2D kernel_;
  InterpolationScheme scheme_;
  double time_ = 0.0;
  double dx_ = 0.0;
  double z_ceiling_ = 0.0;
  PointCloud2D cloud_;
  std::vector<double> volume_, u_, w_, p_;
  std::vector<int> fluid_;
  double x0_ = 0.0, strip_ = 1.0;
  std::vector<double> strip_top_;
};

// ------------------------------------------------------------------------------------------- VOF --
class VofSampler final : public FrameSampler {
 public:
  VofSampler(const CellFrame& f, InterpolationScheme scheme) : f_(f), scheme_(scheme) {
    const std::size_t n = f.xc.size();
    for (const auto* a : {&f.zc, &f.x_lo, &f.x_hi, &f.z_lo, &f.z_hi, &f.alpha, &f.u, &f.w})
      if (a->size() != n)
        throw std::invalid_argument("VOF frame at t = " + std::to_string(f.time_s) +
                                    " s: cell arrays have different lengths");
    if (f_.pressure.size() != n) f_.pressure.assign(n, not_a_number);
    if (n == 0) return;
    double max_size = 0.0, min_width = std::numeric_limits<double>::infinity();
    area_.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      const double dx = f.x_hi[j] - f.x_lo[j], dz = f.z_hi[j] - f.z_lo[j];
      area_[j] = dx * dz;
      max_size = std::max({max_size, dx, dz});
      min_width = std::min(min_width, dx);
    }
    cloud_ = PointCloud2D(f.xc, f.zc, 1.6 * max_size);
    // x bins: every cell is listed in each bin its x-range overlaps.
    xmin_ = *std::min_element(f.x_lo.begin(), f.x_lo.end());
    xmax_ = *std::max_element(f.x_hi.begin(), f.x_hi.end());
    xbin_ = std::max(min_width, (xmax_ - xmin_) / 200000.0);
    const std::size_t nb = static_cast<std::size_t>((xmax_ - xmin_) / xbin_) + 1;
    xbins_.assign(nb, {});
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t b0 = bin_of(f.x_lo[j]), b1 = bin_of(f.x_hi[j]);
      for (std::size_t b = b0; b <= b1; ++b) xbins_[b].push_back(j);
    }
  }

  double time_s() const override { return f_.time_s; }

  std::size_t bin_of(double x) const {
    const double t = std::clamp((x - xmin_) / xbin_, 0.0, static_cast<double>(xbins_.size() - 1));
    return static_cast<std::size_t>(t);
  }

  // Cells cut by the vertical line at x, by increasing centre height.
  std::vector<std::size_t> column_cells(double x) const {
    std::vector<std::size_t> cells;
    if (xbins_.empty() || x < xmin_ || x > xmax_) return cells;
    for (std::size_t j : xbins_[bin_of(x)]) {
      const bool inside = (f_.x_lo[j] <= x && x < f_.x_hi[j]) || (x == xmax_ && f_.x_hi[j] == xmax_);
      if (inside) cells.push_back(j);
    }
    std::sort(cells.begin(), cells.end(), [&](std::size_t a, std::size_t b) { return f_.zc[a] < f_.zc[b]; });
    return cells;
  }

  // Local cell size at (x, z): the larger side of the column cell containing z (or the nearest one).
  double local_size(const std::vector<std::size_t>& column, double x, double z) const {
    std::size_t best = f_.xc.size();
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t j : column) {
      const double d = z < f_.z_lo[j] ? f_.z_lo[j] - z : (z > f_.z_hi[j] ? z - f_.z_hi[j] : 0.0);
      if (d < best_d) { best_d = d; best = j; }
    }
    if (best == f_.xc.size()) best = cloud_.nearest(x, z, std::numeric_limits<double>::infinity());
    if (best == f_.xc.size()) return 0.0;
    return std::max(f_.x_hi[best] - f_.x_lo[best], f_.z_hi[best] - f_.z_lo[best]);
  }

  Stencil stencil(double x, double z, double size, bool water_weighted) const {
    StencilBuilder b;
    const double radius = 1.6 * size;
    cloud_.for_each_within(x, z, radius, [&](std::size_t j, double dx, double dz, double r) {
      const double w = area_[j] * wendland_weight(r, radius);
      b.add(j, dx, dz, water_weighted ? w * std::clamp(f_.alpha[j], 0.0, 1.0) : w);
    });
    Stencil s = b.build(scheme_, size);
    if (s.empty() && water_weighted) return stencil(x, z, size, false);
    return s;
  }

  PointSample sample_point(double x, double z) const override {
    PointSample s;
    const double size = local_size(column_cells(x), x, z);
    if (!(size > 0.0)) return s;
    const Stencil a = stencil(x, z, size, false);
    if (a.empty()) return s;
    s.fraction = a.apply(f_.alpha);
    const Stencil st = stencil(x, z, size, true);
    s.u = st.apply(f_.u);
    s.w = st.apply(f_.w);
    s.pressure = st.apply(f_.pressure);
    return s;
  }

  ColumnSample sample_column(double x, double z_bed, int n_points, double gravity) const override {
    check_points(n_points);
    ColumnSample c;
    c.x_m = x;
    c.z_bed_m = z_bed;
    const std::vector<std::size_t> col = column_cells(x);
    if (col.empty()) return c;
    // eta_int = z_b + sum_k alpha_k dz_k  (the water depth int alpha dz put on the bed)
    double integral = 0.0;
    for (std::size_t j : col) integral += std::clamp(f_.alpha[j], 0.0, 1.0) * (f_.z_hi[j] - f_.z_lo[j]);
    c.surface_from_fraction_m = z_bed + integral;
    // Highest alpha = 0.5 crossing of the piecewise-linear alpha through the cell centres, on the
    // highest run of cells with alpha >= 0.5 that is at least 1.5 cells thick (a thinner run is a
    // droplet or spray above the water); the thickest run if none is.
    std::size_t best_top = col.size(), thickest_top = col.size();
    double thickest = -1.0;
    for (std::size_t k = col.size(); k-- > 0;) {
      if (f_.alpha[col[k]] < 0.5 || (k + 1 < col.size() && f_.alpha[col[k + 1]] >= 0.5)) continue;
      std::size_t low = k;  // k is the top cell of a run; find its bottom
      while (low > 0 && f_.alpha[col[low - 1]] >= 0.5) --low;
      const double thickness = f_.z_hi[col[k]] - f_.z_lo[col[low]];
      const double cell = f_.z_hi[col[k]] - f_.z_lo[col[k]];
      if (thickness > thickest) { thickest = thickness; thickest_top = k; }
      if (thickness >= 1.5 * cell) { best_top = k; break; }
    }
    if (best_top == col.size()) best_top = thickest_top;
    if (best_top < col.size()) {
      const std::size_t k = best_top, j = col[k];
      if (k + 1 == col.size()) {
        c.surface_z_m = f_.z_hi[j];  // water up to the top of the mesh
      } else {
        const std::size_t above = col[k + 1];
        const double a0 = f_.alpha[j], a1 = f_.alpha[above];
        c.surface_z_m = f_.zc[j] + (a0 - 0.5) / (a0 - a1) * (f_.zc[above] - f_.zc[j]);
      }
    }
    if (!std::isfinite(c.surface_z_m)) return c;
    c.depth_m = c.surface_z_m - z_bed;
    if (!(c.depth_m > 0.0)) { c.surface_z_m = not_a_number; c.depth_m = not_a_number; return c; }
    const std::size_t n = static_cast<std::size_t>(n_points);
    // a partly solid bed cell (staircase) holds water at alpha < 0.5: no void within one cell of the bed
    c.bed_exemption_m = local_size(col, x, z_bed);
    // alpha along the column as the surface search sees it: linear between the cell centres
    std::vector<double> zc_col(col.size()), alpha_col(col.size());
    for (std::size_t k = 0; k < col.size(); ++k) {
      zc_col[k] = f_.zc[col[k]];
      alpha_col[k] = std::clamp(f_.alpha[col[k]], 0.0, 1.0);
    }
    c.z.resize(n); c.u.resize(n); c.w.resize(n); c.pressure.resize(n); c.fraction.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double z = z_bed + c.depth_m * static_cast<double>(k) / static_cast<double>(n - 1);
      const double size = local_size(col, x, z);
      const Stencil st = stencil(x, z, size, true);
      c.z[k] = z;
      c.fraction[k] = profile_at(zc_col, alpha_col, z);
      c.u[k] = st.empty() ? 0.0 : st.apply(f_.u);
      c.w[k] = st.empty() ? 0.0 : st.apply(f_.w);
      c.pressure[k] = st.empty() ? not_a_number : st.apply(f_.pressure);
    }
    integrate_column(c, gravity);
    return c;
  }

 private:
  CellFrame f_;
  InterpolationScheme scheme_;
  std::vector<double> area_;
  PointCloud2D cloud_;
  double xmin_ = 0.0, xmax_ = 0.0, xbin_ = 1.0;
  std::vector<std::vector<std::size_t>> xbins_;
};

}  // namespace

std::unique_ptr<FrameSampler> make_sph_sampler(const ParticleFrame& frame,
                                               const SphSamplingSettings& settings) {
  return std::make_unique<SphSampler>(frame, settings);
}

std::unique_ptr<FrameSampler> make_vof_sampler(const CellFrame& frame, InterpolationScheme scheme) {
  return std::make_unique<VofSampler>(frame, scheme);
}

}  // namespace hydrojump::compare
