// Jump metrics on hand-built sections and a synthetic longitudinal profile with known answers.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "cases/hydraulics.hpp"
#include "compare/discrepancy.hpp"
#include "compare/jump_metrics.hpp"

using namespace hydrojump::compare;

namespace {
constexpr double g = 9.81;

// The row of `quantity` in a metric table (fails the test if there is none).
MetricRow metric_row(const std::vector<MetricRow>& rows, const std::string& quantity) {
  const auto it = std::find_if(rows.begin(), rows.end(), [&](const MetricRow& r) { return r.quantity == quantity; });
  REQUIRE(it != rows.end());
  return *it;
}

// A column with a uniform velocity u over depth h on a bed at z_b.
ColumnSample uniform_column(double x, double z_b, double h, double u) {
  ColumnSample c;
  c.x_m = x;
  c.z_bed_m = z_b;
  c.surface_z_m = z_b + h;
  c.depth_m = h;
  for (int k = 0; k < 21; ++k) {
    c.z.push_back(z_b + h * k / 20.0);
    c.u.push_back(u);
    c.w.push_back(0.0);
    c.pressure.push_back(0.0);
  }
  integrate_column(c, g);
  return c;
}

ColumnStatistics as_statistics(const std::string& name, const std::string& role, const ColumnSample& c) {
  ColumnSpec spec{name, role, c.x_m, c.z_bed_m, 21};
  return column_statistics(spec, {c, c}, 21, true);
}

// Stations every 4 mm over 2 m with the time-mean surface zeta(x).
std::vector<ColumnStatistics> stations_with_surface(const std::function<double(double)>& zeta) {
  std::vector<ColumnStatistics> out;
  for (int i = 0; i <= 500; ++i) {
    ColumnStatistics s;
    s.spec = {"", "station", i * 0.004, 0.0, 21};
    s.surface.mean = zeta(s.spec.x_m);
    out.push_back(s);
  }
  return out;
}

// Sections and stations (every ds up to 2 m) of a synthetic jump: the surface y1 up to x_t, a linear
// rise to y2 over L, then y2; reverse near-surface flow over (x_t, x_t + Lr); u_max falling from u1 at
// x_t by 5 /s to 0.6 m/s.
MethodStatistics synthetic_jump(double y1, double u1, double y2, double x_t, double L, double Lr, double ds) {
  MethodStatistics m;
  m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.3, 0.0, y1, u1)));
  m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(1.6, 0.0, y2, y1 * u1 / y2)));
  const int n = static_cast<int>(std::lround(2.0 / ds));
  for (int i = 0; i <= n; ++i) {
    const double x = i * ds;
    ColumnStatistics s;
    s.spec = {"", "station", x, 0.0, 21};
    s.surface.mean = x < x_t ? y1 : (x < x_t + L ? y1 + (y2 - y1) * (x - x_t) / L : y2);
    s.near_surface_velocity.mean = (x > x_t && x < x_t + Lr) ? -0.2 : 0.5;
    s.max_velocity.mean = x < x_t ? u1 : std::max(0.6, u1 - (x - x_t) * 5.0);
    m.stations.push_back(s);
  }
  return m;
}
}  // namespace

