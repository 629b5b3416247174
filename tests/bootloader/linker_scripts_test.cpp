// linker/epuck-app.gld and linker/epuck-bootloader.gld against the flash
// layout of robots/epuck/epuck_flash_layout.h: the same boundaries written twice,
// checked to agree, and the vector tables against the fact sheet's order
// (hardware §1.7).

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

extern "C" {
#include "bootloader/boot_application.h"
#include "robots/epuck/epuck_flash_layout.h"
}

namespace
{

std::string read_script(const std::string &path)
{
    std::ifstream file(path);
    EXPECT_TRUE(file.good()) << path;
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

struct Region {
    unsigned long origin = 0, length = 0;
    unsigned long end() const
    {
        return origin + length;
    }
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

// The script's constants: "NAME = number;" at the start of a line, NAME in
// capitals.
std::map<std::string, unsigned long> constants(const std::string &script)
{
    std::map<std::string, unsigned long> found;
    std::istringstream lines(script);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.empty() || !(std::isupper(static_cast<unsigned char>(line[0])) || line[0] == '_'))
            continue;
        std::istringstream words(line);
        std::string name, equals, value;
        words >> name >> equals >> value;
        if (equals != "=" || value.empty() || value.back() != ';' ||
            !std::isdigit(static_cast<unsigned char>(value[0])))
            continue;
        found[name] = std::stoul(value, nullptr, 0);
    }
    return found;
}

// The text of output section `name` up to the region it goes to.
std::string section(const std::string &script, const std::string &name)
{
    size_t at = script.find("\n  " + name + " ");
    EXPECT_NE(at, std::string::npos) << name;
    return script.substr(at, script.find("} >", at) - at);
}

// What follows each `before` in `text` up to the next `after`, in order.
std::vector<std::string> captures(const std::string &text,
                                  const std::string &before,
                                  const std::string &after)
{
    std::vector<std::string> found;
    for (size_t at = text.find(before); at != std::string::npos; at = text.find(before, at)) {
        at += before.size();
        found.push_back(text.substr(at, text.find(after, at) - at));
    }
    return found;
}

const std::string application_script = read_script("linker/epuck-app.gld");
const std::string bootloader_script = read_script("linker/epuck-bootloader.gld");

// Region `name` of `found` must be [origin, end).
void expect_region(std::map<std::string, Region> &found,
                   const std::string &name,
                   unsigned long origin,
                   unsigned long end)
{
    ASSERT_EQ(found.count(name), 1u) << name;
    EXPECT_EQ(found[name].origin, origin) << name;
    EXPECT_EQ(found[name].end(), end) << name;
}

TEST(LinkerScripts, TheApplicationsRegionsAreTheLayoutsConstants)
{
    auto found = regions(application_script);
    expect_region(found, "boot_vectors", BOOT_VECTORS_BASE, BOOT_APPLICATION_START);
    expect_region(found, "goto_table", BOOT_TABLE_BASE, BOOT_TABLE_END);
    expect_region(found, "program", BOOT_TABLE_END, BOOT_DESCRIPTOR_ADDRESS);
    expect_region(found, "descriptor", BOOT_DESCRIPTOR_ADDRESS, BOOT_APPLICATION_END);
    expect_region(found, "bytecode_store", STORE_REGION_BASE, STORE_REGION_END);
    expect_region(found, "aseba_bootloader", BOOT_LOADER_BASE, BOOT_LOADER_END);
    expect_region(found, "tiny_bootloader", BOOT_TINY_BASE, HAL_FLASH_END);
    auto named = constants(application_script);
    EXPECT_EQ(named["APPLICATION_TABLE_BASE"], BOOT_TABLE_BASE);
    EXPECT_EQ(named["CODE_BASE"], BOOT_TABLE_END);
    EXPECT_EQ(named["DESCRIPTOR_BASE"], BOOT_DESCRIPTOR_ADDRESS);
    EXPECT_EQ(named["BYTECODE_STORE_BASE"], STORE_REGION_BASE);
    EXPECT_EQ(named["ASEBA_BOOTLOADER_BASE"], BOOT_LOADER_BASE);
    EXPECT_EQ(named["TINY_BOOTLOADER_BASE"], BOOT_TINY_BASE);
}

TEST(LinkerScripts, TheBootloadersRegionsAreTheLayoutsConstants)
{
    auto found = regions(bootloader_script);
    // §1.1: the reset GOTO, 62 IVT entries, 2 reserved words, 62 AIVT entries.
    expect_region(found, "reset", 0x0, 0x4);
    expect_region(found, "ivt", BOOT_IVT_BASE, BOOT_IVT_BASE + 62 * 2);
    expect_region(found, "aivt", BOOT_AIVT_BASE, BOOT_AIVT_BASE + 62 * 2);
    EXPECT_LE(found["aivt"].end(), BOOT_APPLICATION_START);
    expect_region(found, "application", BOOT_APPLICATION_START, BOOT_APPLICATION_END);
    expect_region(found, "bytecode_store", STORE_REGION_BASE, STORE_REGION_END);
    expect_region(found, "program", BOOT_LOADER_BASE, BOOT_LOADER_END);
    expect_region(found, "tiny_bootloader", BOOT_TINY_BASE, HAL_FLASH_END);
    auto named = constants(bootloader_script);
    EXPECT_EQ(named["APPLICATION_TABLE_BASE"], BOOT_TABLE_BASE);
    EXPECT_EQ(named["TABLE_SLOT_SPAN"], BOOT_TABLE_SLOT_SPAN);
    EXPECT_EQ(named["BYTECODE_STORE_BASE"], STORE_REGION_BASE);
    EXPECT_EQ(named["ASEBA_BOOTLOADER_BASE"], BOOT_LOADER_BASE);
    EXPECT_EQ(named["TINY_BOOTLOADER_BASE"], BOOT_TINY_BASE);
}

TEST(LinkerScripts, TheLayoutTilesTheFlashInRows)
{
    // The Tiny Bootloader keeps the last 128 words of flash (§4.1), the
    // store holds its 46 rows, every boundary is a row boundary.
    EXPECT_EQ(BOOT_TINY_BASE, 0x17F00u);
    EXPECT_EQ(HAL_FLASH_END, 0x18000u);
    EXPECT_EQ(STORE_REGION_END - STORE_REGION_BASE, 46u * 0x40);
    for (unsigned long boundary : { BOOT_APPLICATION_START,
                                    BOOT_TABLE_END,
                                    BOOT_DESCRIPTOR_ADDRESS,
                                    STORE_REGION_BASE,
                                    BOOT_LOADER_BASE,
                                    BOOT_TINY_BASE })
        EXPECT_EQ(boundary % 0x40, 0u) << std::hex << boundary;
    auto application = regions(application_script);
    auto bootloader = regions(bootloader_script);
    // Both scripts see the same RAM, EEPROM and configuration words.
    for (const char *name : { "data", "eedata", "__FOSC", "__FWDT", "__FBORPOR", "__FGS" }) {
        ASSERT_EQ(application.count(name), 1u) << name;
        ASSERT_EQ(bootloader.count(name), 1u) << name;
        EXPECT_EQ(application[name].origin, bootloader[name].origin) << name;
        EXPECT_EQ(application[name].length, bootloader[name].length) << name;
    }
    // §1.1, §1.5: RAM from 0x800, 4096 bytes of data EEPROM, the
    // configuration words from 0xF80000.
    EXPECT_EQ(application["data"].origin, 0x800u);
    EXPECT_EQ(application["eedata"].origin, 0x7FF000u);
    EXPECT_EQ(application["eedata"].length, 4096u);
    EXPECT_EQ(application["__FOSC"].origin, 0xF80000u);
    EXPECT_EQ(application["__FBORPOR"].origin, 0xF80004u);
}

// The handler names of the application's GOTO table, slot 1 + k for k = 0..61.
std::vector<std::string> table_names()
{
    return captures(section(application_script, ".goto_table"), "LONG(0x040000 | (__table_", " ");
}

TEST(LinkerScripts, TheApplicationsTableHoldsTheResetSlotThenTheVectorsInHardwareOrder)
{
    std::string table = section(application_script, ".goto_table");
    // Slot 0 is GOTO __reset: opcode 0x04 with bits 15:0, then bits 22:16.
    EXPECT_NE(table.find("LONG(0x040000 | (ABSOLUTE(__reset) & 0xFFFF)); "
                         "LONG((ABSOLUTE(__reset) >> 16) & 0x7F);"),
              std::string::npos);
    EXPECT_LT(table.find("__reset"), table.find("__table_"));
    auto names = table_names();
    ASSERT_EQ(names.size(), BOOT_INTERRUPT_COUNT);
    // §1.7: vector k.
    EXPECT_EQ(names[1], "OscillatorFail");
    EXPECT_EQ(names[8], "INT0Interrupt");
    EXPECT_EQ(names[11], "T1Interrupt");
    EXPECT_EQ(names[14], "T2Interrupt");
    EXPECT_EQ(names[15], "T3Interrupt");
    EXPECT_EQ(names[17], "U1RXInterrupt");
    EXPECT_EQ(names[19], "ADCInterrupt");
    EXPECT_EQ(names[22], "MI2CInterrupt");
    EXPECT_EQ(names[29], "T4Interrupt");
    EXPECT_EQ(names[30], "T5Interrupt");
    EXPECT_EQ(names[49], "DCIInterrupt");
    EXPECT_EQ(names[61], "Interrupt53");
    // Each slot's second word uses the same handler, and each handler
    // falls back to __DefaultInterrupt.
    auto second = captures(table, "LONG((__table_", " >> 16) & 0x7F)");
    EXPECT_EQ(second, names);
    for (const auto &name : names)
        EXPECT_NE(application_script.find("__table_" + name + " = DEFINED(__" + name +
                                          ") ? ABSOLUTE(__" + name +
                                          ") : ABSOLUTE(__DefaultInterrupt);"),
                  std::string::npos)
          << name;
    // The table fills its slots but the last, and the region is 4 rows.
    EXPECT_EQ((1 + names.size()) * BOOT_TABLE_SLOT_SPAN, BOOT_TABLE_END - BOOT_TABLE_BASE - 4);
}

TEST(LinkerScripts, TheBootloadersVectorsLeadToTheApplicationsSlots)
{
    auto names = table_names();
    std::string ivt = section(bootloader_script, ".ivt");
    auto slots = captures(ivt, "LONG(APPLICATION_TABLE_BASE + TABLE_SLOT_SPAN * ", "); /* ");
    auto comments = captures(ivt, "); /* ", " */");
    ASSERT_EQ(slots.size(), BOOT_INTERRUPT_COUNT);
    ASSERT_EQ(comments, names);
    auto named = constants(bootloader_script);
    for (uint32_t k = 0; k < BOOT_INTERRUPT_COUNT; k++) {
        unsigned long target =
          named["APPLICATION_TABLE_BASE"] + named["TABLE_SLOT_SPAN"] * std::stoul(slots[k]);
        EXPECT_EQ(target, BOOT_TABLE_INTERRUPT_SLOT(k)) << "vector " << k;
        // The application's slot there holds vector k's handler.
        EXPECT_EQ(names[(target - BOOT_TABLE_BASE) / BOOT_TABLE_SLOT_SPAN - 1], names[k]);
    }
    // The alternate table: the bootloader's own handlers, same order.
    auto alternate = captures(section(bootloader_script, ".aivt"), "LONG(DEFINED(__Alt", ")");
    EXPECT_EQ(alternate, names);
    // The reset GOTO leads to the bootloader's start-up; its code goes to
    // its own region.
    EXPECT_NE(section(bootloader_script, ".reset").find("SHORT(ABSOLUTE(__reset));"),
              std::string::npos);
    EXPECT_NE(section(bootloader_script, ".text").find("ASEBA_BOOTLOADER_BASE"), std::string::npos);
    EXPECT_NE(bootloader_script.find("} >program"), std::string::npos);
}

} // namespace
