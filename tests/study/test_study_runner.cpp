// The study runner: stages run as child processes, a failing case does not stop the others, finished
// stages are cached by the resolved case's fingerprint, and a changed case runs again.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <random>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <toml++/toml.h>
#include <unistd.h>

#include "util/directory_lock.hpp"
#include "util/fingerprint.hpp"
#include "cases/spec_reader.hpp"
#include "app/generate.hpp"
#include "compare/record.hpp"
#include "app/study.hpp"
#include "tests/temp_dir.hpp"

namespace fs = std::filesystem;
using hydrojump::app::StudyOptions;
using hydrojump::app::run_study;
using hydrojump::testing::TempDir;

namespace {

const std::string mini_study = R"(
[study]
name = "mini"
[resolution.quick]
particle_spacing_m = 0.005
vof_cell_size_bed_m = 0.005
vof_cell_size_bulk_m = 0.01
[[case]]
id = "A"
kind = "stilling_basin"
[case.run]
end_time_s = 1.0
[case.bed]
profile = "smooth"
[case.inflow]
depth_m = 0.0254
velocity_m_s = 2.0
[case.tailwater]
depth_m = TAILWATER
[case.domain]
upstream_length_m = 0.2
basin_length_m = 1.36
downstream_length_m = 0.2
air_height_m = 0.1
[[case]]
id = "B"
kind = "stilling_basin"
[case.run]
end_time_s = 1.0
[case.bed]
profile = "smooth"
[case.inflow]
depth_m = 0.0254
velocity_m_s = 3.0
[case.tailwater]
rule = "belanger"
[case.domain]
upstream_length_m = 0.2
basin_length_m = 2.04
downstream_length_m = 0.25
air_height_m = 0.12
)";

std::vector<std::string> lines_of(const fs::path& p) {
  std::vector<std::string> lines;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

std::string with_tailwater(const std::string& value) {
  std::string s = mini_study;
  s.replace(s.find("TAILWATER"), 9, value);
  return s;
}

// Into the empty directory `dir` (a test's TempDir): the mini study (case A's tailwater `tailwater` in m)
// and a stand-in for the hydrojump executable running the shell script `script`; options to run that
// study into dir/out.
StudyOptions mini_study_with_stand_in(const fs::path& dir, const std::string& script,
                                      const std::string& tailwater = "0.104") {
  const fs::path fake = dir / "fake_hydrojump";
  write(fake, "#!/bin/sh\n" + script);
  fs::permissions(fake, fs::perms::owner_all);
  write(dir / "mini.toml", with_tailwater(tailwater));
  StudyOptions options;
  options.spec = (dir / "mini.toml").string();
  options.out = dir / "out";
  options.executable = fake;
  return options;
}

// A stand-in that records each call in `calls` and fails case B's SPH run after running `on_failure`
// (a shell command in B's sph directory "$2").
StudyOptions mini_study_failing_b_sph(const fs::path& dir, const fs::path& calls, const std::string& on_failure) {
  return mini_study_with_stand_in(dir, "echo \"$*\" >> '" + calls.string() + "'\ncase \"$1 $2\" in\n  \"sph \"*/B/sph) " +
                                           on_failure + " ; exit 3 ;;\nesac\nexit 0\n");
}

// Runs the study in a thread until the stand-in SPH run of case `id` has started (it touches
// "$2/running"), then sends this process `signals` (the study's handlers take them), half a second
// apart, and waits for the study to end. Returns its status; `log` gets its log.
int run_study_stopped_by(const StudyOptions& options, const std::vector<int>& signals, std::ostringstream& log,
                         const std::string& id = "A") {
  int status = -1;
  std::thread study([&] { status = run_study(options, log); });
  const fs::path running = options.out / id / "sph" / "running";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!fs::exists(running) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const bool started = fs::exists(running);
  for (std::size_t k = 0; k < signals.size(); ++k) {
    if (k > 0) std::this_thread::sleep_for(std::chrono::milliseconds(500));
    ::kill(::getpid(), signals[k]);
  }
  study.join();
  REQUIRE(started);
  return status;
}

}  // namespace

