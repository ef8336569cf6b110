// Readers: .pvd/.vtp particle series and OpenFOAM cases written by the test (no OpenFOAM run needed).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <vector>

#include "compare/case_comparison.hpp"
#include "compare/readers.hpp"
#include "reference/discharge_samples.hpp"
#include "reference/tailwater_control.hpp"
#include "foam_case_writer.hpp"
#include "synthetic_fields.hpp"
#include "tests/temp_dir.hpp"
#include "vtp_writer.hpp"

using namespace hydrojump::compare;
using namespace hydrojump::compare::testing;
using hydrojump::testing::TempDir;

TEST_CASE("PVD and VTP series give the window frames and arrays and exact section values through files",
          "[compare][readers][sph]") {
  TempDir tmp("pvd");
  const double dx = 0.01;
  auto u = [](double x, double z) { return 1.2 + 0.5 * x + 3.0 * z; };
  auto w = [](double x, double z) { return 0.1 - 0.2 * x + 0.4 * z; };
  std::filesystem::create_directories(tmp.path() / "out");
  std::vector<std::pair<double, std::string>> entries;
  for (int i = 0; i < 3; ++i) {
    const double depth = 0.15 + 0.02 * i;
    const std::string name = "out/particles_" + std::to_string(i) + ".vtp";
    // frames 0 and 2 as the SPH solver writes them, (x, 0, z); frame 1 in the x-y plane
    write_vtp(tmp.path() / name, lattice_particles(0.6, depth, dx, 3, u, w), true, i == 1 ? 1 : 2);
    entries.push_back({0.5 * (i + 1), name});
  }
  write_pvd(tmp.path() / "particles.pvd", entries);
  CHECK(find_pvd(tmp.path()) == tmp.path() / "particles.pvd");

  const auto all = read_pvd(tmp.path() / "particles.pvd");
  REQUIRE(all.size() == 3);
  CHECK(all[2].time_s == Approx(1.5));
  const auto win = entries_in_window(all, 0.9, 2.0, 1e-9);
  REQUIRE(win.size() == 2);
  CHECK(win[0].time_s == Approx(1.0));
  // Outputs written a time step after their nominal time belong to it (1 % of the 0.5 s interval):
  // [1, 1.5] holds the outputs of 1 and 1.5 s, not the one of 0.5 s.
  std::vector<PvdEntry> late = all;
  for (auto& e : late) e.time_s += 6.8e-6;
  const auto late_win = entries_in_window(late, 1.0, 1.5, 0.005);
  REQUIRE(late_win.size() == 2);
  CHECK(late_win[1].time_s == Approx(1.5 + 6.8e-6).epsilon(1e-12));
  CHECK(entries_in_window(late, 1.0, 1.5, 1e-9).size() == 1);
  CHECK(entries_in_window(late, 0.6, 1.5, 0.005).size() == 2);

  const ParticleFrame f1 = read_vtp_particles(win[0].file, win[0].time_s);  // the (x, z, 0) layout
  CHECK(*std::max_element(f1.z.begin(), f1.z.end()) == Approx(0.17 - 0.005));
  const ParticleFrame f = read_vtp_particles(win[1].file, win[1].time_s);
  CHECK(f.time_s == Approx(1.5));
  CHECK(f.x.size() == 60u * (19u + 3u));
  CHECK(*std::max_element(f.z.begin(), f.z.end()) == Approx(0.19 - 0.005));
  SphSamplingSettings s;
  s.particle_spacing_m = dx;
  s.smoothing_length_m = std::sqrt(2.0) * dx;
  const auto sampler = make_sph_sampler(f, s);
  const ColumnSample c = sampler->sample_column(0.3037, 0.0, 21, 9.81);
  CHECK(std::abs(c.surface_z_m - 0.19) < 0.1 * dx);
  for (std::size_t k = 0; k < c.z.size(); ++k) {
    CHECK(c.u[k] == Approx(u(0.3037, c.z[k])).margin(1e-6));
    CHECK(c.w[k] == Approx(w(0.3037, c.z[k])).margin(1e-6));
  }
}

