// The IDE server end to end: an in-process IdeServer on a free port, the
// simulated robots of epuck-emu, and WebSocket clients. Most cases are
// message traces (data/*.trace): what a page sends and the replies and
// updates it must get.

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <filesystem>
#include <fstream>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>

#include <deque>

#include <asio/io_context.hpp>
#include <nlohmann/json.hpp>

#include "tests/console/console_support.hpp"
#include "tools/ide/ide_server.hpp"
#include "websocket_client.hpp"

namespace
{

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// How long a trace waits for an expected message.
constexpr milliseconds EXPECT_LIMIT{ 8000 };

// epuck-emu on a port of the test's choosing, so that it can come back on the
// same port.
class Robots
{
  public:
    // `options`: more of epuck-emu's options (--load FILE).
    Robots(uint16_t port, unsigned count, std::vector<std::string> options = {})
      : port_(port)
      , count_(count)
      , options_(std::move(options))
    {
        start();
    }

    void start()
    {
        std::vector<std::string> command{ console_test::program_path("epuck-emu"),
                                          "--port",
                                          std::to_string(port_),
                                          "--robots",
                                          std::to_string(count_),
                                          "--duration",
                                          "120",
                                          "--quiet" };
        command.insert(command.end(), options_.begin(), options_.end());
        process_ = std::make_unique<console_test::ReferenceProgram>(
          command, std::vector<std::string>{}, folder_.path() + "/epuck-emu.log");
        // Ready once it accepts a connection.
        auto deadline = Clock::now() + milliseconds(5000);
        while (Clock::now() < deadline) {
            int fd = socket(AF_INET, SOCK_STREAM, 0);
            sockaddr_in address{};
            address.sin_family = AF_INET;
            address.sin_port = htons(port_);
            address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
            bool up = connect(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0;
            close(fd);
            if (up)
                return;
            std::this_thread::sleep_for(milliseconds(20));
        }
        throw std::runtime_error("epuck-emu did not start on port " + std::to_string(port_));
    }

    void stop()
    {
        process_.reset();
    }

  private:
    uint16_t port_;
    unsigned count_;
    std::vector<std::string> options_;
    console_test::ScratchFolder folder_;
    std::unique_ptr<console_test::ReferenceProgram> process_;
};

// The IDE server in a thread of its own, on a free port.
class Server
{
  public:
    explicit Server(const std::string &target,
                    aseba::ide::IdeOptions options = {},
                    std::vector<aseba::ide::StaticFile> files = {})
    {
        options.targets = { target };
        options.web.port = 0;
        options.answer_timeout = milliseconds(1000);
        server_ = std::make_unique<aseba::ide::IdeServer>(io_, options, std::move(files));
        thread_ = std::thread([this] { io_.run(); });
    }
    ~Server()
    {
        io_.stop();
        thread_.join();
        server_.reset();
    }
    std::string url() const
    {
        return "ws://127.0.0.1:" + std::to_string(server_->port()) + "/ws";
    }
    uint16_t port() const
    {
        return server_->port();
    }

  private:
    asio::io_context io_;
    std::unique_ptr<aseba::ide::IdeServer> server_;
    std::thread thread_;
};

// Whether `actual` has everything `expected` has: the same scalars, every
// key of an object (others may be there), arrays of the same length whose
// elements match. A string "~TEXT" matches a string containing TEXT, "*"
// anything present.
bool matches(const Json &expected, const Json &actual)
{
    if (expected.is_string()) {
        const std::string &pattern = expected.get_ref<const std::string &>();
        if (pattern == "*")
            return true;
        if (!pattern.empty() && pattern[0] == '~')
            return actual.is_string() &&
                   actual.get<std::string>().find(pattern.substr(1)) != std::string::npos;
    }
    if (expected.is_object()) {
        if (!actual.is_object())
            return false;
        for (const auto &[key, value] : expected.items())
            if (!actual.contains(key) || !matches(value, actual[key]))
                return false;
        return true;
    }
    if (expected.is_array()) {
        if (!actual.is_array() || actual.size() != expected.size())
            return false;
        for (size_t i = 0; i < expected.size(); i++)
            if (!matches(expected[i], actual[i]))
                return false;
        return true;
    }
    return expected == actual;
}

// The messages of a page, with each entry of a "log" message also given as
// a message of its own, {"type": "log-entry", ...entry}, since entries are
// batched as they come.
class Page
{
  public:
    explicit Page(ide_test::WebSocketClient &client)
      : client_(client)
    {
    }