TEST_CASE("eta of a hand-built pair of sections matches (E1 - E2)/E1", "[compare][metrics]") {
  // Run A of Ead & Rajaratnam: y1 = 25.4 mm, U1 = 2.0 m/s, y2 = 0.104 m, q = y1 U1.
  const double y1 = 0.0254, u1 = 2.0, y2 = 0.104, q = y1 * u1;
  MethodStatistics m;
  m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.1, 0.0, y1, u1)));
  m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(1.5, 0.0, y2, q / y2)));
  const double e1 = y1 + q * q / (2 * g * y1 * y1);
  const double e2 = y2 + q * q / (2 * g * y2 * y2);
  CHECK(m.sections[0].energy_coefficient.mean == Approx(1.0).margin(1e-12));
  CHECK(m.sections[0].discharge.mean == Approx(q).margin(1e-12));
  JumpInputs in{y1, u1, 0.0, g, {}};
  const JumpMetrics r = compute_jump_metrics(m, in);
  CHECK(r.e1_m == Approx(e1).epsilon(1e-12));
  CHECK(r.e2_m == Approx(e2).epsilon(1e-12));
  CHECK(r.eta == Approx((e1 - e2) / e1).epsilon(1e-12));
  CHECK(r.eta_alpha1 == Approx((e1 - e2) / e1).epsilon(1e-12));
  CHECK(r.eta_crest_depth == Approx((e1 - e2) / e1).epsilon(1e-12));
  CHECK(r.sequent_depth_m == Approx(y2).margin(1e-12));
  // The kinetic-energy coefficient enters E: a linear profile with the same q has alpha > 1.
  ColumnSample lin = uniform_column(0.1, 0.0, y1, u1);
  for (std::size_t k = 0; k < lin.u.size(); ++k) lin.u[k] = u1 * (0.5 + lin.z[k] / y1);  // mean u1
  integrate_column(lin, g);
  const double alpha = (std::pow(1.5, 4) - std::pow(0.5, 4)) / 4.0;  // int_0^1 (0.5 + s)^3 ds
  CHECK(lin.energy_coefficient == Approx(alpha).epsilon(1e-12));
  CHECK(lin.specific_energy_m == Approx(y1 + alpha * u1 * u1 / (2 * g)).epsilon(1e-12));
}

TEST_CASE("Specific force of hand-built sections: Belanger's pair balances, a drag shows", "[compare][metrics]") {
  // Run B inflow: y1 = 25.4 mm, Fr1 = 6; uniform sections at y1 and at Belanger's y2*.
  const double y1 = 0.0254, u1 = 6.0 * std::sqrt(g * y1), q = y1 * u1;
  const double y2 = hydrojump::cases::belanger_sequent_depth(y1, 6.0);
  MethodStatistics m;
  m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.1, 0.0, y1, u1)));
  m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(1.5, 0.0, y2, q / y2)));
  CHECK(m.sections[0].momentum_coefficient.mean == Approx(1.0).margin(1e-12));
  const double m1 = 0.5 * y1 * y1 + q * q / (g * y1);
  const double m2 = 0.5 * y2 * y2 + q * q / (g * y2);
  JumpInputs in{y1, u1, 0.0, g, {}};
  JumpMetrics r = compute_jump_metrics(m, in);
  CHECK(r.specific_force_upstream_m2 == Approx(m1).epsilon(1e-12));
  CHECK(r.specific_force_downstream_m2 == Approx(m2).epsilon(1e-12));
  CHECK(std::abs(r.bed_force_fraction) < 1e-9);  // Belanger: M1 = M2
  // A linear profile with the same q downstream carries more momentum (beta = 7/6 for u from U/2 to
  // 3U/2): M2 grows by (beta - 1) q^2/(g y2) and the fraction turns negative by that share of M1.
  ColumnSample lin = uniform_column(1.5, 0.0, y2, q / y2);
  for (std::size_t k = 0; k < lin.u.size(); ++k) lin.u[k] = q / y2 * (0.5 + lin.z[k] / y2);
  integrate_column(lin, g);
  const double beta = (std::pow(1.5, 3) - std::pow(0.5, 3)) / 3.0;
  CHECK(lin.momentum_coefficient == Approx(beta).epsilon(1e-12));
  m.sections[1] = as_statistics("downstream", "downstream", lin);
  r = compute_jump_metrics(m, in);
  CHECK(r.bed_force_fraction == Approx(-(beta - 1.0) * q * q / (g * y2) / m1).epsilon(1e-9));
  // A lower tailwater with the uniform profile: the bed took the difference.
  m.sections[1] = as_statistics("downstream", "downstream", uniform_column(1.5, 0.0, 0.8 * y2, q / (0.8 * y2)));
  r = compute_jump_metrics(m, in);
  const double m2_low = 0.5 * 0.64 * y2 * y2 + q * q / (g * 0.8 * y2);
  CHECK(r.bed_force_fraction == Approx((m1 - m2_low) / m1).epsilon(1e-12));
  CHECK(r.bed_force_fraction > 0.1);
}

