// `epuck-image install`: the first installation of the factory image
// (epuck-aseba-factory.hex) through the e-puck's factory Tiny Bootloader,
// over a serial device.

#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace aseba::flash
{

// The command's --help text.
extern const char *const install_usage;

// Runs the command with `arguments` (those after `install`): progress and
// the summary on `out`, errors on `err`. Returns the exit status: 0 when
// every row was acknowledged, 1 when the installation failed, 2 for a usage
// error.
int run_install_command(const std::vector<std::string> &arguments,
                        std::ostream &out,
                        std::ostream &err);

} // namespace aseba::flash