TEST_CASE("Study runner: failures are isolated, results cached, changes re-run", "[study]") {
  const TempDir tmp("study");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  // A stand-in for the hydrojump executable: records each call; the SPH run of case B fails, leaving a
  // checkpoint behind as the real solver does.
  StudyOptions options = mini_study_failing_b_sph(dir, calls, "touch \"$2/checkpoint.bin\"; echo 'B diverged'");
  std::ostringstream log;

  // First run: every stage runs; B's SPH fails but B's VOF and comparison still run.
  CHECK(run_study(options, log) == 1);
  auto first = lines_of(calls);
  CHECK(first.size() == 6);
  CHECK(std::count_if(first.begin(), first.end(), [](const std::string& l) { return l.rfind("compare", 0) == 0; }) == 2);
  CHECK(fs::exists(options.out / "A" / "sph" / "case.toml"));
  CHECK(fs::exists(options.out / "study_report.md"));
  CHECK_THAT(log.str(), Catch::Contains("B: sph FAILED (exit status 3)"));
  CHECK_THAT(log.str(), Catch::Contains("B diverged"));

  // Second run: only the failed stage runs again, resuming, and B's comparison is redone after it.
  fs::remove(calls);
  CHECK(run_study(options, log) == 1);
  auto second = lines_of(calls);
  REQUIRE(second.size() == 2);
  CHECK_THAT(second[0], Catch::StartsWith("sph ") && Catch::Contains("/B/sph") && Catch::EndsWith("--resume"));
  CHECK_THAT(second[1], Catch::StartsWith("compare ") && Catch::Contains("/B"));

  // A changed case runs all its stages again; the unchanged one does not. The previous results are
  // kept beside it as <case>.previous.
  write(options.out / "A" / "sph" / "result.txt", "hours of work");
  write(dir / "mini.toml", with_tailwater("0.11"));
  {
    // ... but not while a run started by hand still writes in it: A fails and nothing is moved.
    const hydrojump::util::DirectoryLock by_hand(options.out / "A" / "sph", "hydrojump sph (by hand)");
    std::ostringstream busy_log;
    CHECK(run_study(options, busy_log) == 2);
    CHECK_THAT(busy_log.str(), Catch::Contains("A: FAILED") &&
                                   Catch::Contains("in use by another process (hydrojump sph (by hand)"));
    CHECK(fs::exists(options.out / "A" / "sph" / "result.txt"));
    CHECK_FALSE(fs::exists(options.out / "A.previous"));
  }
  fs::remove(calls);
  run_study(options, log);
  CHECK(fs::exists(options.out / "A.previous" / "sph" / "result.txt"));
  CHECK_FALSE(fs::exists(options.out / "A" / "sph" / "result.txt"));
  CHECK_THAT(log.str(), Catch::Contains("previous results are kept in"));
  auto third = lines_of(calls);
  CHECK(std::count_if(third.begin(), third.end(), [](const std::string& l) { return l.find("/A") != std::string::npos; }) == 3);
  CHECK(std::count_if(third.begin(), third.end(), [](const std::string& l) { return l.find("/B") != std::string::npos; }) == 2);

  // A comparator change (its stamp holds source_fingerprint, the solvers' hold solver_fingerprint):
  // only the comparison runs again; the solver results are kept.
  write(options.out / "A" / "compare.stamp", "written by another comparator");
  fs::remove(calls);
  run_study(options, log);
  auto fourth = lines_of(calls);
  std::vector<std::string> a_calls;
  std::copy_if(fourth.begin(), fourth.end(), std::back_inserter(a_calls),
               [](const std::string& l) { return l.find("/A") != std::string::npos; });
  REQUIRE(a_calls.size() == 1);
  CHECK_THAT(a_calls[0], Catch::StartsWith("compare "));
  CHECK(fs::exists(options.out / "A" / "sph" / "case.toml"));
}

TEST_CASE("Study runner: an SPH run that failed before its first checkpoint is started over with --restart",
          "[study]") {
  const TempDir tmp("study_restart");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  // B's SPH run fails leaving only a diagnosis (no checkpoint.bin to resume from).
  StudyOptions options = mini_study_failing_b_sph(dir, calls, "echo unstable > \"$2/failure.txt\"");
  std::ostringstream log;
  CHECK(run_study(options, log) == 1);
  auto first = lines_of(calls);
  REQUIRE(first.size() == 6);
  for (const auto& call : first) {
    CHECK_THAT(call, !Catch::Contains("--restart"));
    CHECK_THAT(call, !Catch::Contains("--resume"));
  }

  fs::remove(calls);
  CHECK(run_study(options, log) == 1);
  auto second = lines_of(calls);
  REQUIRE(second.size() == 2);
  CHECK_THAT(second[0], Catch::StartsWith("sph ") && Catch::Contains("/B/sph") && Catch::EndsWith("--restart"));
}

TEST_CASE("Study runner: a failed solver stage leaves what stopped it for its record, and a current failed record is run again",
          "[study]") {
  const TempDir tmp("study_failed");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  // B's SPH run fails with a diagnosis, as the real solver writes it.
  StudyOptions options = mini_study_failing_b_sph(
      dir, calls, "printf 'went unstable at t = 0.5 s\\n  |rho/rho0 - 1| = 0.6\\n' > \"$2/failure.txt\"; echo 'last words'");
  options.sph_threads = 1;
  std::ostringstream log;
  CHECK(run_study(options, log) == 1);
  const fs::path failed = options.out / "B" / "sph.failed";
  REQUIRE(fs::exists(failed));
  CHECK_FALSE(fs::exists(options.out / "A" / "sph.failed"));
  CHECK_FALSE(fs::exists(options.out / "B" / "vof.failed"));
  const toml::table t = toml::parse_file(failed.string());
  const auto study = hydrojump::cases::load_study(options.spec);
  const std::string key = hydrojump::app::method_run_key(study, *study.find_case("B"), "quick", "sph");
  CHECK(t["run_key"].value_or(std::string()) == key);
  CHECK(t["failure"].value_or(std::string()) == "went unstable at t = 0.5 s");
  CHECK(t["legs"].value_or(0) == 1);
  CHECK(t["threads"].value_or(0) == 1);
  CHECK(t["wall_time_s"].value_or(-1.0) >= 0.0);

  // Without a diagnosis of this leg (an old failure.txt), the log's last line and the exit status.
  fs::last_write_time(options.out / "B" / "sph" / "failure.txt", fs::file_time_type::clock::now() - std::chrono::hours(1));
  StudyOptions quiet = mini_study_failing_b_sph(dir, calls, "echo 'second words'");
  quiet.out = options.out;
  CHECK(run_study(quiet, log) == 1);
  const toml::table second = toml::parse_file(failed.string());
  CHECK(second["failure"].value_or(std::string()) == "exit status 3: second words");
  CHECK(second["legs"].value_or(0) == 1);  // no checkpoint to resume: the run started over (--restart)

  // The record of the failed run is current, but a study with it runs the case again (a record of a
  // failure holds no results to import).
  const fs::path records = dir / "records";
  hydrojump::compare::ValidationRecord r;
  r.study = "mini";
  r.case_id = "B";
  r.method = "sph";
  r.resolution = "quick";
  r.run_key = key;
  r.failure = "went unstable at t = 0.5 s";
  r.window_start_s = 0.0;
  r.window_end_s = 1.0;
  hydrojump::compare::write_record(records, r);
  fs::remove(calls);
  StudyOptions again = mini_study_with_stand_in(dir, "echo \"$*\" >> '" + calls.string() + "'\nexit 0\n");
  again.out = dir / "out2";
  again.records = records;
  again.methods = {"sph"};
  std::ostringstream rerun;
  CHECK(run_study(again, rerun) == 0);
  CHECK_THAT(rerun.str(), Catch::Contains("B: record " + (records / "mini" / "B" / "sph-quick.toml").string() +
                                          " is of a run that failed (went unstable at t = 0.5 s): running it"));
  const auto ran = lines_of(calls);
  CHECK(std::count_if(ran.begin(), ran.end(), [](const std::string& l) { return l.rfind("sph ", 0) == 0 && l.find("/B/sph") != std::string::npos; }) == 1);
  // The stage that now finished leaves no failure behind.
  CHECK_FALSE(fs::exists(again.out / "B" / "sph.failed"));
}