TEST_CASE("The experiment's bed force from y1, U1 and the measured y2", "[compare][metrics]") {
  // Run B: y1 = 25.4 mm, U1 = 3.0 m/s (q = 0.0762 m^2/s), measured y2 = 0.145 m. By hand:
  // M1 = 0.0254^2/2 + 0.0762^2/(9.81 0.0254) = 0.000322580 + 0.023302752 = 0.023625332 m^2,
  // M2 = 0.145^2/2 + 0.0762^2/(9.81 0.145) = 0.0105125 + 0.004081999 = 0.014594499 m^2,
  // (M1 - M2)/M1 = 38.2252 %.
  MeasuredReference lab;
  lab.sequent_depth_m = 0.145;
  const auto bed_row = [](const MeasuredReference& reference) {
    return metric_row(metric_table(nullptr, nullptr, reference, 0.0254, 3.0, 9.81, true), "bed_force_fraction");
  };
  const MetricRow bed = bed_row(lab);
  CHECK(bed.experiment == Approx(38.2252).margin(1e-4));
  CHECK(bed.smooth_theory == 0.0);
  CHECK(std::isnan(bed.sph));
  // At Belanger's sequent depth the force balances.
  lab.sequent_depth_m = hydrojump::cases::belanger_sequent_depth(0.0254, 3.0 / std::sqrt(9.81 * 0.0254));
  CHECK(std::abs(bed_row(lab).experiment) < 1e-9);
  // Without a measured y2 there is no experimental value.
  CHECK(std::isnan(bed_row(MeasuredReference{}).experiment));
}

TEST_CASE("The smooth-bed column of the eta rows is Belanger's theory, not the study's listed value", "[compare][metrics]") {
  // Run B: y1 = 25.4 mm, U1 = 3.0 m/s. By hand: Fr1 = 3 / sqrt(9.81 0.0254) = 6.009937,
  // y2* = y1/2 (sqrt(1 + 8 Fr1^2) - 1) = 0.203556 m, E1 = 0.0254 + 9/19.62 = 0.484116 m,
  // E2* = 0.203556 + 0.0762^2 / (19.62 0.203556^2) = 0.210699 m, eta* = (E1 - E2*)/E1 = 56.4776 %.
  MeasuredReference lab;
  lab.eta_smooth_percent = 56.0;  // a listed value, rounded differently: not what the column holds
  const auto rows = metric_table(nullptr, nullptr, lab, 0.0254, 3.0, 9.81, true);
  for (const char* quantity : {"eta", "eta_alpha1", "eta_crest_depth"}) {
    INFO(quantity);
    CHECK(metric_row(rows, quantity).smooth_theory == Approx(56.4776).margin(1e-3));
  }
}

