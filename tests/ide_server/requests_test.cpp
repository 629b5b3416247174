// The browser's requests as data (data/requests.txt): each JSON message and
// what the server must make of it, written from docs/ide-protocol.md.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tools/ide/requests.hpp"

namespace
{

using namespace aseba::ide;

std::string join_lines(const std::vector<unsigned> &lines)
{
    std::string text;
    for (unsigned line : lines)
        text += (text.empty() ? "" : ",") + std::to_string(line);
    return "[" + text + "]";
}

std::string join_words(const std::vector<int16_t> &words)
{
    std::string text;
    for (int16_t word : words)
        text += (text.empty() ? "" : ",") + std::to_string(word);
    return "[" + text + "]";
}

// The parsed request in one line, in the words of data/requests.txt.
std::string describe(const ParsedRequest &parsed)
{
    std::string id = parsed.id ? " id=" + std::to_string(parsed.id) : "";
    return std::visit(
      [&](const auto &request) -> std::string {
          using T = std::decay_t<decltype(request)>;
          if constexpr (std::is_same_v<T, CompileRequest>)
              return "compile " + robot_name(request.robot) +
                     " source=" + std::to_string(request.source.size()) +
                     (request.remember ? "" : " not-remembered") + id;
          else if constexpr (std::is_same_v<T, ScriptRequest>)
              return "script " + robot_name(request.robot) + id;
          else if constexpr (std::is_same_v<T, BytecodeRequest>)
              return "bytecode " + robot_name(request.robot) + id;
          else if constexpr (std::is_same_v<T, LoadRequest>) {
              std::string text = std::string("load run=") + (request.run ? "yes" : "no");
              for (const auto &program : request.programs)
                  text += " " + robot_name(program.robot) + join_lines(program.breakpoints);
              return text + id;
          } else if constexpr (std::is_same_v<T, ControlRequest>) {
              std::string text = std::string("control ") + action_name(request.action);
              for (NodeKey key : request.robots)
                  text += " " + robot_name(key);
              return text + id;
          } else if constexpr (std::is_same_v<T, BreakpointsRequest>)
              return "breakpoints " + robot_name(request.robot) + " " + join_lines(request.lines) +
                     id;
          else if constexpr (std::is_same_v<T, SetVariableRequest>)
              return "set-variable " + robot_name(request.robot) + " " + request.name + "[" +
                     std::to_string(request.index) + "]=" + join_words(request.values) + id;
          else if constexpr (std::is_same_v<T, EmitRequest>)
              return "emit " + request.event + join_words(request.arguments) + id;
          else if constexpr (std::is_same_v<T, DefinitionsRequest>) {
              std::string text = "definitions";
              for (const auto &event : request.definitions.events)
                  text += " event " + event.name + "/" + std::to_string(event.size);
              for (const auto &constant : request.definitions.constants)
                  text += " constant " + constant.name + "=" + std::to_string(constant.value);
              return text + id;
          } else if constexpr (std::is_same_v<T, WatchRequest>) {
              std::string text = "watch";
              for (NodeKey key : request.robots)
                  text += " " + robot_name(key);
              return text + id;
          } else if constexpr (std::is_same_v<T, OpenProjectRequest>)
              return "open-project " + request.file_name + id;
          else
              return std::string("save-project") +
                     (request.to_server_file ? " to-server-file" : "") + id;
      },
      parsed.request);
}

struct Case {
    unsigned line = 0;
    std::string message;
    std::string expected;
};

std::vector<Case> read_cases()
{
    std::ifstream file("tests/ide_server/data/requests.txt");
    EXPECT_TRUE(file)
      << "tests/ide_server/data/requests.txt is missing (run from the repository root)";
    std::vector<Case> cases;
    std::string line;
    unsigned number = 0;
    while (std::getline(file, line)) {
        number++;
        if (line.empty() || line[0] == '#')
            continue;
        if (line.rfind("=> ", 0) == 0) {
            EXPECT_FALSE(cases.empty() || !cases.back().expected.empty())
              << "line " << number << ": '=>' without a message";
            if (!cases.empty())
                cases.back().expected = line.substr(3);
            continue;
        }
        cases.push_back({ number, line, "" });
    }
    return cases;
}

TEST(Requests, EachMessageOfTheDataFileParsesAsExpected)
{
    std::vector<Case> cases = read_cases();
    ASSERT_GT(cases.size(), 40u);
    for (const Case &each : cases) {
        ASSERT_FALSE(each.expected.empty()) << "line " << each.line << ": no '=>' line follows";
        std::string got;
        try {
            got = describe(parse_request(each.message));
        } catch (const RequestError &error) {
            got = std::string("error: ") + error.what();
        }
        EXPECT_EQ(got, each.expected) << "line " << each.line << ": " << each.message;
    }
}

TEST(Requests, TheIdOfABadRequestIsStillFound)
{
    EXPECT_EQ(request_id_of(R"({"id": 12, "type": "nonsense"})"), 12u);
    EXPECT_EQ(request_id_of(R"({"id": -3})"), 0u);
    EXPECT_EQ(request_id_of("not json"), 0u);
}

TEST(Requests, AScriptAtTheLimitIsTakenAndOneByteMoreIsRefused)
{
    std::string source(MAX_SCRIPT_BYTES, 'x');
    EXPECT_NO_THROW(
      parse_request(R"({"type":"compile","robot":"0:1","source":")" + source + "\"}"));
    EXPECT_THROW(parse_request(R"({"type":"compile","robot":"0:1","source":")" + source + "x\"}"),
                 RequestError);
}

TEST(Requests, DeeplyNestedJsonIsAnErrorNotACrash)
{
    std::string deep = std::string(100000, '[') + std::string(100000, ']');
    EXPECT_THROW(parse_request(deep), RequestError);
    EXPECT_THROW(parse_request(R"({"type":"compile","robot":"0:1","source":)" + deep + "}"),
                 RequestError);
}

} // namespace
