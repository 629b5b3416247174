// The reference implementation as a second judge of the node's frames:
// Debian's Aseba message library (libasebacommon), which upstream hosts use
// to read every frame. It aborts the process on an overread, so frames are
// shown to it only after check_frame accepted them.

#pragma once

#include "node_harness.hpp"

namespace node_test
{

// Empty when upstream deserialises `frame` (header included) into the
// message class of its type and consumes its payload exactly.
std::string reference_check(const Bytes &frame);

} // namespace node_test