TEST_CASE("The metric table labels what the set-up held and sets the inputs-only values beside", "[compare][metrics]") {
  // Run B: y1 = 25.4 mm, U1 = 3.0 m/s, y2* = 0.203556 m (hand value above), measured y2 = 0.145 m:
  // the bed effect y2/y2* = 0.712334 in the flume; an SPH y2 of 0.15 m gives 0.736898.
  JumpMetrics sph;
  sph.sequent_depth_m = 0.15;
  sph.toe_x_m = 0.2;
  MeasuredReference lab;
  lab.sequent_depth_m = 0.145;
  const auto held = metric_table(&sph, nullptr, lab, 0.0254, 3.0, 9.81, true);
  CHECK(metric_row(held, "sequent_depth").smooth_theory == Approx(0.203556).margin(1e-6));
  CHECK(metric_row(held, "bed_effect").experiment == Approx(0.712334).margin(1e-6));
  CHECK(metric_row(held, "bed_effect").sph == Approx(0.736898).margin(1e-6));
  CHECK(metric_row(held, "bed_effect").smooth_theory == 1.0);
  // Under the toe-holding control the toe is imposed and y2, eta and the bed force are predicted.
  CHECK(metric_row(held, "toe_position").status == "imposed");
  CHECK(metric_row(held, "toe_mean_of_frames").status == "imposed");
  for (const char* q : {"sequent_depth", "bed_effect", "eta", "eta_alpha1", "eta_crest_depth", "bed_force_fraction",
                        "jump_length", "roller_length", "toe_std", "toe_trend"})
    CHECK(metric_row(held, q).status == "predicted");
  CHECK(metric_row(held, "upstream_depth").status == "input");
  // The run's water balance and steadiness are checks of the run: 1.5 % of q draining, steady.
  sph.window_imbalance = 0.015;
  sph.steady_by_means = 1.0;
  const auto checked = metric_table(&sph, nullptr, lab, 0.0254, 3.0, 9.81, true);
  CHECK(metric_row(checked, "water_imbalance").sph == Approx(1.5));
  CHECK(metric_row(checked, "steady").sph == 1.0);
  CHECK(metric_row(checked, "water_imbalance").status == "check");
  CHECK(metric_row(checked, "steady").status == "check");
  // With the outlet holding a depth it is the other way round (the lengths stay predictions).
  const auto fixed = metric_table(&sph, nullptr, lab, 0.0254, 3.0, 9.81, false);
  for (const char* q : {"sequent_depth", "bed_effect", "eta", "eta_alpha1", "eta_crest_depth", "bed_force_fraction"})
    CHECK(metric_row(fixed, q).status == "imposed");
  for (const char* q : {"toe_position", "toe_mean_of_frames", "jump_length", "roller_length"})
    CHECK(metric_row(fixed, q).status == "predicted");
}

TEST_CASE("The metric table reports both toe positions: of the mean surface and the frames' mean", "[compare][metrics]") {
  JumpMetrics sph;
  sph.toe_x_m = 0.17;                 // an oscillating toe: the mean surface rises upstream of
  sph.toe_mean_of_frames_x_m = 0.21;  // the frames' mean toe
  sph.toe_std_m = 0.04;
  const auto rows = metric_table(&sph, nullptr, MeasuredReference{}, 0.0254, 2.0, 9.81, true);
  const auto value = [&rows](const std::string& quantity) { return metric_row(rows, quantity).sph; };
  CHECK(value("toe_position") == 0.17);
  CHECK(value("toe_mean_of_frames") == 0.21);
  CHECK(value("toe_std") == 0.04);
}

TEST_CASE("Toe and jump and roller lengths of a synthetic mean surface", "[compare][metrics]") {
  // Stations every 2 mm; the roller (0.3 m) ends before the surface settles (0.95 L = 0.38 m).
  const double y1 = 0.0254, u1 = 2.0, y2 = 0.104, x_t = 0.8, L = 0.4, Lr = 0.3, ds = 0.002;
  MethodStatistics m = synthetic_jump(y1, u1, y2, x_t, L, Lr, ds);
  // Three frames, at 1, 2 and 3 s, whose jump sits 2 cm upstream, at, and 2 cm downstream of the mean
  // position: the toe moves 0.02 m/s.
  m.times = {1.0, 2.0, 3.0};
  for (double shift : {-0.02, 0.0, 0.02}) {
    std::vector<double> frame;
    for (const auto& st : m.stations) {
      const double x = st.spec.x_m - shift;
      frame.push_back(x < x_t ? y1 : (x < x_t + L ? y1 + (y2 - y1) * (x - x_t) / L : y2));
    }
    m.station_surface_series.push_back(frame);
  }
  JumpInputs in{y1, u1, 0.0, g, {}};
  const JumpMetrics r = compute_jump_metrics(m, in);
  CHECK(r.toe_frames_found == 3);
  CHECK(r.toe_std_m == Approx(0.02).margin(ds));
  CHECK(r.toe_trend_m_per_s == Approx(0.02).margin(ds / 2.0));
  // Toe: the rise passes 1.5 y1 at x_t + 0.5 y1 L/(y2 - y1) (the running mean of a ramp is the ramp).
  const double x_toe = x_t + 0.5 * y1 * L / (y2 - y1);
  CHECK(r.toe_x_m == Approx(x_toe).margin(ds));
  CHECK(r.toe_mean_of_frames_x_m == Approx(x_toe).margin(ds));
  // Each frame's toe, in the frames' order: the mean position shifted by -2, 0 and +2 cm.
  REQUIRE(r.toe_frames_x_m.size() == 3u);
  CHECK(r.toe_frames_x_m[0] == Approx(x_toe - 0.02).margin(ds));
  CHECK(r.toe_frames_x_m[1] == Approx(x_toe).margin(ds));
  CHECK(r.toe_frames_x_m[2] == Approx(x_toe + 0.02).margin(ds));
  // Settled: within 5 % of (y2 - y1) of y2 from x_t + 0.95 L on.
  CHECK(r.jump_end_x_m == Approx(x_t + 0.95 * L).margin(ds));
  CHECK(r.jump_length_m == Approx(x_t + 0.95 * L - x_toe).margin(2 * ds));
  CHECK(r.roller_end_x_m == Approx(x_t + Lr).margin(ds));
  CHECK(r.roller_length_m == Approx(x_t + Lr - x_toe).margin(2 * ds));
  // u_max reaches 0.6 m/s at x_t + 0.28; within 10 % (0.66) from x_t + 0.268.
  CHECK(r.velocity_settling_distance_m == Approx(x_t + (u1 - 0.66) / 5.0 - x_toe).margin(2 * ds));
  // A monotonic rise: the highest mean surface is y2, first reached at x_t + L (within the running mean).
  CHECK(r.surface_peak_m == Approx(y2).margin(1e-12));
  CHECK(r.surface_peak_x_m == Approx(x_t + L).margin(0.5 * 0.8 * y1 + ds));
  CHECK(r.notes.empty());
}

