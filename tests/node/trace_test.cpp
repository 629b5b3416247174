// Replays the message traces of tests/node/traces (format in README.md):
// frames in, the exact frames the node must answer, error counters. Each
// trace runs twice: its input given whole and one byte at a time.

#include "node_harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>
#include <map>
#include <sstream>
#include <tuple>

using namespace node_test;

namespace
{

const char trace_folder[] = "tests/node/traces";

struct Line {
    unsigned number;
    std::string keyword;
    std::string rest;
};

std::vector<Line> read_trace(const std::string &path)
{
    std::ifstream file(path);
    std::vector<Line> lines;
    std::string text;
    for (unsigned number = 1; std::getline(file, text); number++) {
        // A `#` outside a quoted string starts a comment.
        bool quoted = false;
        for (size_t i = 0; i < text.size(); i++) {
            if (text[i] == '"')
                quoted = !quoted;
            else if (text[i] == '#' && !quoted) {
                text.resize(i);
                break;
            }
        }
        std::istringstream stream(text);
        Line line{ number, "", "" };
        if (!(stream >> line.keyword))
            continue;
        std::getline(stream, line.rest);
        lines.push_back(line);
    }
    return lines;
}

// Hex bytes ("0a") and quoted strings ("abc", their bytes).
Bytes parse_bytes(const std::string &text)
{
    Bytes bytes;
    size_t i = 0;
    while (i < text.size()) {
        if (std::isspace(static_cast<unsigned char>(text[i]))) {
            i++;
        } else if (text[i] == '"') {
            size_t end = text.find('"', i + 1);
            if (end == std::string::npos)
                throw std::runtime_error("unterminated string");
            bytes.insert(bytes.end(), text.begin() + long(i) + 1, text.begin() + long(end));
            i = end + 1;
        } else {
            size_t end = i;
            while (end < text.size() && std::isxdigit(static_cast<unsigned char>(text[end])))
                end++;
            if (end - i != 2)
                throw std::runtime_error("bad byte '" + text.substr(i, 4) + "'");
            bytes.push_back(uint8_t(std::stoul(text.substr(i, 2), nullptr, 16)));
            i = end;
        }
    }
    return bytes;
}

std::map<std::string, unsigned long> parse_counts(const std::string &text)
{
    std::map<std::string, unsigned long> counts;
    std::istringstream stream(text);
    std::string item;
    while (stream >> item) {
        size_t equal = item.find('=');
        if (equal == std::string::npos)
            throw std::runtime_error("expected name=value, got " + item);
        counts[item.substr(0, equal)] = std::stoul(item.substr(equal + 1), nullptr, 0);
    }
    return counts;
}

struct TraceCase {
    std::string path;
    bool byte_by_byte;
};

std::vector<TraceCase> trace_cases()
{
    std::vector<TraceCase> cases;
    for (const auto &entry : std::filesystem::directory_iterator(trace_folder)) {
        if (entry.path().extension() == ".trace") {
            cases.push_back({ entry.path().string(), false });
            cases.push_back({ entry.path().string(), true });
        }
    }
    std::sort(cases.begin(), cases.end(), [](const TraceCase &a, const TraceCase &b) {
        return std::tie(a.path, a.byte_by_byte) < std::tie(b.path, b.byte_by_byte);
    });
    return cases;
}

class TraceTest : public testing::TestWithParam<TraceCase>
{
};

// Fails when frames the trace did not expect were sent.
void expect_no_unread_frames(Harness &harness, const Line &line)
{
    while (!harness.frames.empty()) {
        ADD_FAILURE() << "line " << line.number << ": unexpected frame "
                      << hex(harness.frames.front());
        harness.frames.pop_front();
    }
}

TEST_P(TraceTest, NodeAnswersAsExpected)
{
    const TraceCase &test_case = GetParam();
    std::vector<Line> lines = read_trace(test_case.path);
    ASSERT_FALSE(lines.empty()) << test_case.path;

    std::string preset_name = "tiny";
    uint16_t node_id = 1;
    std::unique_ptr<Harness> harness;
    unsigned checks = 0;

    for (const Line &line : lines) {
        SCOPED_TRACE(test_case.path + ":" + std::to_string(line.number));
        const std::string &keyword = line.keyword;
        if (keyword == "preset" || keyword == "id") {
            ASSERT_FALSE(harness) << "`" << keyword << "` after the node started";
            std::istringstream stream(line.rest);
            if (keyword == "preset")
                stream >> preset_name;
            else
                stream >> node_id;
            continue;
        }
        if (!harness)
            harness = std::make_unique<Harness>(preset(preset_name), node_id);

        if (keyword == "in") {
            expect_no_unread_frames(*harness, line);
            harness->feed(parse_bytes(line.rest), test_case.byte_by_byte);
        } else if (keyword == "out") {
            Bytes expected = parse_bytes(line.rest);
            ASSERT_FALSE(harness->frames.empty()) << "expected " << hex(expected);
            EXPECT_EQ(hex(harness->frames.front()), hex(expected));
            harness->frames.pop_front();
            checks++;
        } else if (keyword == "skip") {
            unsigned long count = std::stoul(line.rest);
            ASSERT_GE(harness->frames.size(), count);
            harness->frames.erase(harness->frames.begin(), harness->frames.begin() + long(count));
        } else if (keyword == "time") {
            expect_no_unread_frames(*harness, line);
            std::string value = line.rest.substr(line.rest.find_first_not_of(' '));
            if (value[0] == '+')
                harness->now += uint32_t(std::stoul(value.substr(1)));
            else
                harness->now = uint32_t(std::stoul(value));
        } else if (keyword == "poll") {
            expect_no_unread_frames(*harness, line);
            harness->poll_until_idle();
        } else if (keyword == "local") {
            expect_no_unread_frames(*harness, line);
            EXPECT_TRUE(node_raise_local_event(&harness->node(), uint16_t(std::stoul(line.rest))));
            harness->poll_until_idle();
        } else if (keyword == "errors") {
            const node_error_counters &errors = harness->node().errors;
            std::map<std::string, unsigned long> actual = { { "oversize", errors.oversize },
                                                            { "truncated", errors.truncated },
                                                            { "malformed", errors.malformed },
                                                            { "wrong_destination",
                                                              errors.wrong_destination },
                                                            { "ignored", errors.ignored } };
            for (const auto &[name, value] : parse_counts(line.rest)) {
                ASSERT_TRUE(actual.count(name)) << "unknown counter " << name;
                EXPECT_EQ(actual[name], value) << name;
                checks++;
            }
        } else if (keyword == "hooks") {
            std::map<std::string, unsigned long> actual = { { "write_bytecode",
                                                              harness->write_bytecode_calls },
                                                            { "reboot", harness->reboot_calls },
                                                            { "suspend", harness->suspend_calls } };
            for (const auto &[name, value] : parse_counts(line.rest)) {
                ASSERT_TRUE(actual.count(name)) << "unknown hook " << name;
                EXPECT_EQ(actual[name], value) << name;
                checks++;
            }
        } else if (keyword == "bytecode") {
            std::istringstream stream(line.rest);
            unsigned long address;
            stream >> address;
            const vm_memory &memory = harness->node().vm.memory;
            std::string word;
            while (stream >> word) {
                ASSERT_LT(address, memory.bytecode_size);
                EXPECT_EQ(memory.bytecode[address], std::stoul(word, nullptr, 16))
                  << "bytecode[" << address << "]";
                address++;
                checks++;
            }
        } else {
            FAIL() << "unknown keyword " << keyword;
        }
    }
    ASSERT_TRUE(harness);
    expect_no_unread_frames(*harness, lines.back());
    for (const std::string &problem : harness->bad)
        ADD_FAILURE() << "malformed frame: " << problem;
    EXPECT_TRUE(harness->canaries_intact());
    EXPECT_GT(checks, 0u) << "a trace must check something";
}

std::string case_name(const testing::TestParamInfo<TraceCase> &info)
{
    std::string name = std::filesystem::path(info.param.path).stem().string();
    std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
    return name + (info.param.byte_by_byte ? "_bytewise" : "_whole");
}

INSTANTIATE_TEST_SUITE_P(Traces, TraceTest, testing::ValuesIn(trace_cases()), case_name);

} // namespace