TEST_CASE("Study runner: the report covers cases run earlier into the same directory while they are current",
          "[study]") {
  const TempDir tmp("study_earlier");
  const fs::path& dir = tmp.path();
  StudyOptions options = mini_study_with_stand_in(dir, "exit 0\n");  // every stage succeeds
  std::ostringstream log;
  const auto report_rows = [&](const std::string& id) {  // the case's rows of the "Runs" table
    std::vector<std::string> rows;
    bool in_runs = false;
    for (const auto& line : lines_of(options.out / "study_report.md")) {
      if (line.rfind("## ", 0) == 0) in_runs = line == "## Runs";
      if (in_runs && line.rfind("| " + id + " | ", 0) == 0) rows.push_back(line);
    }
    return rows;
  };

  options.cases = {"A"};
  REQUIRE(run_study(options, log) == 0);
  CHECK(report_rows("A").size() == 3);  // sph, vof, compare
  CHECK(report_rows("B").empty());      // never run

  // B alone: A's comparison is current, so the report lists it as an earlier run.
  options.cases = {"B"};
  REQUIRE(run_study(options, log) == 0);
  CHECK(report_rows("B").size() == 3);
  const auto a_rows = report_rows("A");
  REQUIRE(a_rows.size() == 1);
  CHECK_THAT(a_rows[0], Catch::StartsWith("| A | compare | earlier run |"));

  // A changed case's old comparison is stale: not reported.
  write(dir / "mini.toml", with_tailwater("0.11"));
  REQUIRE(run_study(options, log) == 0);
  CHECK(report_rows("A").empty());
  CHECK(report_rows("B").size() == 3);
}

TEST_CASE("Study runner: a case named twice in --cases runs once, an unknown one is refused by name", "[study]") {
  // Two workers on one case would share its directory (`--cases X,X --jobs 2` raced on case.toml).
  const auto study = hydrojump::cases::load_study(std::string(HYDROJUMP_SOURCE_DIR) + "/tests/data/basins.toml");
  const auto selected = hydrojump::app::select_cases(study, {"B", "A", "B", "A"});
  REQUIRE(selected.size() == 2u);
  CHECK(selected[0]->id == "B");
  CHECK(selected[1]->id == "A");
  CHECK_THROWS_WITH(hydrojump::app::select_cases(study, {"A", ""}),
                    Catch::Contains("case \"\": no such case") && Catch::Contains("A_smooth"));
  // "all" is every case, as the README's `--cases all` says; it is not a case id among others.
  CHECK(hydrojump::app::select_cases(study, {"all"}).size() == study.cases.size());
  CHECK_THROWS_WITH(hydrojump::app::select_cases(study, {"A", "all"}),
                    Catch::Contains("case \"all\" selects every case and cannot be combined with other case ids"));
}

TEST_CASE("Study runner: what only the solvers' derivations refuse stops the study before it runs or moves anything", "[study]") {
  // A VOF bed cell of 2 cm leaves fewer than 2 cells across y1 = 25.4 mm: the spec's rules pass, the
  // OpenFOAM mesh plan refuses. The study used to find it only when it reached the case, after
  // moving that case's earlier results aside.
  const TempDir tmp("study_derived");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  const StudyOptions options = mini_study_with_stand_in(dir, "echo \"$*\" >> '" + calls.string() + "'\nexit 0\n");
  std::ostringstream log;
  REQUIRE(run_study(options, log) == 0);
  write(options.out / "A" / "sph" / "result.txt", "hours of work");
  std::string coarse = with_tailwater("0.11");
  const std::string cells = "vof_cell_size_bed_m = 0.005\nvof_cell_size_bulk_m = 0.01";
  REQUIRE(coarse.find(cells) != std::string::npos);
  coarse.replace(coarse.find(cells), cells.size(), "vof_cell_size_bed_m = 0.02\nvof_cell_size_bulk_m = 0.02");
  write(dir / "mini.toml", coarse);
  fs::remove(calls);
  CHECK_THROWS_WITH(run_study(options, log), Catch::Contains("mini.toml: case \"A\" at resolution \"quick\": ") &&
                                                 Catch::Contains("inflow depth"));
  CHECK_FALSE(fs::exists(calls));
  CHECK(fs::exists(options.out / "A" / "sph" / "result.txt"));
  CHECK_FALSE(fs::exists(options.out / "A.previous"));
}

