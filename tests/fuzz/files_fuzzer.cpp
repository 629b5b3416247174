// libFuzzer target for the parsers of files users hand to the tools: Intel
// HEX images (tools/flash, what `aseba flash`, `epuck-emu --firmware` and
// `epuck-image` read) and arena files (boards/epuck_host/arena_file, `epuck-emu
// --arena`). An input that starts with ':' is a HEX file, any other an arena
// file. It stops on any sanitizer report, on an exception other than the
// parser's own error, or when an image that was read does not survive what
// the tools do next: cutting it into pages, and writing it as HEX and reading
// it back to the same instructions.
//
// Built and run by `make fuzz` (scripts/fuzz.sh).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "tools/emulator/arena_file.hpp"
#include "tools/flash/hex_image.hpp"

extern "C" {
#include "bootloader/bootloader.h"
}

namespace
{

[[noreturn]] void fail(const char *why)
{
    std::fprintf(stderr, "files_fuzzer: %s\n", why);
    __builtin_trap();
}

void check_hex(const std::string &text)
{
    aseba::flash::ProgramImage image;
    try {
        image = aseba::flash::read_microchip_hex(text, BOOT_APPLICATION_END);
    } catch (const aseba::flash::HexError &) {
        return; // refused with a message: what a bad file must get
    }
    aseba::flash::ProgramImage again;
    try {
        again = aseba::flash::read_microchip_hex(aseba::flash::write_microchip_hex(image),
                                                 BOOT_APPLICATION_END);
    } catch (const aseba::flash::HexError &) {
        fail("an image that was read cannot be read back once written");
    }
    if (again.instructions != image.instructions)
        fail("writing and reading an image changed its instructions");
    try {
        aseba::flash::add_application_descriptor(image);
    } catch (const aseba::flash::HexError &) {
        return; // not an application: refused with a message
    }
    for (const aseba::flash::Page &page : aseba::flash::make_pages(image))
        if (page.number < BOOT_PAGES_START || page.number >= BOOT_PAGES_START + BOOT_PAGES_COUNT)
            fail("a page outside the bootloader's range");
}

void check_arena(const std::string &text)
{
    try {
        aseba::arena::Arena arena = aseba::arena::parse_arena(text, "fuzz");
        if (!(arena.width > 0) || !(arena.height > 0))
            fail("an arena without a positive size was accepted");
    } catch (const std::runtime_error &) {
        // refused with a message
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    std::string text(reinterpret_cast<const char *>(data), size);
    if (!text.empty() && text[0] == ':')
        check_hex(text);
    else
        check_arena(text);
    return 0;
}