TEST_CASE("PVD/VTP errors name the file and what is wrong", "[compare][readers][sph]") {
  TempDir tmp("pvd-bad");
  {
    std::ofstream o(tmp.path() / "bad.pvd");
    o << "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"abc\" file=\"x.vtp\"/></Collection></VTKFile>";
  }
  CHECK_THROWS_WITH(read_pvd(tmp.path() / "bad.pvd"), Catch::Contains("bad.pvd") && Catch::Contains("abc"));
  CHECK_THROWS_WITH(read_pvd(tmp.path() / "none.pvd"), Catch::Contains("none.pvd"));
  // Cut short (the first frame only would be read), a time that is not finite, no time at all.
  const auto write_pvd = [&](const std::string& name, const std::string& text) { std::ofstream(tmp.path() / name) << text; };
  write_pvd("cut.pvd", "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" file=\"p_0.vtp\"/><DataSet time");
  CHECK_THROWS_WITH(read_pvd(tmp.path() / "cut.pvd"), Catch::Contains("cut.pvd: ends before </Collection>"));
  write_pvd("nan.pvd", "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"nan\" file=\"p.vtp\"/></Collection></VTKFile>");
  CHECK_THROWS_WITH(read_pvd(tmp.path() / "nan.pvd"), Catch::Contains("nan.pvd") && Catch::Contains("timestep=\"nan\""));
  // A time listed twice for the same part (a merged or edited file); two parts at one time are fine.
  write_pvd("twice.pvd", "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0.1\" part=\"0\" file=\"a.vtp\"/>"
                         "<DataSet timestep=\"0.2\" part=\"0\" file=\"b.vtp\"/><DataSet timestep=\"0.1\" part=\"0\" "
                         "file=\"c.vtp\"/></Collection></VTKFile>");
  CHECK_THROWS_WITH(read_pvd(tmp.path() / "twice.pvd"),
                    Catch::Contains("twice.pvd: the time 0.1 s is listed twice (a.vtp and c.vtp)"));
  write_pvd("parts.pvd", "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0.1\" part=\"0\" file=\"a.vtp\"/>"
                         "<DataSet timestep=\"0.1\" part=\"1\" file=\"b.vtp\"/></Collection></VTKFile>");
  CHECK(read_pvd(tmp.path() / "parts.pvd").size() == 2u);
  write_pvd("untimed.pvd", "<VTKFile type=\"Collection\"><Collection><DataSet file=\"p.vtp\"/></Collection></VTKFile>");
  CHECK_THROWS_WITH(read_pvd(tmp.path() / "untimed.pvd"), Catch::Contains("untimed.pvd: a <DataSet> has no timestep"));
  const ParticleFrame f = lattice_particles(0.1, 0.05, 0.01, 1, [](double, double) { return 0.0; },
                                            [](double, double) { return 0.0; });
  write_vtp(tmp.path() / "nodensity.vtp", f, false);
  CHECK_THROWS_WITH(read_vtp_particles(tmp.path() / "nodensity.vtp", 0.0),
                    Catch::Contains("nodensity.vtp") && Catch::Contains("\"density\""));
  CHECK_THROWS_WITH(find_pvd(tmp.path() / "empty"), Catch::Contains("no .pvd"));
}

// A damaged frame must not enter the averages as data: a NaN or absurd velocity (the comparison's
// section energy would be wrong and still look fine), a NaN position, no fluid at all.
TEST_CASE("A frame whose values cannot be a particle state is refused, naming the particle", "[compare][readers][sph]") {
  TempDir tmp("vtp-values");
  const ParticleFrame good = lattice_particles(0.1, 0.05, 0.01, 1, [](double, double) { return 0.5; },
                                               [](double, double) { return 0.0; });
  write_vtp(tmp.path() / "good.vtp", good);
  CHECK(read_vtp_particles(tmp.path() / "good.vtp", 0.0).x.size() == good.x.size());
  const auto refused = [&](const std::string& name, const std::function<void(ParticleFrame&)>& damage) {
    ParticleFrame f = good;
    damage(f);
    write_vtp(tmp.path() / name, f);
    std::string message;
    try {
      read_vtp_particles(tmp.path() / name, 0.0);
    } catch (const std::exception& e) {
      message = e.what();
    }
    INFO(name << ": " << message);
    CHECK_THAT(message, Catch::Contains(name));
    return message;
  };
  const std::size_t k = good.x.size() - 3;  // a fluid particle
  REQUIRE(good.type[k] == 0);
  CHECK_THAT(refused("nan_u.vtp", [&](ParticleFrame& f) { f.u[k] = std::numeric_limits<double>::quiet_NaN(); }),
             Catch::Contains("particle " + std::to_string(k) + " has the horizontal velocity (m/s) nan") &&
                 Catch::Contains("frame refused"));
  CHECK_THAT(refused("huge_w.vtp", [&](ParticleFrame& f) { f.w[k] = 1e300; }), Catch::Contains("the vertical velocity"));
  CHECK_THAT(refused("nan_x.vtp", [&](ParticleFrame& f) { f.x[k] = std::numeric_limits<double>::quiet_NaN(); }),
             Catch::Contains("the x coordinate"));
  CHECK_THAT(refused("zero_rho.vtp", [&](ParticleFrame& f) { f.density[k] = 0.0; }), Catch::Contains("the density"));
  CHECK_THAT(refused("type9.vtp", [&](ParticleFrame& f) { f.type[k] = 9; }), Catch::Contains("the type 9"));
  CHECK_THAT(refused("no_fluid.vtp", [&](ParticleFrame& f) { std::fill(f.type.begin(), f.type.end(), 1); }),
             Catch::Contains("no fluid particle (type 0)"));
  // A truncated file: one line with VTK's reason, not VTK's own messages on the terminal.
  {
    std::ifstream in(tmp.path() / "good.vtp");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(tmp.path() / "cut.vtp") << text.substr(0, text.size() * 2 / 3);
  }
  CHECK_THROWS_WITH(read_vtp_particles(tmp.path() / "cut.vtp", 0.0), Catch::Contains("cut.vtp"));
}