    std::optional<Json> next(milliseconds limit)
    {
        if (pending_.empty()) {
            std::optional<std::string> text = client_.receive(limit);
            if (!text)
                return std::nullopt;
            Json message = Json::parse(*text, nullptr, false);
            pending_.push_back(message);
            if (message.value("type", "") == "log")
                for (Json entry : message["entries"]) {
                    entry["type"] = "log-entry";
                    pending_.push_back(entry);
                }
        }
        Json message = std::move(pending_.front());
        pending_.pop_front();
        return message;
    }

  private:
    ide_test::WebSocketClient &client_;
    std::deque<Json> pending_;
};

// Waits for a message matching `expected`, skipping others; the messages
// seen are added to `seen` for the failure report.
bool await(Page &page, const Json &expected, std::string &seen)
{
    auto deadline = Clock::now() + EXPECT_LIMIT;
    while (Clock::now() < deadline) {
        auto left = std::chrono::duration_cast<milliseconds>(deadline - Clock::now());
        std::optional<Json> message = page.next(left);
        if (!message)
            return false;
        if (matches(expected, *message))
            return true;
        std::string type = message->value("type", "");
        if (type != "variables" && type != "status" && type != "log")
            seen += "  " + message->dump().substr(0, 300) + "\n";
    }
    return false;
}

bool await(ide_test::WebSocketClient &client, const Json &expected, std::string &seen)
{
    Page page(client);
    return await(page, expected, seen);
}

// Whether the reply to request `request_id` says ok (false: no reply).
bool answered_ok(Page &page, uint64_t request_id)
{
    for (;;) {
        std::optional<Json> reply = page.next(EXPECT_LIMIT);
        if (!reply)
            return false;
        if (reply->value("id", uint64_t(0)) == request_id)
            return reply->value("ok", false);
    }
}

// Waits until robots 1..count of the first target can take a program.
void await_robots(ide_test::WebSocketClient &client, Page &page, unsigned count)
{
    uint64_t request_id = 1000000; // above a trace's own ids
    for (unsigned id = 1; id <= count; id++) {
        bool ready = false;
        auto deadline = Clock::now() + EXPECT_LIMIT;
        while (!ready && Clock::now() < deadline) {
            request_id++;
            client.send(Json{
              { "id", request_id },
              { "type", "compile" },
              { "robot", "0:" + std::to_string(id) },
              { "source",
                "" } }.dump());
            ready = answered_ok(page, request_id);
            if (!ready)
                std::this_thread::sleep_for(milliseconds(100));
        }
        ASSERT_TRUE(ready) << "robot 0:" << id << " never became ready";
    }
}

// Runs a trace: "robots N" (first), "ready N" waits until robots 1..N are
// described, "> JSON" sends, "< JSON" awaits a matching message (a "log"
// message's entries also come as "log-entry" messages), "stop-robots" /
// "start-robots" stop and restart the emulator on the same port, "sleep
// MS", "#" comments.
void run_trace(const std::filesystem::path &path)
{
    std::ifstream file(path);
    ASSERT_TRUE(file) << path;
    std::vector<std::pair<unsigned, std::string>> lines;
    std::string line;
    for (unsigned number = 1; std::getline(file, line); number++)
        if (!line.empty() && line[0] != '#')
            lines.emplace_back(number, line);
    ASSERT_FALSE(lines.empty());
    unsigned robot_count = 2;
    if (lines.front().second.rfind("robots ", 0) == 0) {
        robot_count = unsigned(std::stoul(lines.front().second.substr(7)));
        lines.erase(lines.begin());
    }
    uint16_t port = console_test::find_free_port();
    Robots robots(port, robot_count);
    Server server("tcp:localhost;" + std::to_string(port));
    ide_test::WebSocketClient client(server.url());
    Page page(client);
    for (const auto &[number, text] : lines) {
        SCOPED_TRACE(path.filename().string() + ":" + std::to_string(number));
        if (text.rfind("ready ", 0) == 0) {
            await_robots(client, page, unsigned(std::stoul(text.substr(6))));
        } else if (text.rfind("> ", 0) == 0) {
            client.send(text.substr(2));
        } else if (text.rfind("< ", 0) == 0) {
            Json expected = Json::parse(text.substr(2), nullptr, false);
            ASSERT_FALSE(expected.is_discarded()) << "not JSON: " << text;
            std::string seen;
            ASSERT_TRUE(await(page, expected, seen)) << "never received " << text << "\nreceived:\n"
                                                     << seen;
        } else if (text == "stop-robots") {
            robots.stop();
        } else if (text == "start-robots") {
            robots.start();
        } else if (text.rfind("sleep ", 0) == 0) {
            std::this_thread::sleep_for(milliseconds(std::stoul(text.substr(6))));
        } else {
            FAIL() << "unknown trace line: " << text;
        }
    }
}

class Traces : public testing::TestWithParam<std::string>
{
};

TEST_P(Traces, RunsAsWritten)
{
    run_trace(std::filesystem::path("tests/ide_server/data") / GetParam());
}

std::vector<std::string> trace_names()
{
    std::vector<std::string> names;
    for (const auto &entry : std::filesystem::directory_iterator("tests/ide_server/data"))
        if (entry.path().extension() == ".trace")
            names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

INSTANTIATE_TEST_SUITE_P(Ide,
                         Traces,
                         testing::ValuesIn(trace_names()),
                         [](const testing::TestParamInfo<std::string> &trace) {
                             std::string name = trace.param.substr(0, trace.param.find('.'));
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

// Robot `name` as the page first sees it described: in the hello, or in a
// robot message; null if never.
Json described_robot(Page &page, const std::string &name)
{
    auto deadline = Clock::now() + EXPECT_LIMIT;
    while (Clock::now() < deadline) {
        std::optional<Json> message = page.next(EXPECT_LIMIT);
        if (!message)
            break;
        Json robots = message->value("type", "") == "hello" ? message->value("robots", Json())
                      : message->value("type", "") == "robot"
                        ? Json::array({ message->value("robot", Json()) })
                        : Json();
        for (const Json &robot : robots)
            if (robot.value("robot", "") == name && robot.value("described", false))
                return robot;
    }
    return Json();
}

// Robots started with the project's program (epuck-emu --load, as make run
// does) are known to run it when the IDE is told so: its variables are named
// from the start, without a load. Without being told, the IDE cannot know
// (Aseba cannot read bytecode back) and names none.
TEST(IdeServer, RobotsThatRunTheProjectAreKnownToFromTheStartWhenToldSo)
{
    const std::string project = "examples/paper-annex.aesl";
    uint16_t port = console_test::find_free_port();
    Robots robots(port, 2, { "--load", project });
    console_test::ScratchFolder scratch;
    std::string copy = scratch.path() + "/paper-annex.aesl";
    std::filesystem::copy_file(project, copy);
    for (bool told : { true, false }) {
        SCOPED_TRACE(told ? "told" : "not told");
        aseba::ide::IdeOptions options;
        options.project_path = copy;
        options.robots_run_project = told;
        Server server("tcp:localhost;" + std::to_string(port), options);
        ide_test::WebSocketClient client(server.url());
        Page page(client);
        Json robot = described_robot(page, "0:1");
        ASSERT_FALSE(robot.is_null()) << "robot 0:1 never described";
        EXPECT_EQ(robot.contains("program"), told) << robot.dump().substr(0, 400);
        bool badness_named = false;
        for (const Json &variable : robot.value("variables", Json::array()))
            if (variable.value("name", "") == "badness" && variable.value("user", false))
                badness_named = true;
        EXPECT_EQ(badness_named, told);
        if (told) {
            EXPECT_EQ(robot["program"].value("bytecodeWords", 0), 206); // asebac's size of it
        }
    }
}

TEST(IdeServer, TwentyTabsAtOnceAreAllServed)
{
    uint16_t port = console_test::find_free_port();
    Robots robots(port, 2);
    Server server("tcp:localhost;" + std::to_string(port));
    std::vector<std::unique_ptr<ide_test::WebSocketClient>> tabs;
    for (int i = 0; i < 20; i++)
        tabs.push_back(std::make_unique<ide_test::WebSocketClient>(server.url()));
    for (size_t i = 0; i < tabs.size(); i++) {
        std::string seen;
        ASSERT_TRUE(await(*tabs[i], Json{ { "type", "hello" } }, seen)) << "tab " << i;
        tabs[i]->send(R"({"id": 5, "type": "watch", "robots": ["0:1"]})");
        ASSERT_TRUE(await(*tabs[i], Json{ { "type", "reply" }, { "id", 5 }, { "ok", true } }, seen))
          << "tab " << i;
    }
    // Every tab shows robot 1's variables.
    for (size_t i = 0; i < tabs.size(); i++) {
        std::string seen;
        EXPECT_TRUE(await(*tabs[i], Json{ { "type", "variables" }, { "robot", "0:1" } }, seen))
          << "tab " << i;
    }
}

TEST(IdeServer, APageOfAnotherSiteCannotOpenTheWebSocket)
{
    uint16_t port = console_test::find_free_port();
    Robots robots(port, 1);
    Server server("tcp:localhost;" + std::to_string(port));
    std::string own = "http://127.0.0.1:" + std::to_string(server.port());
    EXPECT_NO_THROW(ide_test::WebSocketClient(server.url(), own));
    try {
        ide_test::WebSocketClient client(server.url(), "http://attacker.example");
        FAIL() << "a page of another site opened the WebSocket";
    } catch (const std::runtime_error &error) {
        EXPECT_NE(std::string(error.what()).find("403"), std::string::npos) << error.what();
    }
}

// A WebSocket opened by hand, with a small receive buffer, whose page asks
// to watch `request`'s robots and then reads nothing.
int open_stalled_page(uint16_t port, const std::string &request)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    int small = 4096;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0)
        throw std::runtime_error("cannot connect");
    std::string handshake =
      "GET /ws HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";
    // A client's frame is masked (RFC 6455 §5.3); a zero mask keeps it readable.
    std::string frame = { char(0x81), char(0x80 | request.size()), 0, 0, 0, 0 };
    std::string bytes = handshake + frame + request;
    if (write(fd, bytes.data(), bytes.size()) != ssize_t(bytes.size()))
        throw std::runtime_error("cannot write");
    return fd;
}

// Everything the server sends to `fd` during `duration`.
std::string read_for(int fd, milliseconds duration)
{
    std::string received;
    auto deadline = Clock::now() + duration;
    std::vector<char> buffer(1 << 16);
    while (Clock::now() < deadline) {
        ssize_t count = recv(fd, buffer.data(), buffer.size(), MSG_DONTWAIT);
        if (count > 0)
            received.append(buffer.data(), size_t(count));
        else
            std::this_thread::sleep_for(milliseconds(10));
    }
    return received;
}

TEST(IdeServer, APageThatStopsReadingMissesUpdatesAndIsToldWhileOthersAreServed)
{
    uint16_t port = console_test::find_free_port();
    Robots robots(port, 2);
    aseba::ide::IdeOptions options;
    options.web.max_buffered_bytes = 32 * 1024;
    options.web.socket_send_buffer_bytes = 8 * 1024;
    Server server("tcp:localhost;" + std::to_string(port), options);
    int stalled = open_stalled_page(server.port(), R"({"type":"watch","robots":["0:1","0:2"]})");

    ide_test::WebSocketClient reader(server.url());
    Page page(reader);
    await_robots(reader, page, 2);
    std::string seen;
    // Robot 1 emits as fast as it can: the log and the variables flood the
    // stalled page.
    reader.send(
      R"({"id": 1, "type": "definitions", "events": [{"name": "tick", "size": 8}], "constants": []})");
    ASSERT_TRUE(await(page, Json{ { "type", "reply" }, { "id", 1 }, { "ok", true } }, seen));
    reader.send(
      R"({"id": 2, "type": "load", "programs": [{"robot": "0:1", "source": "var n[8]\nonevent ir_sensors\nn[0]++\nemit tick n\nemit tick n\nemit tick n\nemit tick n"}]})");
    ASSERT_TRUE(await(page, Json{ { "type", "reply" }, { "id", 2 }, { "ok", true } }, seen))
      << seen;

    // The reading page gets its replies promptly all along.
    for (int round = 0; round < 20; round++) {
        reader.send(R"({"id": 3, "type": "compile", "robot": "0:2", "source": "var y = 2"})");
        auto sent = Clock::now();
        ASSERT_TRUE(await(page, Json{ { "type", "reply" }, { "id", 3 }, { "ok", true } }, seen));
        EXPECT_LT(Clock::now() - sent, milliseconds(500)) << "round " << round;
        std::this_thread::sleep_for(milliseconds(250));
    }
    // When the stalled page reads again, it is told what it missed, and its
    // connection is still open.
    std::string received = read_for(stalled, milliseconds(3000));
    close(stalled);
    EXPECT_NE(received.find("\"type\":\"hello\""), std::string::npos);
    EXPECT_NE(received.find("\"type\":\"skipped\""), std::string::npos)
      << received.size() << " bytes received, no 'skipped'";
}

// Nobody listens on port 1 of the loopback: a server without robots.
const char *const NO_ROBOTS = "tcp:127.0.0.1;1";

// The page of the tests that need one.
const std::vector<aseba::ide::StaticFile> A_PAGE = {
    { "/index.html", "text/html", "<p>page</p>" }
};

// The server's answer to a request written by hand, sent to `host`: its
// status code (0: none, or no connection) and its head.
struct HttpAnswer {
    int status = 0;
    std::string head;
};

HttpAnswer ask(uint16_t port, const std::string &request, const char *host = "127.0.0.1")
{
    HttpAnswer answer;
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    inet_pton(AF_INET, host, &address.sin_addr);
    if (connect(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0 ||
        write(fd, request.data(), request.size()) != ssize_t(request.size())) {
        close(fd);
        return answer;
    }
    auto deadline = Clock::now() + EXPECT_LIMIT;
    char buffer[4096];
    while (answer.head.find("\r\n\r\n") == std::string::npos && Clock::now() < deadline) {
        pollfd waiting{ fd, POLLIN, 0 };
        if (poll(&waiting, 1, 100) <= 0)
            continue;
        ssize_t count = read(fd, buffer, sizeof buffer);
        if (count <= 0)
            break;
        answer.head.append(buffer, size_t(count));
    }
    close(fd);
    answer.head = answer.head.substr(0, answer.head.find("\r\n\r\n"));
    if (answer.head.rfind("HTTP/1.1 ", 0) == 0)
        answer.status = std::stoi(answer.head.substr(9, 3));
    return answer;
}

// A request for `resource` naming `host`; a WebSocket's opening when
// `websocket`; with the Origin and Cookie headers given (when not empty).
std::string request_for(const std::string &resource,
                        const std::string &host,
                        bool websocket,
                        const std::string &origin = "",
                        const std::string &cookie = "")
{
    std::string request = "GET " + resource + " HTTP/1.1\r\nHost: " + host + "\r\n";
    if (websocket)
        request += "Upgrade: websocket\r\nConnection: Upgrade\r\n"
                   "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n";
    if (!origin.empty())
        request += "Origin: " + origin + "\r\n";
    if (!cookie.empty())
        request += "Cookie: " + cookie + "\r\n";
    return request + "\r\n";
}

// `text` with every "PORT" replaced by `port`.
std::string with_port(std::string text, uint16_t port)
{
    for (size_t at = text.find("PORT"); at != std::string::npos; at = text.find("PORT", at))
        text.replace(at, 4, std::to_string(port));
    return text;
}

// DNS rebinding: a page of evil.example whose name its owner makes resolve
// to this computer sends its own name as Host and as Origin. The Origin
// check alone let its WebSocket in, and it stopped a robot. Only the names
// this server is reached by are served: loopback names, addresses.
struct HostCase {
    const char *host;
    const char *origin; // "": none
    bool websocket;
    int status; // 101: the WebSocket opens; 200: the page is served
};

const HostCase host_cases[] = {
    { "evil.example:PORT", "http://evil.example:PORT", true, 403 },
    { "evil.example:PORT", "", true, 403 },
    { "evil.example:PORT", "", false, 403 },
    { "EVIL.example.:PORT", "", false, 403 },
    { "localhost:PORT", "http://localhost:PORT", true, 101 },
    { "127.0.0.1:PORT", "http://127.0.0.1:PORT", true, 101 },
    { "[::1]:PORT", "http://[::1]:PORT", true, 101 },
    { "robots.localhost:PORT", "http://robots.localhost:PORT", true, 101 },
    { "localhost:PORT", "", false, 200 },
    { "127.0.0.1:PORT", "http://attacker.example", true, 403 },
};

TEST(IdeServer, OnlyTheNamesItIsReachedByAreServed)
{
    Server server(NO_ROBOTS, {}, A_PAGE);
    for (const HostCase &host_case : host_cases) {
        std::string host = with_port(host_case.host, server.port());
        SCOPED_TRACE(host + (host_case.websocket ? " (WebSocket)" : " (page)"));
        HttpAnswer answer = ask(server.port(),
                                request_for(host_case.websocket ? "/ws" : "/",
                                            host,
                                            host_case.websocket,
                                            with_port(host_case.origin, server.port())));
        EXPECT_EQ(answer.status, host_case.status) << answer.head;
    }
}

// Bound beyond the loopback, the server asks for its token (the address
// aseba-ide prints carries it, then a cookie does): the page and its
// WebSocket are refused without it.
struct TokenCase {
    const char *resource;
    const char *cookie; // "": none
    bool websocket;
    int status;
};

const TokenCase token_cases[] = {
    { "/ws", "", true, 403 },
    { "/ws?token=wrong", "", true, 403 },
    { "/ws?token=a-token", "", true, 101 },
    { "/ws", "aseba-ide-token-PORT=a-token", true, 101 },
    { "/ws", "aseba-ide-token-1=a-token", true, 403 },
    { "/", "", false, 403 },
    { "/?token=a-tokeX", "", false, 403 },
    { "/?token=a-token", "", false, 200 },
    { "/", "other=1; aseba-ide-token-PORT=a-token", false, 200 },
};

TEST(IdeServer, WithATokenNothingIsServedWithoutIt)
{
    aseba::ide::IdeOptions options;
    options.web.access_token = "a-token";
    Server server(NO_ROBOTS, options, A_PAGE);
    std::string host = "127.0.0.1:" + std::to_string(server.port());
    for (const TokenCase &token_case : token_cases) {
        SCOPED_TRACE(std::string(token_case.resource) + " " + token_case.cookie);
        HttpAnswer answer = ask(server.port(),
                                request_for(token_case.resource,
                                            host,
                                            token_case.websocket,
                                            "",
                                            with_port(token_case.cookie, server.port())));
        EXPECT_EQ(answer.status, token_case.status) << answer.head;
    }
    // The page's address sets the cookie that its own requests then carry.
    HttpAnswer page = ask(server.port(), request_for("/?token=a-token", host, false));
    EXPECT_TRUE(page.head.find("Set-Cookie: aseba-ide-token-" + std::to_string(server.port()) +
                               "=a-token;") != std::string::npos)
      << page.head;
}

// What a page can make the server keep is bounded: scripts of robots that
// are or were on the network only (see data/scripts.trace), and all of them
// within a budget (1,604 scripts of 250 KB for robots that never were took
// the server to 1.18 GB).
TEST(IdeServer, TheScriptsItKeepsStayWithinTheirBudget)
{
    uint16_t port = console_test::find_free_port();
    Robots robots(port, 2);
    aseba::ide::IdeOptions options;
    options.max_script_bytes = 100 * 1024;
    Server server("tcp:localhost;" + std::to_string(port), options);
    ide_test::WebSocketClient client(server.url());
    Page page(client);
    await_robots(client, page, 2);
    struct Step {
        const char *robot;
        size_t kilobytes;
        Json reply; // what the reply must hold
    };
    const Step steps[] = {
        { "0:1", 60, { { "ok", true } } },
        { "0:2", 60, { { "ok", false }, { "error", "~more than the 102400 the IDE keeps" } } },
        { "0:1", 30, { { "ok", true } } }, // a script replaced counts once
        { "0:2", 60, { { "ok", true } } },
    };
    uint64_t id = 0;
    for (const Step &step : steps) {
        SCOPED_TRACE(std::string(step.robot) + ", " + std::to_string(step.kilobytes) + " KB");
        client.send(Json{ { "id", ++id },
                          { "type", "script" },
                          { "robot", step.robot },
                          { "source", std::string(step.kilobytes * 1024, 'x') } }
                      .dump());
        Json expected = step.reply;
        expected["type"] = "reply";
        expected["id"] = id;
        std::string seen;
        EXPECT_TRUE(await(page, expected, seen)) << seen;
    }
}

// Opening a project of 34,000 nodes (1.9 MB) blocked the server for 21 s,
// and every page with it: reading was quadratic, and done on the thread that
// serves the pages. Another page is answered while it opens, and it opens
// within the usual wait.
TEST(IdeServer, AnotherPageIsServedWhileALargeProjectOpens)
{
    Server server(NO_ROBOTS);
    ide_test::WebSocketClient opener(server.url());
    ide_test::WebSocketClient other(server.url());
    Page opener_page(opener), other_page(other);
    std::string seen;
    ASSERT_TRUE(await(opener_page, Json{ { "type", "hello" } }, seen));
    ASSERT_TRUE(await(other_page, Json{ { "type", "hello" } }, seen));

    std::string project = "<!DOCTYPE aesl-source>\n<network>\n";
    for (int i = 0; i < 34000; i++)
        project +=
          "<node nodeId=\"" + std::to_string(i % 65535) + "\" name=\"e-puck\">var x</node>\n";
    project += "</network>\n";
    opener.send(Json{
      { "id", 1 }, { "type", "open-project" }, { "name", "large.aesl" }, { "content", project } }
                  .dump());
    other.send(R"({"id": 2, "type": "watch", "robots": []})");
    ASSERT_TRUE(await(other_page, Json{ { "type", "reply" }, { "id", 2 }, { "ok", true } }, seen))
      << seen;
    EXPECT_TRUE(await(opener_page, Json{ { "type", "reply" }, { "id", 1 }, { "ok", true } }, seen))
      << seen;
}

// The server's port holds a bounded number of connections (it had no cap:
// enough of them exhausted its descriptors). A newcomer beyond the cap is
// closed at once, until the connection silent the longest has been so for
// the grace: then it gives way.
TEST(IdeServer, ItsPortHoldsABoundedNumberOfConnectionsAndTheSilentGiveWay)
{
    aseba::ide::IdeOptions options;
    options.web.connections = { 3, std::chrono::milliseconds(2000) };
    Server server(NO_ROBOTS, options);
    std::vector<std::unique_ptr<ide_test::WebSocketClient>> pages;
    for (int i = 0; i < 3; i++)
        pages.push_back(std::make_unique<ide_test::WebSocketClient>(server.url()));
    auto opened_at = Clock::now();
    EXPECT_THROW(ide_test::WebSocketClient late(server.url()), std::runtime_error);
    std::this_thread::sleep_until(opened_at + milliseconds(2200));
    ide_test::WebSocketClient newcomer(server.url());
    std::string seen;
    EXPECT_TRUE(await(newcomer, Json{ { "type", "hello" } }, seen));
    auto deadline = Clock::now() + EXPECT_LIMIT;
    while (!pages[0]->closed() && Clock::now() < deadline)
        std::this_thread::sleep_for(milliseconds(20));
    EXPECT_TRUE(pages[0]->closed()) << "the page silent the longest was not closed";
    EXPECT_FALSE(pages[1]->closed());
    EXPECT_FALSE(pages[2]->closed());
}

// aseba-ide itself: by default on the loopback only, where its address has
// no token; bound beyond, the address it prints carries one, without which
// its WebSocket is refused.
TEST(AsebaIde, BoundBeyondTheLoopbackItServesOnlyThoseGivenItsAddress)
{
    for (bool beyond : { false, true }) {
        SCOPED_TRACE(beyond ? "--bind 0.0.0.0" : "default");
        console_test::ScratchFolder scratch;
        std::string log = scratch.path() + "/aseba-ide.log";
        std::vector<std::string> command{
            console_test::program_path("aseba-ide"), "--port", "0", NO_ROBOTS
        };
        if (beyond)
            command.insert(command.end(), { "--bind", "0.0.0.0" });
        console_test::ReferenceProgram ide(command, {}, log);
        std::string line;
        auto deadline = Clock::now() + EXPECT_LIMIT;
        while (line.find(" (robots on") == std::string::npos && Clock::now() < deadline) {
            std::this_thread::sleep_for(milliseconds(50));
            std::ifstream file(log);
            std::getline(file, line);
        }
        size_t open = line.find("open http://");
        ASSERT_NE(open, std::string::npos) << line;
        size_t colon = line.find(':', open + 12);
        uint16_t port = uint16_t(std::stoi(line.substr(colon + 1)));
        std::string host = "127.0.0.1:" + std::to_string(port);
        size_t token_at = line.find("?token=");
        EXPECT_EQ(token_at != std::string::npos, beyond) << line;
        EXPECT_EQ(ask(port, request_for("/ws", host, true)).status, beyond ? 403 : 101);
        // 127.0.0.2 is this computer, but not the loopback address listened
        // on: as another computer, it is not served by default.
        EXPECT_EQ(ask(port, request_for("/ws", host, true), "127.0.0.2").status != 0, beyond);
        if (beyond) {
            std::string token = line.substr(token_at + 7, line.find(' ', token_at) - token_at - 7);
            EXPECT_EQ(token.size(), 32u) << line;
            EXPECT_EQ(ask(port, request_for("/ws?token=" + token, host, true)).status, 101);
        }
    }
}

} // namespace

// The server is a client like any other: against a reference node (an
// e-puck of Debian's asebaplayground behind asebaswitch) it compiles against
// the node's own description, loads, debugs and exchanges events.
TEST(IdeServer, DrivesAReferencePlaygroundEpuckThroughAReferenceSwitch)
{
    console_test::PlaygroundBehindSwitch reference;
    Server server(reference.target());
    ide_test::WebSocketClient client(server.url());
    Page page(client);
    await_robots(client, page, 1);
    std::string seen;
    // The playground's e-puck has speed.left, not our firmware's leftSpeed.
    client.send(R"({"id": 1, "type": "compile", "robot": "0:1", "source": "speed.left = 1"})");
    ASSERT_TRUE(await(
      page, Json{ { "type", "reply" }, { "id", 1 }, { "compile", { { "ok", true } } } }, seen))
      << seen;
    client.send(R"({"id": 2, "type": "compile", "robot": "0:1", "source": "leftSpeed = 1"})");
    ASSERT_TRUE(await(
      page,
      Json{ { "type", "reply" },
            { "id", 2 },
            { "compile",
              { { "ok", false },
                { "error", { { "line", 1 }, { "message", "~leftSpeed is not a defined" } } } } } },
      seen))
      << seen;

    client.send(
      R"({"id": 3, "type": "definitions", "events": [{"name": "ping", "size": 2}, {"name": "pong", "size": 2}], "constants": []})");
    ASSERT_TRUE(await(page, Json{ { "type", "reply" }, { "id", 3 }, { "ok", true } }, seen))
      << seen;
    client.send(
      R"({"id": 4, "type": "load", "programs": [{"robot": "0:1", "source": "var counter = 0\nonevent ir_sensors\n  counter = counter + 1\nonevent ping\n  emit pong [args[0] + args[1], id]\n"}]})");
    ASSERT_TRUE(await(page, Json{ { "type", "reply" }, { "id", 4 }, { "ok", true } }, seen))
      << seen;
    client.send(R"({"id": 5, "type": "emit", "event": "ping", "args": [40, 2]})");
    ASSERT_TRUE(await(
      page,
      Json{
        { "type", "log-entry" }, { "source", "0:1" }, { "name", "pong" }, { "args", { 42, 1 } } },
      seen))
      << seen;
    client.send(
      R"({"id": 6, "type": "set-variable", "robot": "0:1", "name": "speed.left", "values": [55]})");
    ASSERT_TRUE(await(page, Json{ { "type", "reply" }, { "id", 6 }, { "ok", true } }, seen))
      << seen;

    // A breakpoint in the ir_sensors handler (about 40 Hz on the playground).
    client.send(R"({"id": 7, "type": "breakpoints", "robot": "0:1", "lines": [3]})");
    ASSERT_TRUE(await(page,
                      Json{ { "type", "reply" },
                            { "id", 7 },
                            { "ok", true },
                            { "breakpoints", { { { "line", 3 }, { "set", true } } } } },
                      seen))
      << seen;
    ASSERT_TRUE(
      await(page,
            Json{ { "type", "robot" },
                  { "robot", { { "robot", "0:1" }, { "state", "stepping" }, { "line", 3 } } } },
            seen))
      << seen;
    client.send(R"({"id": 8, "type": "control", "robots": ["0:1"], "action": "stop"})");
    ASSERT_TRUE(await(page, Json{ { "type", "reply" }, { "id", 8 }, { "ok", true } }, seen))
      << seen;
    EXPECT_TRUE(reference.running()) << "asebaplayground or asebaswitch ended";
}
