// The executor against the manual, case by case: the cases of
// tests/dspic30_sim/semantics.cases (the format is described at its top)
// are assembled together by pic30-elf-as, each at its own address, linked
// and converted to Intel HEX by the pic30-elf tools, then run one by one on
// a fresh CPU from the registers and memory given, and compared with what
// the case expects.

#include "tests/dspic30_sim/pic30_toolchain.hpp"
#include "tools/dspic30_sim/cpu.hpp"
#include "tools/dspic30_sim/disassembler.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace aseba::dspic30
{
namespace
{

constexpr const char *cases_path = "tests/dspic30_sim/semantics.cases";
constexpr uint32_t cases_base = 0x200;   // where the first case is linked
constexpr uint32_t case_span = 0x100;    // PC units per case
constexpr int instruction_limit = 10000; // per case, when it runs to its end

struct Case {
    std::string name;
    std::string cite;
    std::vector<std::string> assembly;
    std::vector<std::string> before;
    std::vector<std::string> after;
    int run = -1; // instructions to execute; -1: to the end
    int line = 0;
};

std::vector<std::string> words_of(const std::string &text)
{
    std::istringstream in(text);
    std::vector<std::string> words;
    std::string w;
    while (in >> w)
        words.push_back(w);
    return words;
}

std::vector<Case> read_cases()
{
    std::ifstream in(cases_path);
    EXPECT_TRUE(in) << "cannot read " << cases_path;
    std::vector<Case> cases;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (line.empty() || line[0] == '#')
            continue;
        const auto space = line.find(' ');
        const std::string keyword = line.substr(0, space);
        const std::string rest = space == std::string::npos ? "" : line.substr(space + 1);
        if (keyword == "case") {
            cases.push_back(Case{ rest, "", {}, {}, {}, -1, number });
            continue;
        }
        if (cases.empty()) {
            ADD_FAILURE() << cases_path << ":" << number << ": outside a case";
            continue;
        }
        Case &c = cases.back();
        if (keyword == "cite")
            c.cite = rest;
        else if (keyword == "asm")
            c.assembly.push_back(rest);
        else if (keyword == "before")
            for (const auto &w : words_of(rest))
                c.before.push_back(w);
        else if (keyword == "after")
            for (const auto &w : words_of(rest))
                c.after.push_back(w);
        else if (keyword == "run")
            c.run = std::stoi(rest);
        else
            ADD_FAILURE() << cases_path << ":" << number << ": unknown keyword " << keyword;
    }
    return cases;
}

// The labels a case defines ("name:" at the start of a line), renamed so
// that every case has its own.
std::string prefixed(const std::string &label, std::size_t index)
{
    return "c" + std::to_string(index) + "_" + label;
}

bool identifier_char(char c)
{
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// `text` with each whole-word label replaced by its case's name for it.
std::string rename_labels(const std::string &text,
                          const std::vector<std::string> &labels,
                          std::size_t index)
{
    std::string result;
    for (std::size_t i = 0; i < text.size();) {
        if (!identifier_char(text[i])) {
            result += text[i++];
            continue;
        }
        std::size_t j = i;
        while (j < text.size() && identifier_char(text[j]))
            ++j;
        const std::string word = text.substr(i, j - i);
        bool is_label = false;
        for (const auto &label : labels)
            is_label = is_label || word == label;
        result += is_label ? prefixed(word, index) : word;
        i = j;
    }
    return result;
}

std::vector<std::string> labels_of(const Case &c)
{
    std::vector<std::string> labels;
    for (const auto &line : c.assembly) {
        std::size_t i = line.find_first_not_of(" \t");
        if (i == std::string::npos ||
            !(std::isalpha(static_cast<unsigned char>(line[i])) || line[i] == '_'))
            continue;
        std::size_t j = i;
        while (j < line.size() && identifier_char(line[j]))
            ++j;
        if (j < line.size() && line[j] == ':')
            labels.push_back(line.substr(i, j - i));
    }
    return labels;
}

using Program = test::AssembledProgram;

Program build(const std::vector<Case> &cases)
{
    std::ostringstream source;
    source << "\t.text\n";
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto labels = labels_of(cases[i]);
        source << "\t.org 0x" << std::hex << i * case_span << std::dec << "\n";
        source << prefixed("start", i) << ":\n";
        for (const auto &line : cases[i].assembly)
            source << "\t" << rename_labels(line, labels, i) << "\n";
        source << prefixed("end", i) << ":\n\tnop\n";
    }
    return test::assemble_program(source.str(), cases_base);
}

// A value of the case file: hexadecimal, or a label of the case.
uint32_t value_of(const std::string &text,
                  const Program &program,
                  const std::vector<std::string> &labels,
                  std::size_t index)
{
    for (const auto &label : labels)
        if (text == label)
            return program.symbols.at(prefixed(label, index));
    return static_cast<uint32_t>(std::stoull(text, nullptr, 16));
}

struct Named {
    const char *name;
    uint16_t address;
};
constexpr Named data_registers[] = {
    { "RCOUNT", sfr::RCOUNT }, { "DCOUNT", sfr::DCOUNT }, { "TBLPAG", sfr::TBLPAG },
    { "PSVPAG", sfr::PSVPAG }, { "SPLIM", sfr::SPLIM },   { "INTCON1", sfr::INTCON1 },
    { "RCON", sfr::RCON },
};

uint16_t address_of(const std::string &name)
{
    for (const auto &r : data_registers)
        if (name == r.name)
            return r.address;
    return 0xFFFF;
}

void apply(Cpu &cpu,
           const std::string &assignment,
           const Program &program,
           const std::vector<std::string> &labels,
           std::size_t index)
{
    const auto equals = assignment.find('=');
    const std::string name = assignment.substr(0, equals);
    const uint32_t value = value_of(assignment.substr(equals + 1), program, labels, index);
    if (name[0] == 'W' && name.size() <= 3)
        cpu.set_w(std::stoi(name.substr(1)), static_cast<uint16_t>(value));
    else if (name == "SR")
        cpu.set_sr(static_cast<uint16_t>(value));
    else if (name == "CORCON")
        cpu.set_corcon(static_cast<uint16_t>(value));
    else if (name == "ACCA" || name == "ACCB")
        cpu.set_accumulator(
          name == "ACCB",
          static_cast<int64_t>(std::stoull(assignment.substr(equals + 1), nullptr, 16)));
    else if (name[0] == '[')
        cpu.write_data(static_cast<uint16_t>(std::stoul(name.substr(1), nullptr, 16)),
                       static_cast<uint16_t>(value));
    else if (name.rfind("b[", 0) == 0)
        cpu.write_data(static_cast<uint16_t>(std::stoul(name.substr(2), nullptr, 16)),
                       static_cast<uint16_t>(value),
                       true);
    else if (address_of(name) != 0xFFFF)
        cpu.write_data(address_of(name), static_cast<uint16_t>(value));
    else
        ADD_FAILURE() << "unknown register " << name;
}

// The value of `name` now (SR&MASK and INTCON1&MASK keep the masked bits).
uint64_t observe(Cpu &cpu, const std::string &name, uint64_t cycles_spent)
{
    const auto amp = name.find('&');
    if (amp != std::string::npos) {
        const uint64_t mask = std::stoull(name.substr(amp + 1), nullptr, 16);
        return observe(cpu, name.substr(0, amp), cycles_spent) & mask;
    }
    if (name[0] == 'W' && name.size() <= 3)
        return cpu.w(std::stoi(name.substr(1)));
    if (name == "SR")
        return cpu.sr();
    if (name == "CORCON")
        return cpu.corcon();
    if (name == "ACCA" || name == "ACCB")
        return static_cast<uint64_t>(cpu.accumulator(name == "ACCB")) & ((uint64_t{ 1 } << 40) - 1);
    if (name == "PC")
        return cpu.pc();
    if (name == "CYCLES")
        return cycles_spent;
    if (name[0] == '[')
        return cpu.read_data(static_cast<uint16_t>(std::stoul(name.substr(1), nullptr, 16)));
    if (name.rfind("b[", 0) == 0)
        return cpu.read_data(static_cast<uint16_t>(std::stoul(name.substr(2), nullptr, 16)), true);
    if (address_of(name) != 0xFFFF)
        return cpu.read_data(address_of(name));
    ADD_FAILURE() << "unknown register " << name;
    return 0;
}

TEST(Semantics, EveryCaseOfTheCaseFile)
{
    const auto cases = read_cases();
    ASSERT_FALSE(cases.empty());
    const Program program = build(cases);
    int passed = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Case &c = cases[i];
        SCOPED_TRACE(c.name + " (" + cases_path + ":" + std::to_string(c.line) + ", " + c.cite +
                     ")");
        const auto labels = labels_of(c);
        Cpu cpu;
        for (const auto &[address, word] : program.words)
            cpu.program(address, word);
        cpu.power_on_reset();
        for (const auto &assignment : c.before)
            apply(cpu, assignment, program, labels, i);
        const uint32_t start = program.symbols.at(prefixed("start", i));
        const uint32_t end = program.symbols.at(prefixed("end", i));
        ASSERT_EQ(start, cases_base + i * case_span) << "the cases were not laid out as expected";
        cpu.set_pc(start);
        const uint64_t cycles_before = cpu.cycles();
        int executed = 0;
        const int limit = c.run >= 0 ? c.run : instruction_limit;
        while (executed < limit && (c.run >= 0 || cpu.pc() != end)) {
            cpu.run(cpu.cycles() + 1);
            ++executed;
        }
        if (c.run < 0) {
            EXPECT_EQ(cpu.pc(), end) << "the case did not reach its end";
        }
        bool ok = true;
        for (const auto &assignment : c.after) {
            const auto equals = assignment.find('=');
            const std::string name = assignment.substr(0, equals);
            const uint64_t expected =
              name == "CYCLES" ? std::stoull(assignment.substr(equals + 1))
              : (name == "ACCA" || name == "ACCB")
                ? std::stoull(assignment.substr(equals + 1), nullptr, 16)
                : value_of(assignment.substr(equals + 1), program, labels, i);
            const uint64_t actual = observe(cpu, name, cpu.cycles() - cycles_before);
            if (actual != expected) {
                ok = false;
                ADD_FAILURE() << name << ": expected " << std::hex << expected << ", got "
                              << actual;
            }
        }
        passed += ok;
    }
    std::printf("%d of %zu semantics cases as the manual says\n", passed, cases.size());
}

} // namespace
} // namespace aseba::dspic30
