// The camera's pixel port as the dsPIC's pins see it (hardware §3.5): VSYNC,
// HREF and PCLK on RC4, RC3 and RC14, a byte on RD8..RD15, all as a
// function of the chip's clock, the bytes given by the robot's world
// (host_world.camera_byte). The world's camera answers a host board at
// once; the chip has to catch the lines as they pass, so here they run on a
// timing of their own:
//
// - a frame is frame_rows rows: first the vertical blank (blank_rows rows,
//   VSYNC inactive, no HREF), then the window's `rows` rows, VSYNC active
//   throughout (the PO3030K table's "VSYNC start and stop rows" are the
//   window's first and last, §3.5);
// - a row is row_cycles long: HREF active for its row_bytes bytes, then
//   inactive for the rest (the horizontal blank);
// - a byte is byte_cycles long, on the data lines the whole time; PCLK at
//   the inactive level for the first half, at the latching level for the
//   second.
//
// ⚠ The real camera's timing under the firmware's register settings is not
// in the sources read. byte_cycles is the library's: its capture reads a
// row with a loop of exactly 8 instruction cycles per byte, without PCLK
// (§3.5), so that is the byte rate its register table gives. The frame and
// row lengths follow the table's frame size (851 x 851 at VGA, a quarter
// in QQVGA: 213 rows of 213 pixels, 426 bytes), which gives 20 frames a
// second, near the 18.4 reported for the PO6030K.
//
// Timers counting HREF or VSYNC on their external clock pins (T4CK RC3,
// T5CK RC4) see the rising edges through href_clock() and vsync_clock().

#pragma once

#include "tools/dspic30_sim/timers.hpp"

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
    static constexpr uint64_t byte_cycles = 8;
    static constexpr unsigned row_bytes = 240; // 120 pixels of RGB565
    static constexpr unsigned row_length_bytes = 426;
    static constexpr uint64_t row_cycles = row_length_bytes * byte_cycles;
    static constexpr unsigned rows = 120; // the window (EPUCK_CAMERA_WINDOW_ROWS)
    static constexpr unsigned frame_rows = 213;
    static constexpr unsigned blank_rows = frame_rows - rows;
    static constexpr uint64_t blank_cycles = blank_rows * row_cycles;
    static constexpr uint64_t frame_cycles = frame_rows * row_cycles;

    // The port of the camera `world` renders; `world` outlives the port.
    explicit Dspic30PixelPort(const host_world &world)
      : world_(world)
    {
    }

    // The lines' levels at `cycle` of the chip's clock.
    PixelPortLevels at(uint64_t cycle) const;

    // HREF's and VSYNC's rising edges, for a timer's external clock.
    const dspic30::ClockInput &href_clock() const
    {
        return href_edges_;
    }
    const dspic30::ClockInput &vsync_clock() const
    {
        return vsync_edges_;
    }

  private:
    // Rising edges `per_frame` times a frame, `spacing` cycles apart from
    // `first` cycles into the frame.
    class FrameEdges : public dspic30::ClockInput
    {
      public:
        FrameEdges(uint64_t first, uint64_t spacing, uint64_t per_frame)
          : first_(first)
          , spacing_(spacing)
          , per_frame_(per_frame)
        {
        }
        uint64_t rising_edges(uint64_t from, uint64_t to) const override;
        uint64_t rising_edge(uint64_t after, uint64_t n) const override;

      private:
        uint64_t edges_until(uint64_t cycle) const; // at or before `cycle`
        uint64_t first_, spacing_, per_frame_;
    };

    const host_world &world_;
    const FrameEdges href_edges_{ blank_cycles, row_cycles, rows };
    const FrameEdges vsync_edges_{ blank_cycles, frame_cycles, 1 };
};

} // namespace aseba::arena