TEST_CASE("An OpenFOAM case written by hand gives its times and cells and fields and exact section values",
          "[compare][readers][vof]") {
  TempDir tmp("foam");
  const FoamBox box{0.6, 0.3, 0.01, 60, 40};
  const double dz = box.height / box.nz;
  write_foam_mesh(tmp.path(), box);
  auto cell_alpha = [dz](double surface) {
    return [surface, dz](double, double y) { return std::clamp((surface - (y - 0.5 * dz)) / dz, 0.0, 1.0); };
  };
  auto u = [](double x, double y) { return 0.8 - 0.3 * x + 2.0 * y; };
  auto v = [](double x, double y) { return 0.05 + 0.1 * x - 0.2 * y; };
  auto zero = [](double, double) { return 0.0; };
  write_foam_fields(tmp.path(), "0.5", box, cell_alpha(0.1), zero, zero);
  write_foam_fields(tmp.path(), "1", box, cell_alpha(0.1234), u, v);
  CHECK(has_openfoam_results(tmp.path()));

  OpenFoamResults foam(tmp.path());
  REQUIRE(foam.times().size() == 2);
  CHECK(foam.times()[0] == Approx(0.5));
  CHECK(foam.times_in_window(0.8, 5.0, 1e-9).size() == 1);
  CHECK(foam.times_in_window(0.8, 0.995, 0.01).size() == 1);  // the output of 1 s, 5 ms past the window
  CHECK(foam.times_in_window(0.8, 0.985, 0.01).empty());

  const CellFrame f1 = foam.read(1.0);
  REQUIRE(f1.xc.size() == 2400u);
  const auto sampler = make_vof_sampler(f1, InterpolationScheme::mls_linear);
  for (double x : {0.2, 0.3037}) {
    const ColumnSample c = sampler->sample_column(x, 0.0, 41, 9.81);
    REQUIRE(c.wet());
    CHECK(std::abs(c.surface_z_m - 0.1234) <= dz / 12.0 + 1e-9);
    CHECK(c.surface_from_fraction_m == Approx(0.1234).margin(1e-9));
    for (std::size_t k = 0; k < c.z.size(); ++k) {
      CHECK(c.u[k] == Approx(u(x, c.z[k])).margin(1e-6));
      CHECK(c.w[k] == Approx(v(x, c.z[k])).margin(1e-6));
    }
  }
  // Switching times reads the other directory.
  const CellFrame f0 = foam.read(0.5);
  const auto s0 = make_vof_sampler(f0, InterpolationScheme::mls_linear);
  const ColumnSample c0 = s0->sample_column(0.3, 0.0, 21, 9.81);
  CHECK(c0.surface_from_fraction_m == Approx(0.1).margin(1e-9));
  CHECK(std::abs(c0.u[5]) < 1e-12);
}

TEST_CASE("OpenFOAM reader errors name the directory", "[compare][readers][vof]") {
  TempDir tmp("foam-bad");
  CHECK_FALSE(has_openfoam_results(tmp.path()));
  CHECK(missing_openfoam_results(tmp.path()) == "no system/controlDict (not an OpenFOAM case)");
  CHECK_THROWS_WITH(OpenFoamResults(tmp.path()), Catch::Contains("controlDict") && Catch::Contains(tmp.path().string()));
  // A written time but no mesh: the reason is the mesh, not the times.
  std::filesystem::create_directories(tmp.path() / "system");
  std::ofstream(tmp.path() / "system" / "controlDict") << "FoamFile {}\n";
  std::filesystem::create_directories(tmp.path() / "0.2");
  std::ofstream(tmp.path() / "0.2" / "alpha.water") << "FoamFile {}\n";
  CHECK_THAT(missing_openfoam_results(tmp.path()), Catch::StartsWith("no mesh (constant/polyMesh/owner)"));
}