TEST_CASE("A roller longer than the rise: the jump ends at the roller end, not inside it", "[compare][metrics]") {
  // The surface is within 5 % of (y2 - y1) of y2 from x_t + 0.95 L = x_t + 0.19 m, but the reverse
  // surface flow goes on to x_t + 0.5 m: section 3-3 cannot lie upstream of 2-2, so Lj = Lr.
  const double y1 = 0.0508, u1 = 4.07, y2 = 0.31, x_t = 0.6, L = 0.2, Lr = 0.5, ds = 0.002;
  const JumpInputs in{y1, u1, 0.0, g, {}};
  const JumpMetrics r = compute_jump_metrics(synthetic_jump(y1, u1, y2, x_t, L, Lr, ds), in);
  const double x_toe = x_t + 0.5 * y1 * L / (y2 - y1);
  REQUIRE(r.toe_x_m == Approx(x_toe).margin(ds));
  CHECK(r.roller_end_x_m == Approx(x_t + Lr).margin(ds));
  CHECK(r.jump_end_x_m == Approx(r.roller_end_x_m).margin(1e-12));
  CHECK(r.jump_length_m == Approx(r.roller_length_m).margin(1e-12));
  CHECK(std::count_if(r.notes.begin(), r.notes.end(), [](const std::string& n) {
          return n.find("already inside the roller") != std::string::npos;
        }) == 1);
  // A surface still rising at the roller end keeps the band's answer (and no note).
  const JumpMetrics later = compute_jump_metrics(synthetic_jump(y1, u1, y2, x_t, 0.8, Lr, ds), in);
  const double x_toe_later = x_t + 0.5 * y1 * 0.8 / (y2 - y1);
  CHECK(later.jump_end_x_m == Approx(x_t + 0.95 * 0.8).margin(2 * ds));  // the band edge falls on a station
  CHECK(later.jump_length_m == Approx(x_t + 0.95 * 0.8 - x_toe_later).margin(3 * ds));
  CHECK(later.notes.empty());
}

