// The camera's pixel port on the chip's clock (see dspic30_pixel_port.hpp).

#include "dspic30_pixel_port.hpp"

namespace aseba::arena
{
namespace
{

// The sync level boards/epuck_dspic30/epuck_dspic30_config.h takes
// (DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL; that header cannot be read beside the
// host board's, which host_world.h brings), and PCLK's, which no firmware
// reads now (the row is read by the instructions' timing).
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
    if (in_frame < blank_cycles)
        return levels;
    levels.vsync = active;
    const uint64_t in_rows = in_frame - blank_cycles;
    const uint64_t row = in_rows / row_cycles;
    const uint64_t in_row = in_rows % row_cycles;
    if (in_row >= row_bytes * byte_cycles)
        return levels;
    levels.href = active;
    const uint64_t byte = in_row / byte_cycles;
    levels.pclk = in_row % byte_cycles >= byte_cycles / 2 ? latch : !latch;
    levels.data = world_.camera_byte(world_.context, uint16_t(row), uint16_t(byte), cycle);
    return levels;
}

uint64_t Dspic30PixelPort::FrameEdges::edges_until(uint64_t cycle) const
{
    const uint64_t frames = cycle / frame_cycles;
    const uint64_t in_frame = cycle % frame_cycles;
    uint64_t in_this_frame = 0;
    if (in_frame >= first_) {
        in_this_frame = (in_frame - first_) / spacing_ + 1;
        if (in_this_frame > per_frame_)
            in_this_frame = per_frame_;
    }
    return frames * per_frame_ + in_this_frame;
}

uint64_t Dspic30PixelPort::FrameEdges::rising_edges(uint64_t from, uint64_t to) const
{
    return to <= from ? 0 : edges_until(to) - edges_until(from);
}

uint64_t Dspic30PixelPort::FrameEdges::rising_edge(uint64_t after, uint64_t n) const
{
    const uint64_t index = edges_until(after) + n - 1; // counted from the first edge, 0
    return (index / per_frame_) * frame_cycles + first_ + (index % per_frame_) * spacing_;
}

} // namespace aseba::arena