TEST_CASE("water leaving the VOF domain through its top is read over restarts and noted above 1 % of q",
          "[compare][readers][vof]") {
  TempDir tmp("top-outflow");
  const auto dir = tmp.path() / "postProcessing" / "discharge_atmosphere";
  auto write_rows = [&](const std::string& start, const std::vector<std::pair<double, double>>& rows) {
    std::filesystem::create_directories(dir / start);
    std::ofstream out(dir / start / "surfaceFieldValue.dat");
    out << "# Region type : patch atmosphere\n# Time          \tsum(alphaPhi0.water)\tsum(phi)\n";
    for (const auto& [t, v] : rows) out << t << "\t" << v << "\t" << -v << "\n";
  };
  // No samples (a case written before the function object existed): no note, no error.
  CHECK(hydrojump::reference::read_surface_field_value(dir).empty());
  CHECK(vof_top_outflow_note(tmp.path(), 0.0, 10.0, 0.0508, 0.005).empty());
  // A first run wrote rows up to 6 s; it was resumed from 5 s, which rewrote 5 s on (rows from 5 s on are
  // the resumed run's, the earlier run's rows at 5.5 and 6 s are dropped).
  write_rows("0", {{4.5, 0.0}, {5.0, 1.0}, {5.5, 1.0}, {6.0, 1.0}});
  write_rows("5", {{5.0, 5.08e-5}, {5.5, 5.08e-5}, {6.0, 5.08e-5}, {6.5, 0.0}});
  const auto rows = hydrojump::reference::read_surface_field_value(dir);
  REQUIRE(rows.size() == 5);
  CHECK(rows[1].first == 5.0);
  CHECK(rows[1].second == 5.08e-5);
  // 5.08e-5 m^3/s over a 5 mm thick mesh is 0.01016 m^2/s, 20 % of q = 0.0508 m^2/s.
  const std::string note = vof_top_outflow_note(tmp.path(), 5.0, 6.0, 0.0508, 0.005);
  CHECK_THAT(note, Catch::Contains("0.0102 m^2/s") && Catch::Contains("20 % of the inflow q") &&
                       Catch::Contains("air_height_m"));
  // Over 5-6.5 s the mean is 3/4 of that (15 %); over 6.5 s alone nothing leaves: no note.
  CHECK_THAT(vof_top_outflow_note(tmp.path(), 5.0, 6.5, 0.0508, 0.005), Catch::Contains("15 % of the inflow q"));
  CHECK(vof_top_outflow_note(tmp.path(), 6.5, 7.0, 0.0508, 0.005).empty());
  // Just below the 1 % threshold: no note; a damaged row names the file and line.
  write_rows("7", {{7.0, 0.0099 * 0.0508 * 0.005}});
  CHECK(vof_top_outflow_note(tmp.path(), 7.0, 7.0, 0.0508, 0.005).empty());
  { std::ofstream(dir / "7" / "surfaceFieldValue.dat", std::ios::app) << "7.5 n/a\n"; }
  CHECK_THROWS_WITH(hydrojump::reference::read_surface_field_value(dir), Catch::Contains("7/surfaceFieldValue.dat:4") &&
                                                       Catch::Contains("expected a time and a value"));
}

