// The serial link to the robot for the Tiny Bootloader's uploader: a tty
// (the Bluetooth RFCOMM device or a serial adapter) opened at 115200 raw
// 8N1 by the console's transport (tools/client/transport.hpp).

#pragma once

#include <memory>
#include <string>

#include "tools/flash/tiny_upload.hpp"

namespace aseba::flash
{

// Opens `device` (a path such as /dev/rfcomm0, or the console's
// `ser:device=PATH`); throws std::runtime_error with the system's reason
// when it is no serial device or cannot be opened.
std::unique_ptr<TinyLink> open_tiny_serial_link(const std::string &device);

} // namespace aseba::flash
