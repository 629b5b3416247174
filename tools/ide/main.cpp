// aseba-ide: the group IDE, served to any browser of the lab.

#include <csignal>
#include <iostream>

#include <CLI/CLI.hpp>
#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>

#include "ide_server.hpp"
#include "web_assets.hpp"

namespace
{

constexpr uint16_t DEFAULT_PORT = 33380;

} // namespace

int main(int argc, char **argv)
{
    using namespace aseba;
    ide::IdeOptions options;
    options.web.port = DEFAULT_PORT;
    unsigned timeout_ms = unsigned(client::DEFAULT_ANSWER_TIMEOUT.count());

    CLI::App app(
      "The Aseba group IDE: program, debug and watch a whole group of robots from a web page.\n"
      "Serves the page on http://ADDRESS:PORT/ and joins the Aseba networks given as TARGETs.",
      "aseba-ide");
    app.add_option(
      "targets",
      options.targets,
      "Aseba networks to join: tcp:HOST;PORT, HOST:PORT, ser:device=PATH or a serial device "
      "path; several at once (default tcp:localhost;33333)");
    app
      .add_option(
        "-p,--port", options.web.port, "the port of the page and its WebSocket (0: any free port)")
      ->capture_default_str();
    app
      .add_option(
        "--bind",
        options.web.bind_address,
        "the address to listen on; 0.0.0.0 lets every computer that reaches this one program the "
        "robots (the Aseba protocol has no authentication)")
      ->capture_default_str();
    app.add_option("--project",
                   options.project_path,
                   "an .aesl project to open at start and to save to (created by the first save)");
    app.add_option(
      "--arena",
      options.arena_feed,
      "the arena feed of simulated robots (epuck-emu --arena-feed PORT), as tcp:HOST;PORT or "
      "HOST:PORT: shows the arena, with the first target's robots in it");
    app
      .add_option("--timeout", timeout_ms, "how long to wait for a robot's answer, in milliseconds")
      ->capture_default_str()
      ->check(CLI::Range(10u, 60000u));
    CLI11_PARSE(app, argc, argv);
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
        return 1;
    }
    return 0;
}