TEST_CASE("Study runner validates before running anything", "[study]") {
  const TempDir tmp("study_invalid");
  const fs::path& dir = tmp.path();
  const StudyOptions options = mini_study_with_stand_in(dir, "exit 1\n", "-1");
  std::ostringstream log;
  CHECK_THROWS_WITH(run_study(options, log), Catch::Contains("tailwater.depth_m = -1"));
  CHECK_FALSE(fs::exists(options.out));
}

TEST_CASE("Study runner: a second study on the same output directory stops before running anything", "[study]") {
  const TempDir tmp("study_busy");
  const fs::path& dir = tmp.path();
  const StudyOptions options = mini_study_with_stand_in(dir, "exit 1\n");
  const hydrojump::util::DirectoryLock first(options.out, "hydrojump study (the first)");
  std::ostringstream log;
  CHECK_THROWS_WITH(run_study(options, log), Catch::Contains(options.out.string() + " is in use by another process "
                                                             "(hydrojump study (the first), pid"));
  CHECK(log.str().empty());  // nothing started
}

TEST_CASE("Study runner: --methods runs only the chosen solvers, --force re-runs cached stages, --jobs runs stages side by side",
          "[study]") {
  const TempDir tmp("study_options");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  // Each call is recorded and takes 0.5 s; while the file "overlap" exists, a call also waits (up to
  // 30 s) until two calls have started, so that two cases run side by side overlap however slowly the
  // study starts its second case (a loaded machine, a sanitizer build).
  const fs::path overlap = dir / "overlap";
  StudyOptions options = mini_study_with_stand_in(
      dir, "echo \"start $*\" >> '" + calls.string() + "'\nsleep 0.5\ni=0\nwhile [ -e '" + overlap.string() +
               "' ] && [ \"$(grep -c '^start' '" + calls.string() + "')\" -lt 2 ] && [ $i -lt 600 ]; do sleep 0.05; i=$((i + 1)); done\n"
               "echo \"end $*\" >> '" + calls.string() + "'\nexit 0\n");
  std::ostringstream log;
  const auto starts = [&] {
    std::vector<std::string> s;
    for (const auto& l : lines_of(calls))
      if (l.rfind("start ", 0) == 0) s.push_back(l.substr(6));
    return s;
  };

  // --methods sph: no OpenFOAM stage at all; the comparison still runs (on the SPH result alone).
  options.methods = {"sph"};
  REQUIRE(run_study(options, log) == 0);
  auto run = starts();
  CHECK(run.size() == 4);  // sph and compare for A and B
  // One job: the SPH runs keep their own thread default (OMP_NUM_THREADS or all cores).
  CHECK(std::none_of(run.begin(), run.end(), [](const std::string& l) { return l.find("--threads") != std::string::npos; }));
  CHECK(std::none_of(run.begin(), run.end(), [](const std::string& l) { return l.rfind("vof ", 0) == 0; }));

  // Cached: nothing runs; --force runs every stage again.
  fs::remove(calls);
  REQUIRE(run_study(options, log) == 0);
  CHECK(starts().empty());
  options.force = true;
  REQUIRE(run_study(options, log) == 0);
  CHECK(starts().size() == 4);

  // --jobs 2: the two cases' first stages start before either ends.
  fs::remove(calls);
  options.jobs = 2;
  write(overlap, "");
  REQUIRE(run_study(options, log) == 0);
  fs::remove(overlap);
  const auto lines = lines_of(calls);
  REQUIRE(lines.size() >= 2);
  CHECK(lines[0].rfind("start ", 0) == 0);
  CHECK(lines[1].rfind("start ", 0) == 0);
  // ... and the cores are shared out: each SPH run gets cores / 2 threads (at least one).
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const std::string shared = "--threads " + std::to_string(std::max(1, cores / 2));
  run = starts();
  CHECK(std::count_if(run.begin(), run.end(), [&](const std::string& l) {
          return l.rfind("sph ", 0) == 0 && l.find(shared) != std::string::npos;
        }) == 2);
  // --threads sets them.
  fs::remove(calls);
  options.sph_threads = 3;
  REQUIRE(run_study(options, log) == 0);
  run = starts();
  CHECK(std::count_if(run.begin(), run.end(), [](const std::string& l) {
          return l.rfind("sph ", 0) == 0 && l.find("--threads 3") != std::string::npos;
        }) == 2);

  // One job: the larger case (B: a longer basin at a higher speed) runs first, each case's comparison
  // right after its solver stage; the report keeps the spec's order.
  fs::remove(calls);
  options.jobs = 1;
  options.sph_threads = 0;
  REQUIRE(run_study(options, log) == 0);
  run = starts();
  REQUIRE(run.size() == 4);
  CHECK(run[0].find("sph ") == 0);
  CHECK(run[0].find("/B/sph") != std::string::npos);
  CHECK(run[1].find("compare ") == 0);
  CHECK(run[1].find("/B") != std::string::npos);
  CHECK(run[2].find("/A/sph") != std::string::npos);
  const std::string report = hydrojump::util::read_text_file(options.out / "study_report.md");
  const auto a_row = report.find("| A | sph |"), b_row = report.find("| B | sph |");
  CHECK(a_row < b_row);

  // --jobs 2 on one case: its SPH and OpenFOAM runs side by side, its comparison after both ended.
  fs::remove(calls);
  options.jobs = 2;
  options.methods = {"sph", "vof"};
  options.cases = {"A"};
  write(overlap, "");
  REQUIRE(run_study(options, log) == 0);
  fs::remove(overlap);
  const auto both = lines_of(calls);
  REQUIRE(both.size() == 6);
  CHECK(both[0].rfind("start ", 0) == 0);
  CHECK(both[1].rfind("start ", 0) == 0);
  const std::string first_two = both[0] + "\n" + both[1];
  CHECK_THAT(first_two, Catch::Contains("start sph ") && Catch::Contains("start vof "));
  CHECK(both[4].rfind("start compare ", 0) == 0);
}

