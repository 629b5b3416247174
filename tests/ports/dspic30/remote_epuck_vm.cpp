// The image's VM with the e-puck's natives (see remote_epuck_vm.hpp).

#include "remote_epuck_vm.hpp"

#include <iterator>

#include "tests/ports/stm32f4/remote_link.hpp"

extern "C" {
#include "nat_dsp.h"
#include "nat_standard.h"
#include "nat_words.h"
}

namespace dspic30_test
{
namespace
{

const vm_native_module *const epuck_like_modules[] = { NAT_STANDARD_MODULES NAT_DSP_MODULES };

// The VM the image holds.
const vm_state *open_vm = nullptr;

} // namespace

const vm_native_table epuck_like_table = { epuck_like_modules,
                                           uint16_t(std::size(epuck_like_modules)),
                                           nat_words };

std::optional<uint16_t> epuck_index(const vm_native &native)
{
    const uint16_t count = vm_native_count(&epuck_like_table);
    for (uint16_t i = 0; i < count; ++i)
        if (vm_native_at(&epuck_like_table, i)->function == native.function)
            return i;
    return std::nullopt;
}

void open_epuck_vm(vm_state &vm)
{
    qemu_test::Bytes answer =
      qemu_test::RemoteMachine::instance().open(REMOTE_OPEN_VM, REMOTE_NATIVES_EPUCK, &vm, 1);
    qemu_test::Reader reader{ answer };
    qemu_test::RemoteMachine::instance().take_changes(reader);
    open_vm = &vm;
}

void use_epuck_vm(vm_state &vm)
{
    if (open_vm != &vm)
        open_epuck_vm(vm);
}

void call_epuck_native(vm_state &vm,
                       uint16_t index,
                       uint16_t pc,
                       const std::vector<int16_t> &popped_words)
{
    use_epuck_vm(vm);
    qemu_test::Writer writer;
    writer.u8(REMOTE_VM_CALL_NATIVE);
    writer.u16(index);
    writer.u16(pc);
    writer.u16(uint16_t(popped_words.size()));
    for (int16_t word : popped_words)
        writer.u16(uint16_t(word));
    if (qemu_test::call_vm(&vm, writer) == 0)
        qemu_test::fail("the image refused a native call");
}

} // namespace dspic30_test
