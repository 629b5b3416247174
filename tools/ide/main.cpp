// aseba-ide: the group IDE, served to any browser of the lab.

#include <csignal>
#include <cstdio>
#include <iostream>
#include <random>
#include <unistd.h>

#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>

#include "ide_server.hpp"
#include "tools/client/terminal_text.hpp"
#include "tools/command_line/command_line.hpp"
#include "web_assets.hpp"

namespace
{

constexpr uint16_t DEFAULT_PORT = 33380;

const char *const USAGE = "usage: aseba-ide [options] [TARGET...]";

const char *const DESCRIPTION =
  R"(The Aseba group IDE: program, debug and watch a whole group of robots from a
web page. Serves the page on http://ADDRESS:PORT/ and joins the Aseba
networks given as TARGETs; prints the address to open. Every browser tab
that opens it shows the same robots, scripts and definitions
(docs/ide.md).)";

// Descriptors the IDE needs besides its web port's connections: its
// listener, its links to the robots and the arena, standard streams,
// sanitizers, a margin.
constexpr size_t OTHER_DESCRIPTORS = 64;

// 128 random bits, as hexadecimal digits.
std::string random_token()
{
    std::random_device source;
    std::string token;
    for (int i = 0; i < 4; i++) {
        char word[9];
        std::snprintf(word, sizeof word, "%08x", unsigned(source()));
        token += word;
    }
    return token;
}

// This computer's name, which other computers may use to reach it.
std::string host_name()
{
    char name[256] = {};
    return gethostname(name, sizeof name - 1) == 0 ? name : "";
}

// The address to open: the bind address, or this computer's name when it
// listens on every interface; with the token when one is needed.
std::string page_address(const aseba::ide::WebServerOptions &web, uint16_t port)
{
    std::string host = web.bind_address;
    if (host == "0.0.0.0" || host == "::")
        host = web.host_names.empty() ? "localhost" : web.host_names.back();
    else if (host.find(':') != std::string::npos)
        host = "[" + host + "]";
    std::string address = "http://" + host + ":" + std::to_string(port) + "/";
    return web.access_token.empty() ? address : address + "?token=" + web.access_token;
}

// The program; its output is checked by main.
int serve(int argc, char **argv)
{
    using namespace aseba;
    ide::IdeOptions options;
    options.web.port = DEFAULT_PORT;
    unsigned timeout_ms = unsigned(client::DEFAULT_ANSWER_TIMEOUT.count());

    CLI::App app(DESCRIPTION, "aseba-ide");
    auto formatter = command_line::use_common_style(app);
    formatter->set_usage(&app, USAGE);
    app.footer(command_line::EXIT_STATUS_TEXT);
    app
      .add_option("targets",
                  options.targets,
                  "Aseba networks to join: tcp:HOST;PORT, HOST:PORT, ser:device=PATH or a\n"
                  "serial device path; several at once (default tcp:localhost;33333)")
      ->type_name("TARGET");
    app
      .add_option("-p,--port",
                  options.web.port,
                  "the port of the page and its WebSocket (default 33380; 0: any free port)")
      ->check(CLI::Range(0, 65535).description(""))
      ->type_name("N");
    app
      .add_option("--bind",
                  options.web.bind_address,
                  "the address to listen on (default 127.0.0.1, this computer only);\n"
                  "beyond the loopback (0.0.0.0: every interface), the page's address\n"
                  "carries a token printed at start, without which nothing is served:\n"
                  "whoever has that address can program the robots")
      ->type_name("ADDRESS");
    app
      .add_option("--allow-host",
                  options.web.host_names,
                  "a name of this computer that browsers may use to reach the page\n"
                  "(repeatable; localhost, IP addresses and, with --bind beyond the\n"
                  "loopback, this computer's host name are always allowed)")
      ->type_name("NAME");
    app
      .add_option("--project",
                  options.project_path,
                  "an .aesl project to open at start and to save to (created by the\n"
                  "first save)")
      ->type_name("FILE");
    app.add_flag("--robots-run-project",
                 options.robots_run_project,
                 "the robots already run the project's programs (as epuck-emu --load\n"
                 "of the same file gives them): name their variables and lines from the\n"
                 "start, without loading");
    app
      .add_option("--arena",
                  options.arena_feed,
                  "the arena feed of simulated robots (epuck-emu --arena-feed PORT), as\n"
                  "tcp:HOST;PORT or HOST:PORT: shows the arena, with the first target's\n"
                  "robots in it")
      ->type_name("FEED");
    app
      .add_option("--timeout",
                  timeout_ms,
                  "how long to wait for a robot's answer, in milliseconds (default 1000)")
      ->check(CLI::Range(10u, 60000u).description(""))
      ->type_name("MS");
    command_line::parse_or_exit(app, argc, argv);
    if (options.targets.empty())
        options.targets.push_back(client::DEFAULT_TARGET);
    options.answer_timeout = client::Milliseconds(timeout_ms);
    // Beyond the loopback, anyone who reaches the port could drive the
    // robots (Aseba has no authentication): only those given the address
    // with its token may, as with Jupyter.
    if (!ide::is_loopback_address(options.web.bind_address)) {
        options.web.access_token = random_token();
        if (std::string name = host_name(); !name.empty())
            options.web.host_names.push_back(name);
    }

    try {
        connections::reserve_descriptors(options.web.connections.capacity + OTHER_DESCRIPTORS);
        asio::io_context io;
        ide::IdeServer server(io, options, ide::web_assets());
        asio::signal_set signals(io, SIGINT, SIGTERM);
        signals.async_wait([&](const std::error_code &, int) {
            server.stop();
            io.stop();
        });
        std::cout << "aseba-ide: open " << page_address(options.web, server.port())
                  << " (robots on";
        for (const std::string &target : options.targets)
            std::cout << " " << target;
        std::cout << "; Ctrl-C stops)" << std::endl;
        // Nobody could open the page without this line (main says why).
        if (!std::cout || std::fflush(stdout) != 0)
            return command_line::EXIT_FAILED;
        io.run();
    } catch (const std::exception &error) {
        std::cerr << "aseba-ide: " << error.what() << "\n";
        return command_line::EXIT_FAILED;
    }
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    // Its messages may name robots as the network does: escaped before a
    // terminal sees them.
    aseba::client::TerminalFilter errors(std::cerr);
    return aseba::command_line::finish_standard_output("aseba-ide", serve(argc, argv));
}