TEST_CASE("Study runner: the SPH threads of each job", "[study]") {
  using hydrojump::app::sph_threads_per_job;
  CHECK(sph_threads_per_job(3, 2, 2) == 3);  // asked for
  CHECK(sph_threads_per_job(0, 1, 2) == 0);  // one job: the solver's default
  CHECK(sph_threads_per_job(0, 2, 2) == 1);
  CHECK(sph_threads_per_job(0, 2, 8) == 4);
  CHECK(sph_threads_per_job(0, 3, 2) == 1);  // more jobs than cores: one each
}

TEST_CASE("Study runner: the solver stages at once", "[study]") {
  using hydrojump::app::stage_jobs;
  CHECK(stage_jobs(0, 1, 2, 20) == 2);    // one per core
  CHECK(stage_jobs(0, 4, 16, 20) == 4);   // one per --np (or --threads) cores
  CHECK(stage_jobs(0, 4, 2, 20) == 1);    // at least one
  CHECK(stage_jobs(0, 1, 16, 4) == 4);    // no more than there are stages to run
  CHECK(stage_jobs(0, 1, 16, 1) == 1);    // one left to run (the others cached): it gets all the cores
  CHECK(stage_jobs(3, 1, 2, 20) == 3);    // asked for
  CHECK(stage_jobs(3, 1, 2, 0) == 1);
}

TEST_CASE("Study runner: a reworded description or a relaxed stability limit keeps the solver results, and hand-made results are kept",
          "[study]") {
  const TempDir tmp("study_wording");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  // The stand-in fails A's SPH run once (leaving a checkpoint, as a run stopped at the density limit
  // does) while dir/fail_A exists.
  StudyOptions options = mini_study_with_stand_in(
      dir, "echo \"$*\" >> '" + calls.string() + "'\ncase \"$1 $2\" in\n  \"sph \"*/A/sph) if [ -e '" +
               (dir / "fail_A").string() + "' ]; then touch \"$2/checkpoint.bin\"; exit 1; fi ;;\nesac\nexit 0\n");
  write(dir / "fail_A", "");
  std::ostringstream log;
  CHECK(run_study(options, log) == 1);

  // Another description and a relaxed density limit: no directory is moved, A's SPH run resumes, B's
  // solver stages stay cached, both comparisons run again, and the case.toml has the new description.
  fs::remove(calls);
  fs::remove(dir / "fail_A");
  std::string text = with_tailwater("0.104");
  text.replace(text.find("name = \"mini\""), 13, "name = \"mini\"\ndescription = \"reworded\"\n[sph]\nmax_density_variation = 0.4");
  write(dir / "mini.toml", text);
  CHECK(run_study(options, log) == 0);
  const auto second = lines_of(calls);
  CHECK(second.size() == 3);
  CHECK(std::count(second.begin(), second.end(), "sph " + (options.out / "A" / "sph").string() + " --resume") == 1);
  CHECK(std::count_if(second.begin(), second.end(), [](const std::string& l) { return l.rfind("compare", 0) == 0; }) == 2);
  CHECK_FALSE(fs::exists(options.out / "A.previous"));
  CHECK_FALSE(fs::exists(options.out / "B.previous"));
  CHECK_THAT(hydrojump::util::read_text_file(options.out / "B" / "sph" / "case.toml"), Catch::Contains("description = \"reworded\""));
  CHECK_THAT(log.str(), Catch::Contains("inputs rewritten, results kept"));

  // A setting that changes the run still starts the case afresh (previous results kept aside).
  fs::remove(calls);
  text.replace(text.find("max_density_variation = 0.4"), 27, "cfl_number = 0.1");
  write(dir / "mini.toml", text);
  CHECK(run_study(options, log) == 0);
  CHECK(lines_of(calls).size() == 6);
  CHECK(fs::exists(options.out / "A.previous"));

  // Results made by hand (generate and sph run outside the study: no stamps) are kept aside, not
  // deleted, when the study starts the case.
  const fs::path by_hand = dir / "by_hand";
  fs::create_directories(by_hand / "A" / "sph");
  write(by_hand / "A" / "sph" / "case.toml", "[case.run]\nend_time_s = 1.0\n");
  write(by_hand / "A" / "sph" / "summary.json", "{\"hours\": 3}\n");
  options.out = by_hand;
  options.cases = {"A"};
  CHECK(run_study(options, log) == 0);
  CHECK(hydrojump::util::read_text_file(by_hand / "A.previous" / "sph" / "summary.json") == "{\"hours\": 3}\n");
}