TEST_CASE("A mean surface cresting above y2 over the jump is reported as a standing wave", "[compare][metrics]") {
  // Surface: y1 up to x_t, a rise to a plateau at c y2 over (x_t + 0.2, x_t + 0.3), a trough at 0.7 y2
  // at x_t + 0.5, then y2 from x_t + 0.7 on (run D at `default` once peaked at 1.54 y2).
  const double y1 = 0.0508, u1 = 4.07, y2 = 0.31, x_t = 1.0, ds = 0.004;
  const auto surface = [&](double x, double c) {
    const std::vector<double> xs{0.0, x_t, x_t + 0.2, x_t + 0.3, x_t + 0.5, x_t + 0.7, 3.0};
    const std::vector<double> zs{y1, y1, c * y2, c * y2, 0.7 * y2, y2, y2};
    std::size_t k = 1;
    while (k + 1 < xs.size() && x > xs[k]) ++k;
    return zs[k - 1] + (zs[k] - zs[k - 1]) * (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
  };
  const auto metrics = [&](double c) {
    MethodStatistics m;
    m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.3, 0.0, y1, u1)));
    m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(2.5, 0.0, y2, y1 * u1 / y2)));
    for (int i = 0; i <= 750; ++i) {
      ColumnStatistics s;
      s.spec = {"", "station", i * ds, 0.0, 21};
      s.surface.mean = surface(i * ds, c);
      s.near_surface_velocity.mean = 0.5;
      s.max_velocity.mean = u1;
      m.stations.push_back(s);
    }
    return compute_jump_metrics(m, JumpInputs{y1, u1, 0.0, g, {}});
  };
  const auto wave_notes = [](const JumpMetrics& r) {
    return std::count_if(r.notes.begin(), r.notes.end(),
                         [](const std::string& n) { return n.find("standing wave") != std::string::npos; });
  };
  const JumpMetrics wave = metrics(1.5);
  CHECK(wave.surface_peak_m == Approx(1.5 * y2).margin(1e-9));
  CHECK(wave.surface_peak_x_m >= x_t + 0.2 - ds);
  CHECK(wave.surface_peak_x_m <= x_t + 0.3 + ds);
  CHECK(wave_notes(wave) == 1);
  // 15 % above y2 is within the 20 % a roller's surface may overshoot: no note, the peak still reported.
  const JumpMetrics low = metrics(1.15);
  CHECK(low.surface_peak_m == Approx(1.15 * y2).margin(1e-9));
  CHECK(wave_notes(low) == 0);
  // The metric table carries the peak.
  const auto rows = metric_table(&wave, nullptr, MeasuredReference{}, y1, u1, g, true);
  CHECK(metric_row(rows, "surface_peak").sph == Approx(1.5 * y2).margin(1e-9));
}

TEST_CASE("Missing sections and no jump are reported as notes and are not crashes", "[compare][metrics]") {
  MethodStatistics m;
  JumpInputs in{0.0254, 2.0, 0.0, g, {}};
  JumpMetrics r = compute_jump_metrics(m, in);
  CHECK(std::isnan(r.eta));
  CHECK(r.notes.size() >= 2);
  for (int i = 0; i <= 100; ++i) {
    ColumnStatistics s;
    s.spec = {"", "station", i * 0.01, 0.0, 21};
    s.surface.mean = 0.0254;  // supercritical all the way: no toe
    m.stations.push_back(s);
  }
  r = compute_jump_metrics(m, in);
  CHECK(std::isnan(r.toe_x_m));
  bool found = false;
  for (const auto& n : r.notes) found = found || n.find("no jump toe") != std::string::npos;
  CHECK(found);
}

TEST_CASE("No toe in the reach: the downstream section's values are not reported as a jump's", "[compare][metrics]") {
  // A jump swept out of the domain: the downstream section at 1.6 m samples the incoming stream
  // (y1, U1), which would read as y2 = y1, eta = 0 and a balanced momentum.
  const double y1 = 0.0254, u1 = 2.0;
  MethodStatistics m;
  m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.3, 0.0, y1, u1)));
  m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(1.6, 0.0, y1, u1)));
  m.stations = stations_with_surface([&](double) { return y1; });
  const JumpMetrics r = compute_jump_metrics(m, JumpInputs{y1, u1, 0.0, g, {}});
  CHECK(std::isnan(r.toe_x_m));
  CHECK(std::isnan(r.sequent_depth_m));
  CHECK(std::isnan(r.e2_m));
  CHECK(std::isnan(r.eta));
  CHECK(std::isnan(r.eta_alpha1));
  CHECK(std::isnan(r.eta_crest_depth));
  CHECK(std::isnan(r.specific_force_downstream_m2));
  CHECK(std::isnan(r.bed_force_fraction));
  // The incoming stream itself is still measured.
  CHECK(r.e1_m == Approx(y1 + u1 * u1 / (2 * g)).epsilon(1e-9));
  bool found = false;
  for (const auto& n : r.notes) found = found || n.find("no jump toe") != std::string::npos;
  CHECK(found);
}

