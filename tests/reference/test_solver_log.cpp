// Reading interFoam logs: progress values and the signs of divergence or a crash.
#include <catch2/catch.hpp>

#include <string>

#include "reference/solver_log.hpp"

using hydrojump::reference::DivergenceLimits;
using hydrojump::reference::SolverLog;

namespace {

// One healthy interFoam time step as OpenFOAM v1912 prints it.
std::string step(double co, double dt, double t) {
  return "Courant Number mean: 0.0108 max: " + std::to_string(co) +
         "\nInterface Courant Number mean: 0.0127 max: 0.43\n"
         "deltaT = " + std::to_string(dt) + "\nTime = " + std::to_string(t) +
         "\n\nPIMPLE: iteration 1\n"
         "smoothSolver:  Solving for alpha.water, Initial residual = 0.0026, Final residual = 2.1e-10, No Iterations 2\n"
         "GAMG:  Solving for p_rgh, Initial residual = 0.0031, Final residual = 5.1e-05, No Iterations 1\n"
         "ExecutionTime = 12.5 s  ClockTime = 13 s\n\n";
}

}  // namespace

TEST_CASE("progress values are read from the log", "[reference][solver_log]") {
  SolverLog log(DivergenceLimits{0.8, 25.0, 1e-9});
  log.add_text("/*---*\\\ntrapFpe: Floating point exception trapping enabled (FOAM_SIGFPE).\n");
  log.add_text(step(0.5, 1e-4, 0.0001));
  log.add_text(step(0.79, 2e-4, 0.0003));
  CHECK_FALSE(log.failed());
  CHECK(log.steps() == 2);
  CHECK(*log.time_s() == Approx(0.0003));
  CHECK(*log.time_step_s() == Approx(2e-4));
  CHECK(*log.courant_max() == Approx(0.79));
  CHECK(*log.interface_courant_max() == Approx(0.43));
  CHECK(*log.execution_time_s() == Approx(12.5));
}

TEST_CASE("text arriving in pieces is split into lines correctly", "[reference][solver_log]") {
  SolverLog log;
  log.add_text("Time = 0.12");
  CHECK_FALSE(log.time_s().has_value());
  log.add_text("5\nCourant Number mean: 0.1 max: 0.");
  log.add_text("6\n");
  CHECK(*log.time_s() == Approx(0.125));
  CHECK(*log.courant_max() == Approx(0.6));
}

TEST_CASE("without adjustable time steps the time step is the difference of times", "[reference][solver_log]") {
  SolverLog log;
  log.add_text("Time = 0.01\nCourant Number mean: 0.1 max: 0.2\nTime = 0.02\n");
  CHECK(*log.time_step_s() == Approx(0.01));
}

TEST_CASE("a Courant blow-up is detected with the lines leading to it", "[reference][solver_log]") {
  SolverLog log(DivergenceLimits{0.8, 25.0, 1e-9});
  log.add_text(step(0.7, 1e-4, 0.0001));
  log.add_text("Courant Number mean: 2.67 max: 82.08\n");
  REQUIRE(log.failed());
  CHECK_THAT(log.failure(), Catch::Contains("blew up") && Catch::Contains("82.1") && Catch::Contains("t = 0.0001"));
  CHECK_THAT(log.failure_context(), Catch::Contains("max: 82.08"));
  // Later lines do not replace the first diagnosis.
  log.add_text("--> FOAM FATAL ERROR:\n");
  CHECK_THAT(log.failure(), Catch::Contains("blew up"));
}

TEST_CASE("Courant numbers up to 25 maxCo are not a blow-up", "[reference][solver_log]") {
  SolverLog log(DivergenceLimits{0.8, 25.0, 1e-9});
  log.add_text("Courant Number mean: 0.1 max: 19.9\n");
  CHECK_FALSE(log.failed());
}

TEST_CASE("NaN anywhere in the numbers is a failure", "[reference][solver_log]") {
  for (const std::string line : {"Courant Number mean: nan max: nan", "deltaT = -nan",
                                 "GAMG:  Solving for p_rgh, Initial residual = nan, Final residual = nan, No Iterations 1000"}) {
    INFO(line);
    SolverLog log;
    log.add_line(line);
    CHECK(log.failed());
    CHECK_THAT(log.failure(), Catch::Contains("not a number"));
  }
}

TEST_CASE("a collapsing time step is a failure", "[reference][solver_log]") {
  SolverLog log(DivergenceLimits{0.8, 25.0, 1e-9});
  log.add_line("deltaT = 7.79e-115");
  CHECK_THAT(log.failure(), Catch::Contains("time step collapsed"));
}

TEST_CASE("crashes and fatal errors are failures but the FPE banner is not", "[reference][solver_log]") {
  {
    SolverLog log;
    log.add_line("trapFpe: Floating point exception trapping enabled (FOAM_SIGFPE).");
    CHECK_FALSE(log.failed());
  }
  {
    SolverLog log;
    log.add_line("#0  Foam::error::printStack(Foam::Ostream&) at ??:?");
    CHECK_THAT(log.failure(), Catch::Contains("crashed"));
  }
  {
    SolverLog log;
    log.add_line("#1  Foam::sigFpe::sigHandler(int) at ??:?");
    CHECK_THAT(log.failure(), Catch::Contains("floating-point"));
  }
  {
    SolverLog log;
    log.add_line("--> FOAM FATAL IO ERROR: ");
    CHECK_THAT(log.failure(), Catch::Contains("fatal error"));
  }
}

TEST_CASE("the tail keeps the last lines only", "[reference][solver_log]") {
  SolverLog log(DivergenceLimits{}, 3);
  for (int i = 0; i < 10; ++i) log.add_line("line " + std::to_string(i));
  CHECK(log.tail() == "    line 7\n    line 8\n    line 9\n");
}

TEST_CASE("durations are formatted for people", "[reference][solver_log]") {
  using hydrojump::reference::format_duration;
  CHECK(format_duration(42.4) == "42 s");
  CHECK(format_duration(185) == "3 min 05 s");
  CHECK(format_duration(3720) == "1 h 02 min");
  CHECK(format_duration(-1) == "?");
}