TEST_CASE("Study runner: a stop request stops the running stage with its state written and starts no other",
          "[study]") {
  const TempDir tmp("study-stop");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  // The stand-in's SPH run goes on until it gets SIGTERM, which it records (the real one writes a
  // checkpoint) before it exits as a stopped process does.
  StudyOptions options = mini_study_with_stand_in(
      dir, "echo \"$*\" >> '" + calls.string() + "'\ncase \"$1\" in\n  sph) trap 'echo TERM > \"$2/term\"; touch \"$2/checkpoint.bin\"; exit 143' TERM\n"
           "    touch \"$2/running\"\n    while true; do sleep 0.05; done ;;\nesac\nexit 0\n");
  options.cases = {"A", "B"};
  std::ostringstream log;
  // As `kill -TERM <study>`: the signal reaches the study alone (its stages run in their own groups).
  // One job: the larger case, B (a longer basin at a higher speed), runs first.
  const int status = run_study_stopped_by(options, {SIGTERM}, log, "B");
  INFO(log.str());
  CHECK(status == 128 + SIGTERM);
  CHECK(fs::exists(options.out / "B" / "sph" / "term"));  // passed on to the stage
  CHECK(fs::exists(options.out / "B" / "sph.started"));  // the next study resumes it
  CHECK_THAT(log.str(), Catch::Contains("B: sph stopped on request") && Catch::Contains("study stopped by SIGTERM"));
  // Nothing after it: not B's VOF run or comparison, not case A.
  const auto called = lines_of(calls);
  REQUIRE(called.size() == 1);
  CHECK(called.front().rfind("sph ", 0) == 0);
  const std::string report = hydrojump::util::read_text_file(options.out / "study_report.md");
  CHECK_THAT(report, Catch::Contains("| B | sph | stopped |") &&
                         Catch::Contains("| B | vof | skipped (the study was stopped) |") &&
                         Catch::Contains("| B | compare | skipped |") &&
                         Catch::Contains("| A | sph | skipped (the study was stopped) |") &&
                         Catch::Contains("| A | vof | skipped (the study was stopped) |"));

  // The next study resumes the run (a stand-in that finishes after 0.3 s): its stage's wall time counts
  // both legs.
  const double first_leg = [&] {
    std::istringstream in(hydrojump::util::read_text_file(options.out / "B" / "sph.legs"));
    double seconds = -1.0;
    int legs = 0;
    in >> seconds >> legs;
    CHECK(legs == 1);
    return seconds;
  }();
  CHECK(first_leg > 0.0);
  write(dir / "fake_hydrojump", "#!/bin/sh\necho \"$*\" >> '" + calls.string() + "'\nsleep 0.3\nexit 0\n");
  options.cases = {"B"};
  std::ostringstream resumed;
  REQUIRE(run_study(options, resumed) == 0);
  INFO(resumed.str());
  CHECK(lines_of(calls).at(1).find("--resume") != std::string::npos);
  const auto info = toml::parse_file((options.out / "B" / "sph.stage.toml").string());
  CHECK(info["legs"].value_or(0) == 2);
  CHECK_THAT(info["machine"].value_or(std::string()), Catch::EndsWith(" cores"));
  CHECK(info["wall_time_s"].value_or(0.0) >= first_leg + 0.3);
  CHECK_FALSE(fs::exists(options.out / "B" / "sph.legs"));
  // Legs left over beside a stage that then runs from the beginning (no started marker: not a resume)
  // are not counted.
  write(options.out / "B" / "vof.legs", "100 3\n");
  fs::remove(options.out / "B" / "vof.stamp");
  std::ostringstream again;
  REQUIRE(run_study(options, again) == 0);
  const auto vof_info = toml::parse_file((options.out / "B" / "vof.stage.toml").string());
  CHECK(vof_info["legs"].value_or(0) == 1);
  CHECK(vof_info["wall_time_s"].value_or(1e9) < 100.0);
  // A VOF stage that ran in one leg.
  CHECK(toml::parse_file((options.out / "B" / "vof.stage.toml").string())["legs"].value_or(0) == 1);
}

TEST_CASE("Study runner: an output directory OpenFOAM cannot run in is refused before anything runs", "[study]") {
  const TempDir tmp("study-blank");
  StudyOptions options = mini_study_with_stand_in(tmp.path(), "exit 0\n");
  options.out = tmp.path() / "my study";
  std::ostringstream log;
  CHECK_THROWS_WITH(run_study(options, log), Catch::Contains("--out " + options.out.string()) &&
                                                 Catch::Contains("its path holds a blank") &&
                                                 Catch::Contains("--methods sph"));
  CHECK_FALSE(fs::exists(options.out));
  // The SPH solver has no such limit.
  options.methods = {"sph"};
  CHECK(run_study(options, log) == 0);
  // A file where the study directory should be.
  options.out = tmp.path() / "a_file";
  write(options.out, "not a directory\n");
  CHECK_THROWS_WITH(run_study(options, log),
                    Catch::Contains("--out " + options.out.string() + ": cannot be made a study directory (a file of that name is there)"));
}

TEST_CASE("Study runner: a stop request stops both solver stages of a case run side by side and skips its comparison",
          "[study]") {
  const TempDir tmp("study-stop-both");
  const fs::path& dir = tmp.path();
  // Both stand-in solvers go on until SIGTERM, which they record before exiting as stopped runs do.
  StudyOptions options = mini_study_with_stand_in(
      dir, "case \"$1\" in\n  sph|vof) trap 'echo TERM > \"$2/term\"; exit 143' TERM\n"
           "    touch \"$2/running\"\n    while true; do sleep 0.05; done ;;\nesac\nexit 0\n");
  options.cases = {"A"};
  options.jobs = 2;
  // Wait for the OpenFOAM stand-in too before the signal.
  const fs::path vof_running = options.out / "A" / "vof" / "running";
  std::ostringstream log;
  int status = -1;
  std::thread study([&] { status = run_study(options, log); });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!(fs::exists(vof_running) && fs::exists(options.out / "A" / "sph" / "running")) &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const bool both_started = fs::exists(vof_running) && fs::exists(options.out / "A" / "sph" / "running");
  ::kill(::getpid(), SIGTERM);
  study.join();
  REQUIRE(both_started);
  INFO(log.str());
  CHECK(status == 128 + SIGTERM);
  for (const char* method : {"sph", "vof"}) {
    CHECK(fs::exists(options.out / "A" / method / "term"));
    CHECK(fs::exists(options.out / "A" / (std::string(method) + ".started")));  // the next study resumes it
    CHECK(fs::exists(options.out / "A" / (std::string(method) + ".legs")));
  }
  CHECK_FALSE(fs::exists(options.out / "A" / "compare.stamp"));
  const std::string report = hydrojump::util::read_text_file(options.out / "study_report.md");
  CHECK_THAT(report, Catch::Contains("| A | sph | stopped |") && Catch::Contains("| A | vof | stopped |") &&
                         Catch::Contains("| A | compare | skipped |"));
}

