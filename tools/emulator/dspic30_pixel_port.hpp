// The camera's pixel port as the dsPIC's pins see it (hardware §3.5): VSYNC,
// HREF and PCLK on RC4, RC3 and RC14, a byte on RD8..RD15, all as a
// function of the chip's clock, the bytes given by the robot's world
// (host_world.camera_byte). The world's camera answers a host board at
// once; the chip has to catch the lines as it polls them, so here they run
// on a timing of their own:
//
// - a frame begins every frame_cycles: VSYNC active for vsync_cycles, then
//   the window's rows one after the other;
// - a row: HREF active for href_lead_cycles, then for its row_bytes bytes,
//   then inactive for row_gap_cycles;
// - a byte: byte_cycles long, PCLK at the inactive level for the first
//   half, at the latching level for the second, the byte on the data lines
//   the whole time.
//
// ⚠ The real camera's PCLK and frame rate under the firmware's register
// settings are not in the sources read (§3.5): byte_cycles is chosen so that
// the firmware's polling loop (dspic30_camera.c) sees every edge, as the
// real one must; frame_cycles keeps a whole frame under the firmware's
// 500 ms frame timeout. The firmware needs time between seeing HREF turn
// active and watching PCLK (the end of its wait, entering its critical
// section): with the first byte's PCLK low half right at HREF (64 cycles)
// it missed that byte and read the row one byte late (every pixel's bytes
// swapped); href_lead_cycles gives it that time, as the real camera must.

#pragma once

#include <cstdint>

extern "C" {
#include "boards/epuck_host/host_world.h"
}

namespace aseba::arena
{

struct PixelPortLevels {
    bool vsync = false;
    bool href = false;
    bool pclk = false;
    uint8_t data = 0;
};

class Dspic30PixelPort
{
  public:
    static constexpr uint64_t byte_cycles = 192;
    static constexpr unsigned row_bytes = 240; // 120 pixels of RGB565
    static constexpr unsigned rows = 120;      // the window (EPUCK_CAMERA_WINDOW_ROWS)
    static constexpr uint64_t href_lead_cycles = 256;
    static constexpr uint64_t row_gap_cycles = 512;
    static constexpr uint64_t row_cycles =
      href_lead_cycles + row_bytes * byte_cycles + row_gap_cycles;
    static constexpr uint64_t vsync_cycles = 2048;
    static constexpr uint64_t frame_cycles = vsync_cycles + rows * row_cycles + 4096;

    // The port of the camera `world` renders; `world` outlives the port.
    explicit Dspic30PixelPort(const host_world &world)
      : world_(world)
    {
    }

    // The lines' levels at `cycle` of the chip's clock.
    PixelPortLevels at(uint64_t cycle) const;

  private:
    const host_world &world_;
};

} // namespace aseba::arena
