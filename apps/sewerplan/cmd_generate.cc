// SPDX-License-Identifier: MIT
// sewerplan generate: filled in when the generator lands.
#include "command.h"

namespace sewerplan::cli {
void add_generate_command(CLI::App&, Context&) {}
}  // namespace sewerplan::cli