TEST_CASE("Study runner: a changed case whose new directory no solver ran in does not replace the kept results",
          "[study]") {
  const TempDir tmp("study-previous");
  const fs::path& dir = tmp.path();
  StudyOptions options = mini_study_with_stand_in(dir, "exit 0\n");
  options.cases = {"A"};
  options.methods = {"sph"};
  std::ostringstream log;
  REQUIRE(run_study(options, log) == 0);
  write(options.out / "A" / "sph" / "result.txt", "hours of work");
  write(dir / "mini.toml", with_tailwater("0.11"));  // changed: A's results are kept aside
  REQUIRE(run_study(options, log) == 0);
  REQUIRE(fs::exists(options.out / "A.previous" / "sph" / "result.txt"));
  // As a study stopped after preparing A and before its solver ran: generated, no stamp, no results.
  for (const char* file : {"sph.stamp", "sph.started", "compare.stamp"}) fs::remove(options.out / "A" / file);
  write(dir / "mini.toml", with_tailwater("0.12"));
  REQUIRE(run_study(options, log) == 0);
  CHECK(fs::exists(options.out / "A.previous" / "sph" / "result.txt"));
  CHECK(fs::exists(options.out / "A" / "sph.stamp"));
}

TEST_CASE("Study runner: a second stop request stops a stage that does not stop on the first", "[study]") {
  const TempDir tmp("study-stop-twice");
  const fs::path& dir = tmp.path();
  // The stand-in's SPH run ignores SIGTERM (a stage stuck while writing its state).
  StudyOptions options = mini_study_with_stand_in(
      dir, "case \"$1\" in\n  sph) trap '' TERM\n    touch \"$2/running\"\n    while true; do sleep 0.05; done ;;\nesac\nexit 0\n");
  options.cases = {"A"};
  std::ostringstream log;
  const int status = run_study_stopped_by(options, {SIGINT, SIGINT}, log);  // Ctrl-C twice
  INFO(log.str());
  CHECK(status == 128 + SIGINT);
  CHECK_THAT(log.str(), Catch::Contains("A: sph stopped on request") && Catch::Contains("study stopped by SIGINT"));
}

TEST_CASE("Study runner: a case whose records match is imported instead of run and a stale record is named and the case runs",
          "[study]") {
  const TempDir tmp("study_records");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  // A stand-in whose comparison writes the metrics table a real one would.
  StudyOptions options = mini_study_with_stand_in(
      dir, "echo \"$*\" >> '" + calls.string() + "'\nif [ \"$1\" = compare ]; then mkdir -p \"$2/csv\"; printf '"
           "quantity,unit,sph,vof,experiment,published_sph,smooth_theory,status\\nsequent_depth,m,0.11,0.12,0.104,nan,"
           "0.13,predicted\\neta,%%,45,44,48.43,47.08,39.2,predicted\\n' > \"$2/csv/metrics.csv\"; fi\nexit 0\n");
  std::ostringstream log;
  REQUIRE(run_study(options, log) == 0);
  const fs::path records = dir / "records";
  for (const char* id : {"A", "B"})
    for (auto r : hydrojump::compare::records_from_case_dir(options.out / id, {"2026-11-29", "test"}))
      hydrojump::compare::write_record(records, r);
  CHECK(fs::exists(records / "mini" / "A" / "sph-quick.toml"));
  CHECK(fs::exists(records / "mini" / "B" / "vof-quick.toml"));

  // Into a fresh directory with the records: nothing runs, and the report has the recorded values.
  fs::remove(calls);
  options.out = dir / "out2";
  options.records = records;
  std::ostringstream imported;
  CHECK(run_study(options, imported) == 0);
  CHECK_FALSE(fs::exists(calls));
  CHECK_THAT(imported.str(), Catch::Contains("A: imported from") && Catch::Contains("(not run)"));
  CHECK_THAT(hydrojump::util::read_text_file(options.out / "A" / "csv" / "metrics.csv"),
             Catch::Contains("sequent_depth,m,0.11,0.12,0.104"));
  CHECK_THAT(hydrojump::util::read_text_file(options.out / "study_report.md"),
             Catch::Contains("| A | sph | imported (record of 2026-11-29) |"));

  // A changed case: its records are stale (another run key), it runs; B is still imported.
  write(dir / "mini.toml", with_tailwater("0.11"));
  std::ostringstream stale;
  CHECK(run_study(options, stale) == 0);
  CHECK_THAT(stale.str(), Catch::Contains("A: record " + (records / "mini" / "A" / "sph-quick.toml").string() + " is stale"));
  CHECK_THAT(stale.str(), Catch::Contains("B: imported from"));
  const auto ran = lines_of(calls);
  CHECK(std::count_if(ran.begin(), ran.end(), [](const std::string& l) { return l.find("/A") != std::string::npos; }) == 3);
  CHECK(std::count_if(ran.begin(), ran.end(), [](const std::string& l) { return l.find("/B") != std::string::npos; }) == 0);
}

