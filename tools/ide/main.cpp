// aseba-ide: the group IDE, served to any browser of the lab.

#include <csignal>
#include <iostream>

#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>

#include "ide_server.hpp"
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

} // namespace

int main(int argc, char **argv)
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
                  "0.0.0.0 lets every computer that reaches this one program the robots\n"
                  "(the Aseba protocol has no authentication)")
      ->type_name("ADDRESS");
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

    try {
        asio::io_context io;
        ide::IdeServer server(io, options, ide::web_assets());
        asio::signal_set signals(io, SIGINT, SIGTERM);
        signals.async_wait([&](const std::error_code &, int) {
            server.stop();
            io.stop();
        });
        std::string host =
          options.web.bind_address == "0.0.0.0" ? "localhost" : options.web.bind_address;
        std::cout << "aseba-ide: open http://" << host << ":" << server.port() << "/ (robots on";
        for (const std::string &target : options.targets)
            std::cout << " " << target;
        std::cout << "; Ctrl-C stops)" << std::endl;
        io.run();
    } catch (const std::exception &error) {
        std::cerr << "aseba-ide: " << error.what() << "\n";
        return command_line::EXIT_FAILED;
    }
    return 0;
}
