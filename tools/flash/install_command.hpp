// `epuck-image install`: the first installation of the factory image
// (epuck-aseba-factory.hex) through the e-puck's factory Tiny Bootloader,
// over a serial device.

#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace aseba::flash
{

// Runs the command with `arguments` (those after `install`): its help or
// progress and the summary on `out`, errors on `err`. Returns the exit
// status: 0 when every row was acknowledged (or for --help), 1 when the
// installation failed, 2 for a usage error or a FACTORY.hex that cannot be
// read or used.
int run_install_command(const std::vector<std::string> &arguments,
                        std::ostream &out,
                        std::ostream &err);

} // namespace aseba::flash