TEST_CASE("the VOF water balance over the window: filling, draining and steady, with the SPH monitor's rule",
          "[compare][readers][vof]") {
  TempDir tmp("water-balance");
  // Fluxes in m^3/s through a 5 mm thick 2D mesh: q = 0.0508 m^2/s is 2.54e-4 m^3/s; OpenFOAM's patch
  // fluxes point out of the domain, so the inlet's is negative.
  const double thickness = 0.005, q = 0.0508, flux = q * thickness;
  auto write_patch = [&](const std::string& name, double value) {
    const auto dir = tmp.path() / "postProcessing" / name / "0";
    std::filesystem::create_directories(dir);
    std::ofstream out(dir / "surfaceFieldValue.dat");
    out << "# Time          \tsum(alphaPhi0.water)\tsum(phi)\n";
    for (double t : {5.0, 5.5, 6.0}) out << t << "\t" << value << "\t0\n";
    out << 7.0 << "\t" << 100.0 << "\t0\n";  // outside the window: ignored
  };
  VofRunNoteInputs in{tmp.path(), 5.0, 6.0, q, thickness, 0.01, 0.068};
  // No samples (a case written before these function objects): no note.
  CHECK(vof_run_note(in).empty());
  // The outlet passes 95 % of the inflow: filling by 5 % of q, not steady whatever the toe does.
  write_patch("discharge_inlet", -flux);
  write_patch("discharge_outlet", 0.95 * flux);
  RunBalance balance;
  std::string note = vof_run_note(in, &balance);
  CHECK_THAT(note, Catch::Contains("in 0.0508, out 0.04826 m^2/s") && Catch::Contains("= -5 % of q (filling)") &&
                       Catch::Contains("toe trend 0.01 m/s") && Catch::Contains("NOT steady by the window means"));
  CHECK(balance.imbalance == Approx(-0.05));
  CHECK(balance.steady == false);
  // 99 % at the outlet and 1 % through the top: balanced.
  write_patch("discharge_outlet", 0.99 * flux);
  write_patch("discharge_atmosphere", 0.01 * flux);
  note = vof_run_note(in, &balance);
  CHECK_THAT(note, Catch::Contains("+ top 0.000508") && Catch::Contains("(steady by the window means") &&
                       Catch::Contains("< 0.068 m"));
  CHECK(balance.imbalance == Approx(0.0).margin(1e-12));
  CHECK(balance.steady == true);
  // The same balance with the toe moving 0.1 m/s (more than a 68 mm wavelength per second): not steady;
  // an unknown trend is not steady either.
  in.toe_trend_m_per_s = -0.1;
  CHECK_THAT(vof_run_note(in), Catch::Contains("NOT steady"));
  in.toe_trend_m_per_s = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(vof_run_note(in), Catch::Contains("toe trend unknown") && Catch::Contains("NOT steady"));
  // Draining: 103 % leaves (102 % at the outlet, 1 % at the top).
  in.toe_trend_m_per_s = 0.0;
  write_patch("discharge_outlet", 1.02 * flux);
  CHECK_THAT(vof_run_note(in), Catch::Contains("= 3 % of q (draining)") && Catch::Contains("NOT steady"));
  // The SPH monitor's two further conditions: a balanced window is not steady when frames lost their
  // toe (the jump left the reach in them), or when the run stopped before the window's end.
  write_patch("discharge_outlet", 0.99 * flux);
  REQUIRE_THAT(vof_run_note(in), Catch::Contains("(steady by the window means"));
  in.frames = 40;
  in.frames_without_toe = 20;
  CHECK_THAT(vof_run_note(in), Catch::Contains("no toe in 20 of 40 frames") && Catch::Contains("NOT steady"));
  in.frames_without_toe = 0;
  in.reaches_window_end = false;
  CHECK_THAT(vof_run_note(in), Catch::Contains("the run has not reached 6 s") && Catch::Contains("NOT steady"));
}

TEST_CASE("a VOF run whose tailwater was set by the tailgate control says so, with the window's Umean and toe",
          "[compare][readers][vof]") {
  TempDir tmp("tailwater-note");
  CHECK(vof_tailwater_control_note(tmp.path(), 0.0, 10.0).empty());  // no log: a fixed tailwater
  using hydrojump::reference::TailwaterControlStep;
  for (const TailwaterControlStep& s : {TailwaterControlStep{0.5, 0.3, 5, 0.38, 0.381, 0.36},
                                        TailwaterControlStep{1.0, 0.2, 5, 0.38, 0.381, 0.40},
                                        TailwaterControlStep{1.5, std::nan(""), 0, 0.38, 0.381, 0.38},
                                        TailwaterControlStep{2.0, 0.1, 5, 0.38, 0.381, 0.30}}) {
    hydrojump::reference::append_tailwater_control_log(tmp.path(), s);
  }
  // Over 1-1.5 s: Umean 0.38-0.4 (mean 0.39), the one toe 0.2 m.
  CHECK_THAT(vof_tailwater_control_note(tmp.path(), 1.0, 1.5),
             Catch::Contains("2 steps in the window") && Catch::Contains("outlet Umean 0.38-0.4 m/s (mean 0.39)") &&
                 Catch::Contains("legs' mean toe 0.2 m") && Catch::Contains("the depth the held jump needed"));
  CHECK_THAT(vof_tailwater_control_note(tmp.path(), 0.0, 10.0), Catch::Contains("mean 0.36)") && Catch::Contains("toe 0.2 m"));
  CHECK(vof_tailwater_control_note(tmp.path(), 2.5, 3.0).empty());
}
