// The camera's pixel port on the chip's clock (see dspic30_pixel_port.hpp).

#include "dspic30_pixel_port.hpp"

namespace aseba::arena
{
namespace
{

// The levels boards/epuck_dspic30/epuck_dspic30_config.h takes
// (DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL, DSPIC30_CAMERA_PCLK_LATCH_LEVEL); that
// header cannot be read beside the host board's, which host_world.h brings.
constexpr bool sync_active_level = true;
constexpr bool pclk_latch_level = true;

} // namespace

PixelPortLevels Dspic30PixelPort::at(uint64_t cycle) const
{
    const bool active = sync_active_level;
    const bool latch = pclk_latch_level;
    PixelPortLevels levels;
    levels.vsync = !active;
    levels.href = !active;
    levels.pclk = !latch;
    const uint64_t in_frame = cycle % frame_cycles;
    if (in_frame < vsync_cycles) {
        levels.vsync = active;
        return levels;
    }
    const uint64_t in_rows = in_frame - vsync_cycles;
    const uint64_t row = in_rows / row_cycles;
    const uint64_t in_row = in_rows % row_cycles;
    if (row >= rows || in_row >= href_lead_cycles + row_bytes * byte_cycles)
        return levels;
    levels.href = active;
    if (in_row < href_lead_cycles)
        return levels;
    const uint64_t in_bytes = in_row - href_lead_cycles;
    const uint64_t byte = in_bytes / byte_cycles;
    levels.pclk = in_bytes % byte_cycles >= byte_cycles / 2 ? latch : !latch;
    levels.data = world_.camera_byte(world_.context, uint16_t(row), uint16_t(byte), cycle);
    return levels;
}

} // namespace aseba::arena