TEST_CASE("A jump reaching the upstream section gives no E1 or eta, and its pinned frames are counted", "[compare][metrics]") {
  // The whole reach subcritical: the mean surface 0.10 m from x = 0 on, with q = 0.0508 m^2/s, and the
  // upstream section at 0.3 m inside it. Without the check the toe would be the search start (0.3 m)
  // and eta = (E1 - E2)/E1 of two subcritical sections, -2.7 %, with no note.
  const double y1 = 0.0254, u1 = 2.0, q = y1 * u1;
  MethodStatistics m;
  m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.3, 0.0, 0.10, q / 0.10)));
  m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(1.6, 0.0, 0.104, q / 0.104)));
  m.stations = stations_with_surface([](double) { return 0.10; });
  // Two frames: one like the mean, one with the jump at 0.8 m (supercritical y1 upstream of it).
  m.times = {1.0, 2.0};
  std::vector<double> pinned, held;
  for (const auto& st : m.stations) {
    pinned.push_back(0.10);
    held.push_back(st.spec.x_m < 0.8 ? y1 : 0.10);
  }
  m.station_surface_series = {pinned, held};
  const JumpMetrics r = compute_jump_metrics(m, JumpInputs{y1, u1, 0.0, g, {}});
  CHECK(r.toe_x_m == Approx(0.3).margin(0.004));
  CHECK(std::isnan(r.e1_m));
  CHECK(std::isnan(r.eta));
  CHECK(std::isnan(r.eta_alpha1));
  CHECK(std::isnan(r.eta_crest_depth));
  CHECK(std::isnan(r.specific_force_upstream_m2));
  CHECK(std::isnan(r.bed_force_fraction));
  CHECK(std::isnan(r.roller_length_m));
  CHECK(std::isnan(r.jump_length_m));
  // The downstream section still gives the depth behind the jump.
  CHECK(r.sequent_depth_m == Approx(0.104).margin(1e-9));
  CHECK(r.toe_frames_found == 2);
  CHECK(r.toe_frames_at_search_start == 1);
  bool section_note = false, frames_note = false;
  for (const auto& n : r.notes) {
    section_note = section_note || n.find("the jump reaches it") != std::string::npos;
    frames_note = frames_note || n.find("in 1 of 2 frames the toe is at the search start") != std::string::npos;
  }
  CHECK(section_note);
  CHECK(frames_note);
}

TEST_CASE("A single frame in the window has no standard deviation", "[compare][metrics]") {
  const ScalarStats one = stats_of({0.2});
  CHECK(one.mean == 0.2);
  CHECK(one.count == 1);
  CHECK(std::isnan(one.std));
  const ScalarStats two = stats_of({0.2, 0.4, std::nan("")});
  CHECK(two.count == 2);
  CHECK(two.std == Approx(std::sqrt(0.02)).epsilon(1e-12));
}

