// hydrojump — side-by-side SPH and OpenFOAM studies of hydraulic jumps on corrugated stilling-basin beds.
#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "util/child_process.hpp"
#include "cases/spec_reader.hpp"
#include "compare/cli.hpp"
#include "app/generate.hpp"
#include "app/record_cli.hpp"
#include "app/study.hpp"
#include "hydrojump/version.hpp"
#include "reference/cli.hpp"
#include "sph/cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "hydrojump: hydraulic jumps in stilling basins (smooth and sinusoidal corrugated beds) run with a\n"
      "weakly compressible SPH solver and with an OpenFOAM interFoam (VOF) reference, both generated from\n"
      "one study spec (TOML), then compared on common sections against laboratory data.\n\n"
      "Typical use:\n"
      "  hydrojump check cases/ead2002.toml\n"
      "  hydrojump generate cases/ead2002.toml --out runs --case A --resolution quick\n"
      "  hydrojump sph runs/A/sph\n"
      "  hydrojump vof runs/A/vof\n"
      "  hydrojump compare runs/A\n"
      "  hydrojump study cases/ead2002.toml --resolution quick\n",
      "hydrojump"};
  app.set_version_flag("--version", std::string("hydrojump ") + hydrojump::version_string);
  app.require_subcommand(1);

  hydrojump::app::register_case_commands(app);
  hydrojump::sph::register_commands(app);
  hydrojump::reference::register_commands(app);
  hydrojump::compare::register_commands(app);
  hydrojump::app::register_study_command(app);
  hydrojump::app::register_record_commands(app);

  // A mistyped command is named as such (CLI11 itself says only "A subcommand is required").
  if (argc > 1 && argv[1][0] != '-') {
    std::string commands;
    bool known = false;
    for (const CLI::App* command : app.get_subcommands({})) {
      known = known || command->get_name() == argv[1];
      commands += (commands.empty() ? "" : ", ") + command->get_name();
    }
    if (!known) {
      std::cerr << "hydrojump: unknown command \"" << argv[1] << "\" (commands: " << commands
                << "; hydrojump --help explains them)\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return app.exit(e);  // a command's own exit status (128 + signal after a stop, a study's failures)
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a command-line mistake exits 2, the usage-error status (as an
    // invalid spec does), instead of CLI11's own codes (104-114).
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const hydrojump::cases::SpecError& e) {
    std::cerr << "hydrojump: invalid spec: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "hydrojump: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