TEST_CASE("Study runner: a record's key is its own method's: the other solver's settings leave it current", "[study]") {
  using hydrojump::app::method_run_key;
  using hydrojump::cases::parse_study;
  const auto key = [](const std::string& text, const char* method) {
    const auto s = parse_study(text, "mini.toml", ".");
    return method_run_key(s, s.cases.at(0), "quick", method);
  };
  const std::string base = with_tailwater("0.11");
  const std::string vof_changed = "[vof]\nmax_courant = 0.5\n" + base;
  const std::string sph_changed = "[sph]\ncfl_number = 0.15\n" + base;
  const std::string case_changed = with_tailwater("0.12");
  CHECK(key(vof_changed, "sph") == key(base, "sph"));
  CHECK(key(vof_changed, "vof") != key(base, "vof"));
  CHECK(key(sph_changed, "vof") == key(base, "vof"));
  CHECK(key(sph_changed, "sph") != key(base, "sph"));
  CHECK(key(case_changed, "sph") != key(base, "sph"));
  CHECK(key(case_changed, "vof") != key(base, "vof"));
  const auto s = parse_study(base, "mini.toml", ".");
  CHECK_THROWS_AS(method_run_key(s, s.cases.at(0), "quick", "lbm"), std::invalid_argument);
}

namespace {

// Every file under `top` whose name marks a temporary of an atomic write (util/atomic_file.hpp).
std::vector<std::string> temporaries_under(const fs::path& top) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(top))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) found.push_back(e.path().string());
  return found;
}

}  // namespace

// The study killed outright (SIGKILL: no handler runs, its stages get SIGTERM from Linux) at random
// moments, again and again, and started once more each time, finishes every stage once, with its
// stamps whole: a further study finds everything current and runs nothing. The stand-in's solver
// stages take 0.3 s in steps whose progress they save atomically (as a checkpoint), resume from it, and
// write their result at the end; its comparison takes 0.1 s.
TEST_CASE("Study runner: killed at random moments and started again each time it finishes every stage and runs nothing more",
          "[study][kills]") {
  const TempDir tmp("study-kills");
  const fs::path& dir = tmp.path();
  const fs::path calls = dir / "calls.txt";
  const std::string stage =
      "echo \"$*\" >> '" + calls.string() + "'\n"
      "case \"$1\" in\n"
      "  sph|vof)\n"
      "    n=0; if [ \"$3\" = --resume ] && [ -f \"$2/progress\" ]; then n=$(cat \"$2/progress\"); fi\n"
      "    while [ \"$n\" -lt 6 ]; do sleep 0.05; n=$((n + 1)); echo $n > \"$2/.progress.new\"; mv \"$2/.progress.new\" \"$2/progress\"; done\n"
      "    echo \"$1 done\" > \"$2/.result.new\"; mv \"$2/.result.new\" \"$2/result.txt\"; echo \"finished $1 $2\" >> '" + calls.string() + "' ;;\n"
      "  compare) sleep 0.1; echo compared > \"$2/.compared.new\"; mv \"$2/.compared.new\" \"$2/compared.txt\" ;;\n"
      "esac\nexit 0\n";
  StudyOptions options = mini_study_with_stand_in(dir, stage);

  const char* fixed_seed = std::getenv("HYDROJUMP_KILL_SEED");
  const unsigned seed = fixed_seed ? static_cast<unsigned>(std::strtoul(fixed_seed, nullptr, 10)) : std::random_device{}();
  INFO("kill seed " << seed << " (HYDROJUMP_KILL_SEED repeats it)");
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> delay_ms(20, 250);
  int kills = 0;
  for (int attempt = 0; kills < 20 && attempt < 100; ++attempt) {
    const pid_t study = ::fork();
    REQUIRE(study >= 0);
    if (study == 0) {
      std::ostringstream ignored;
      ::_exit(run_study(options, ignored));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(random)));
    ::kill(study, SIGKILL);
    int status = 0;
    ::waitpid(study, &status, 0);
    if (WIFEXITED(status)) break;  // it finished before the kill
    ++kills;
  }
  CHECK(kills >= 20);
  // What a study killed inside an atomic write leaves (a pid no process has: above the kernel's pid_max).
  const std::string dead = std::to_string((1 << 22) + 99);
  write(options.out / (".study_report.md.tmp." + dead + ".0"), "half");
  if (fs::is_directory(options.out / "A")) write(options.out / "A" / (".compare.stamp.tmp." + dead + ".3"), "half");
  std::ostringstream log;
  REQUIRE(run_study(options, log) == 0);
  INFO(log.str());
  for (const char* id : {"A", "B"}) {
    CHECK(hydrojump::util::read_text_file(options.out / id / "sph" / "result.txt") == "sph done\n");
    CHECK(hydrojump::util::read_text_file(options.out / id / "vof" / "result.txt") == "vof done\n");
    CHECK(hydrojump::util::read_text_file(options.out / id / "compared.txt") == "compared\n");
  }
  const auto called = lines_of(calls);
  // Each solver stage finished, and was not run again once the study had recorded it: at most once more
  // (a kill between a stage's end and the study's record of it runs it again, resumed, which ends at once).
  for (const char* id : {"/A/sph", "/A/vof", "/B/sph", "/B/vof"}) {
    const auto finished = std::count_if(called.begin(), called.end(), [&](const std::string& l) {
      return l.rfind("finished", 0) == 0 && l.find(id) != std::string::npos;
    });
    CHECK(finished >= 1);
    CHECK(finished <= 2);
  }
  CHECK(temporaries_under(options.out).empty());
  // Everything current: a further study runs nothing.
  fs::remove(calls);
  std::ostringstream again;
  CHECK(run_study(options, again) == 0);
  CHECK_FALSE(fs::exists(calls));
}