TEST_CASE("A toe downstream of the downstream section gives no y2 or eta, with a note", "[compare][metrics]") {
  // The synthetic ramp jump of the test above (toe near 0.87 m) with the downstream section at 0.6 m,
  // where the time-mean surface is still the incoming supercritical layer.
  const double y1 = 0.0254, u1 = 2.0, y2 = 0.104, x_t = 0.8, L = 0.4;
  MethodStatistics m;
  m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.3, 0.0, y1, u1)));
  m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(0.6, 0.0, y1, u1)));
  m.stations = stations_with_surface([&](double x) { return x < x_t ? y1 : (x < x_t + L ? y1 + (y2 - y1) * (x - x_t) / L : y2); });
  JumpInputs in{y1, u1, 0.0, g, {}};
  const JumpMetrics r = compute_jump_metrics(m, in);
  CHECK(r.toe_x_m > 0.85);
  CHECK(std::isnan(r.sequent_depth_m));
  CHECK(std::isnan(r.eta));
  CHECK(std::isnan(r.eta_crest_depth));
  CHECK(std::isnan(r.jump_length_m));
  // The downstream section samples the incoming stream here, so M1 = M2 would read as Belanger's
  // balance: not reported, nor what lies beyond the sections.
  CHECK(std::isnan(r.specific_force_downstream_m2));
  CHECK(std::isnan(r.bed_force_fraction));
  CHECK(std::isnan(r.roller_length_m));
  CHECK(std::isnan(r.velocity_settling_distance_m));
  bool found = false;
  for (const auto& n : r.notes) found = found || n.find("swept past") != std::string::npos;
  CHECK(found);
}

TEST_CASE("A section whose mean discharge is off the inflow q is named in the notes", "[compare][metrics]") {
  const double y1 = 0.0254, u1 = 2.0, y2 = 0.104, q = y1 * u1;
  auto has_note = [](const JumpMetrics& r, const std::string& part) {
    for (const auto& n : r.notes)
      if (n.find(part) != std::string::npos) return true;
    return false;
  };
  JumpInputs in{y1, u1, 0.0, g, {}};
  for (const double factor : {1.04, 1.08, 0.9}) {
    MethodStatistics m;
    m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.1, 0.0, y1, u1)));
    m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(1.5, 0.0, y2, factor * q / y2)));
    const JumpMetrics r = compute_jump_metrics(m, in);
    INFO("downstream q = " << factor << " q");
    CHECK(has_note(r, "\"downstream\" section's mean discharge") == (std::abs(factor - 1.0) > 0.05));
    CHECK_FALSE(has_note(r, "\"upstream\" section's mean discharge"));
  }
  MethodStatistics m;
  m.sections.push_back(as_statistics("upstream", "upstream", uniform_column(0.1, 0.0, y1, u1)));
  m.sections.push_back(as_statistics("downstream", "downstream", uniform_column(1.5, 0.0, y2, 1.077 * q / y2)));
  CHECK(has_note(compute_jump_metrics(m, in), "is 7.7 % off the inflow q"));
}

TEST_CASE("The jet height is where the fastest forward flow runs at x_2y2 over the depth there", "[compare][metrics]") {
  // A hand-built section 0.1 m deep over a bed at z = -0.01 m: a wall jet (u_max at 0.02 m above the
  // bed: 0.2), then a surface jet (u_max at 0.09 m: 0.9); heights wet in under half the frames do not count.
  MethodStatistics m;
  ColumnStatistics s;
  s.spec = {"x_2y2", "interior", 0.6, -0.01, 11};
  s.n_times = s.n_wet = 10;
  s.depth.mean = 0.1;
  for (int k = 0; k <= 10; ++k) {
    s.z.push_back(-0.01 + 0.01 * k);
    s.u_mean.push_back(k == 2 ? 1.2 : 0.3);
    s.wet_fraction.push_back(1.0);
  }
  m.sections.push_back(s);
  JumpInputs in{0.0254, 2.0, 0.0, g, {}};
  CHECK(compute_jump_metrics(m, in).jet_height_fraction == Approx(0.2).margin(1e-12));
  m.sections[0].u_mean[9] = 1.5;
  CHECK(compute_jump_metrics(m, in).jet_height_fraction == Approx(0.9).margin(1e-12));
  m.sections[0].wet_fraction[9] = 0.4;  // a splash height: the wall jet again
  CHECK(compute_jump_metrics(m, in).jet_height_fraction == Approx(0.2).margin(1e-12));
  m.sections[0].spec.name = "x_4y2";  // no section x_2y2: not measured
  CHECK(std::isnan(compute_jump_metrics(m, in).jet_height_fraction));
}
