// linker/epuck-app.gld against the fact sheet: memory regions (§1.1, §4.1,
// §5.1) and the interrupt vector table's order (§1.7).

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{

std::string read_script()
{
    std::ifstream file("linker/epuck-app.gld");
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

struct Region {
    unsigned long origin, length;
};

// The MEMORY lines: "name (attributes) : ORIGIN = 0x..., LENGTH = 0x...".
std::map<std::string, Region> regions(const std::string &script)
{
    std::map<std::string, Region> found;
    std::istringstream lines(script);
    std::string line;
    while (std::getline(lines, line)) {
        size_t origin = line.find("ORIGIN");
        size_t length = line.find("LENGTH");
        if (origin == std::string::npos || length == std::string::npos)
            continue;
        std::istringstream words(line);
        std::string name;
        words >> name;
        found[name] = { std::stoul(line.substr(line.find('=', origin) + 1), nullptr, 16),
                        std::stoul(line.substr(line.find('=', length) + 1), nullptr, 16) };
    }
    return found;
}

// The handler names in one vector table section, in slot order: each slot
// starts "LONG(DEFINED(__Name)".
std::vector<std::string> vector_slots(const std::string &script, const std::string &section)
{
    const std::string marker = "LONG(DEFINED(__";
    size_t at = script.find(section + " ");
    size_t stop = script.find("} >", at);
    std::vector<std::string> names;
    while ((at = script.find(marker, at)) < stop) {
        at += marker.size();
        names.push_back(script.substr(at, script.find(')', at) - at));
    }
    return names;
}

TEST(LinkerScript, RegionsFollowTheMemoryMap)
{
    auto found = regions(read_script());
    ASSERT_EQ(found.count("program"), 1u);
    EXPECT_EQ(found["reset"].origin, 0x0u);
    EXPECT_EQ(found["ivt"].origin, 0x4u);
    EXPECT_EQ(found["aivt"].origin, 0x84u);
    EXPECT_EQ(found["program"].origin, 0x100u); // __CODE_BASE
    // The bootloader keeps the last 128 words of flash (§4.1).
    EXPECT_EQ(found["bootloader"].origin, 0x17F00u);
    EXPECT_EQ(found["bootloader"].origin + found["bootloader"].length, 0x18000u);
    // Application, bytecode store and bootloader tile the flash, row aligned.
    EXPECT_EQ(found["program"].origin + found["program"].length, found["bytecode_store"].origin);
    EXPECT_EQ(found["bytecode_store"].origin + found["bytecode_store"].length,
              found["bootloader"].origin);
    for (const char *name : { "program", "bytecode_store", "bootloader" }) {
        EXPECT_EQ(found[name].origin % 0x40, 0u) << name;
        EXPECT_EQ(found[name].length % 0x40, 0u) << name;
    }
    // Room for two copies of 1024 bytecode words, one per instruction.
    EXPECT_GE(found["bytecode_store"].length, 2u * 1024 * 2);
    EXPECT_EQ(found["eedata"].origin, 0x7FF000u);
    EXPECT_EQ(found["eedata"].length, 4096u);
    EXPECT_EQ(found["data"].origin, 0x800u);
    EXPECT_EQ(found["__FOSC"].origin, 0xF80000u);
    EXPECT_EQ(found["__FBORPOR"].origin, 0xF80004u);
}

TEST(LinkerScript, VectorTablesHoldSixtyTwoSlotsInHardwareOrder)
{
    std::string script = read_script();
    for (const char *section : { ".ivt", ".aivt" }) {
        auto slots = vector_slots(script, section);
        ASSERT_EQ(slots.size(), 62u) << section;
        // §1.7: slot k (IVT address 0x04 + 2k); the AIVT names __AltXxx first.
        auto name = [&](size_t k) {
            std::string slot = slots[k];
            return slot.rfind("Alt", 0) == 0 ? slot.substr(3) : slot;
        };
        EXPECT_EQ(name(1), "OscillatorFail");
        EXPECT_EQ(name(8), "INT0Interrupt");
        EXPECT_EQ(name(11), "T1Interrupt");
        EXPECT_EQ(name(14), "T2Interrupt");
        EXPECT_EQ(name(15), "T3Interrupt");
        EXPECT_EQ(name(17), "U1RXInterrupt");
        EXPECT_EQ(name(19), "ADCInterrupt");
        EXPECT_EQ(name(22), "MI2CInterrupt");
        EXPECT_EQ(name(29), "T4Interrupt");
        EXPECT_EQ(name(30), "T5Interrupt");
        EXPECT_EQ(name(49), "DCIInterrupt");
        EXPECT_EQ(name(61), "Interrupt53");
    }
}

} // namespace
