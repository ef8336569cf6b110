#include "compare/cli.hpp"

namespace hydrojump::compare {

void register_commands(CLI::App& /*app*/) {}

}  // namespace hydrojump::compare
