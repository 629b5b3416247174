// The host's side of the harness image (remote_protocol.h): the image
// running in QEMU (or, in the dsPIC30F's tests, on the simulated chip), one
// request and its answer at a time, and the mirror of the remote machine's
// memory that the vm.h and node.h shims keep in step.

#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

extern "C" {
#include "tests/ports/stm32f4/remote_protocol.h"
#include "vm.h"
}

namespace qemu_test
{

using Bytes = std::vector<uint8_t>;

// A request's payload under construction.
struct Writer {
    Bytes bytes;
    void u8(uint8_t value)
    {
        bytes.push_back(value);
    }
    void u16(uint16_t value)
    {
        bytes.push_back(uint8_t(value));
        bytes.push_back(uint8_t(value >> 8));
    }
    void u32(uint32_t value)
    {
        u16(uint16_t(value));
        u16(uint16_t(value >> 16));
    }
};

// An answer's payload being read; throws on reading past its end.
struct Reader {
    const Bytes &bytes;
    size_t at = 0;
    uint8_t u8();
    uint16_t u16();
};

// The byte link to the harness image, started on first use: QEMU's serial
// port (qemu_link.cpp) or the simulated dsPIC30F's UART1
// (tests/ports/dspic30/simulated_link.cpp); a test program links one.
class HarnessLink
{
  public:
    virtual ~HarnessLink() = default;
    virtual void send(const uint8_t *bytes, size_t count) = 0;
    // Exactly `count` bytes, or fail().
    virtual void receive(uint8_t *bytes, size_t count) = 0;
};

// Starts the harness image and waits for its announcement (an empty
// REMOTE_OK answer); `count_instructions`: for measurements (QEMU's
// -icount).
std::unique_ptr<HarnessLink> open_harness_link(bool count_instructions);

// The remote machine's VM as the host sees it: the state block and memory
// sent before each call, what changed applied after it.
class RemoteMachine
{
  public:
    // Opens a bare VM (REMOTE_OPEN_VM) or a node (REMOTE_OPEN_NODE) over
    // `vm`'s memory, starting QEMU on first use; returns the answer (the
    // caller reads it, take_changes included).
    Bytes open(uint8_t command, uint8_t natives_or_preset, vm_state *vm, uint16_t node_id);

    // Runs `call` (its arguments in `arguments`, the call byte first), the
    // host's changes to the VM sent with it; returns the answer after the
    // result (events first), and the result in `*result`.
    Bytes call(const Writer &arguments, uint16_t *result);

    // Reads the state block and memory runs at `reader` into the VM.
    void take_changes(Reader &reader);

    // REMOTE_BENCH; returns its answer.
    Bytes bench(uint16_t event, uint16_t runs);

    // Before the first call: run QEMU with -icount (the guest's clock counts
    // instructions), for measurements; the simulated chip counts its cycles anyway.
    bool count_instructions = false;

    // The machine of this test program (the harness image in QEMU).
    static RemoteMachine &instance();

  private:
    Bytes exchange(uint8_t command, const Bytes &payload);
    void write_changes(Writer &writer);

    std::shared_ptr<HarnessLink> link_;
    vm_state *vm_ = nullptr;
    std::vector<uint16_t> seen_[3]; // the memory as the remote machine has it
};

// Runs the call in `arguments` (the call byte first) on the bare VM `vm`:
// its events to the VM's callbacks, its changes into `vm`; returns its
// result (remote_vm.cpp).
uint16_t call_vm(vm_state *vm, const Writer &arguments);

// Stops the test with `message` (a broken remote machine is no test result).
[[noreturn]] void fail(const std::string &message);

} // namespace qemu_test
