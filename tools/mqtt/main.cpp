// aseba-mqtt: Aseba networks on an MQTT broker (docs/mqtt.md). A thin
// command line over the bridge library.

#include <csignal>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include "bridge.hpp"
#include "tools/client/terminal_text.hpp"
#include "tools/command_line/command_line.hpp"

namespace
{

using namespace aseba;
using namespace aseba::mqtt;

const char *const USAGE = "usage: aseba-mqtt [options] [-t TARGET]... [-b mqtt://HOST:PORT]";

const char *const DESCRIPTION =
  R"(Connects Aseba networks (robots, epuck-emu, a switch) to an MQTT broker, so
that analysis tools subscribe to the swarm's events and networks on several
PCs join into one swarm. Topics (docs/mqtt.md), under PREFIX (default aseba):
  PREFIX/event/NAME                      every event, JSON {"args":[...],...}, QoS 1
  PREFIX/bridge/NAME                     this bridge online or not (retained)
  PREFIX/network/NET/node/ID             each node's description (retained)
  PREFIX/network/NET/node/ID/variable/V  --variable values, on change (retained)
  PREFIX/network/NET/node/ID/command     commands in, with --accept-commands
  PREFIX/network/NET/node/ID/reply       their results
Read-only by default: it publishes and delivers nothing to the robots (a
command gets a refusal on its reply topic). --accept-events delivers the
broker's events to the robots (this joins networks: run one bridge with it in
front of each); --accept-commands runs commands (load, run, pause, stop, reset,
reboot). Who may publish what is the broker's to decide (its users and ACLs).
Event names come from --program or --event; other events go by number. It
runs until interrupted, and keeps reconnecting to the targets and the broker.)";

volatile std::sig_atomic_t stop_flag = 0;

void on_signal(int)
{
    stop_flag = 1;
}

std::string host_name()
{
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) != 0 || name[0] == '\0')
        return "aseba";
    std::string text = name;
    for (char &c : text)
        if (c == '/' || c == '+' || c == '#')
            c = '-';
    return text;
}

struct CommandLine {
    BridgeOptions options;
    std::string broker_url = "mqtt://localhost:1883";
    std::string password_file;
    std::string program_file;
    std::vector<std::string> event_declarations;
    unsigned long variable_period_ms = DEFAULT_VARIABLE_PERIOD.count();
    double duration_seconds = 0;
};

[[noreturn]] void usage_error(const std::string &message)
{
    command_line::print_usage_error("aseba-mqtt", message);
    std::exit(command_line::EXIT_USAGE);
}

CommandLine parse(int argc, char **argv)
{
    CommandLine line;
    BridgeOptions &options = line.options;
    CLI::App app(DESCRIPTION, "aseba-mqtt");
    auto formatter = command_line::use_common_style(app);
    formatter->set_usage(&app, USAGE);
    app.footer(command_line::EXIT_STATUS_TEXT);
    app
      .add_option("-t,--target",
                  options.targets,
                  "an Aseba network: tcp:HOST;PORT, HOST:PORT, ser:device=PATH or a\n"
                  "device path; repeatable (default tcp:localhost;33333)")
      ->allow_extra_args(false)
      ->type_name("TARGET");
    app
      .add_option("-b,--broker",
                  line.broker_url,
                  "the broker: mqtt://HOST:PORT, or mqtts://HOST:PORT for TLS\n"
                  "(default mqtt://localhost:1883; mqtts port 8883)")
      ->type_name("URL");
    app
      .add_option("--name",
                  options.name,
                  "this bridge's name on the broker, and its network's (default:\n"
                  "this computer's name); with several targets, the networks are\n"
                  "NAME-1, NAME-2, ... in their order")
      ->type_name("NAME");
    app.add_option("--prefix", options.topics.prefix, "the topics' first levels (default aseba)")
      ->type_name("PREFIX");
    app.add_flag("--accept-events",
                 options.accept_events,
                 "deliver the events published on the broker to the robots");
    app.add_flag("--accept-commands",
                 options.accept_commands,
                 "run the commands published on the broker (load, run, stop, ...)");
    app
      .add_option("-p,--program",
                  line.program_file,
                  "the program on the robots (.aesl project or script): its event\n"
                  "names and sizes, and its variables for --variable")
      ->type_name("FILE");
    app
      .add_option("--event",
                  line.event_declarations,
                  "declare a global event of SIZE words (without --program);\n"
                  "repeatable, in the program's order")
      ->allow_extra_args(false)
      ->type_name("NAME[:SIZE]");
    app
      .add_option("--variable",
                  options.variables,
                  "publish this variable of every node when it changes: NAME,\n"
                  "NAME[i] or NAME[i:j]; repeatable")
      ->allow_extra_args(false)
      ->type_name("V");
    app
      .add_option("--variable-period",
                  line.variable_period_ms,
                  "how often the variables are read (default 1000)")
      ->check(CLI::Range(10ul, 3600000ul).description(""))
      ->type_name("MS");
    app
      .add_option("--max-event-rate",
                  options.events_per_second,
                  "events per second from the broker to the robots, at most; more\n"
                  "are dropped and logged (default 1000)")
      ->check(CLI::Range(1u, 1000000u).description(""))
      ->type_name("N");
    app
      .add_option("--queue",
                  options.broker.pending_limit,
                  "events kept while the broker is unreachable, sent when it is back\n"
                  "(default 10000; more are dropped and logged)")
      ->check(CLI::Range(size_t(1), size_t(10000000)).description(""))
      ->type_name("N");
    app.add_option("--username", options.broker.username, "the broker's user name")
      ->type_name("USER");
    app
      .add_option("--password",
                  options.broker.password,
                  "the password (other users of this computer may see it: prefer\n"
                  "--password-file)")
      ->type_name("PASSWORD");
    app.add_option("--password-file", line.password_file, "the password: FILE's first line")
      ->type_name("FILE");
    app
      .add_option("--cafile",
                  options.broker.ca_file,
                  "TLS: the authority that signed the broker's certificate (default:\n"
                  "the system's authorities)")
      ->type_name("FILE");
    app.add_option("--capath", options.broker.ca_path, "TLS: a folder of authorities")
      ->type_name("DIR");
    app.add_option("--cert", options.broker.cert_file, "TLS: this client's certificate")
      ->type_name("FILE");
    app.add_option("--key", options.broker.key_file, "TLS: this client's private key")
      ->type_name("FILE");
    app
      .add_option("--keepalive",
                  options.broker.keepalive_seconds,
                  "seconds between pings to the broker; it declares the bridge gone\n"
                  "after 1.5 times that (default 10)")
      ->check(CLI::Range(5, 3600).description(""))
      ->type_name("S");
    app.add_option("--duration", line.duration_seconds, "stop after S seconds (default: never)")
      ->check(CLI::Range(0.0, 1e9).description(""))
      ->type_name("S");
    command_line::parse_or_exit(app, argc, argv);

    try {
        options.broker.address = parse_broker_url(line.broker_url);
    } catch (const BrokerError &error) {
        usage_error(error.what());
    }
    if (options.targets.empty())
        options.targets.push_back(client::DEFAULT_TARGET);
    if (options.name.empty())
        options.name = host_name();
    if (!is_topic_level(options.name))
        usage_error("--name must be a topic level: not empty, no '/', '+' or '#'");
    const std::string &prefix = options.topics.prefix;
    if (prefix.empty() || prefix.find_first_of("+#") != std::string::npos ||
        prefix.front() == '/' || prefix.back() == '/' || prefix.find("//") != std::string::npos)
        usage_error("--prefix must be topic levels without '+', '#' or empty levels");
    for (size_t i = 0; i < options.targets.size(); i++)
        options.networks.push_back(
          options.targets.size() == 1 ? options.name : options.name + "-" + std::to_string(i + 1));
    options.broker.client_id = "aseba-mqtt-" + options.name;
    options.variable_period = Milliseconds(line.variable_period_ms);
    try {
        for (const std::string &text : line.event_declarations)
            options.declared.events.push_back(parse_event_declaration(text));
    } catch (const std::invalid_argument &error) {
        usage_error(error.what());
    }
    return line;
}

// The input files, read before anything connects: one that cannot be used
// is bad usage (status 2).
void read_files(CommandLine &line)
{
    if (!line.password_file.empty()) {
        std::ifstream file(line.password_file);
        if (!file || !std::getline(file, line.options.broker.password)) {
            std::cerr << "aseba-mqtt: " << line.password_file << ": cannot read the password\n";
            std::exit(command_line::EXIT_USAGE);
        }
    }
    if (!line.program_file.empty()) {
        try {
            line.options.program =
              client::read_program_file(line.program_file, line.options.declared);
        } catch (const client::FileError &error) {
            std::cerr << "aseba-mqtt: " << error.what() << "\n";
            std::exit(command_line::EXIT_USAGE);
        }
    }
}

} // namespace

int main(int argc, char **argv)
{
    // The bridge's log names nodes and events as the network does: escaped
    // before a terminal sees them.
    aseba::client::TerminalFilter errors(std::cerr);
    CommandLine line = parse(argc, argv);
    read_files(line);
    struct sigaction action {
    };
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    std::signal(SIGPIPE, SIG_IGN);
    try {
        const BridgeOptions &options = line.options;
        std::cerr << "aseba-mqtt: bridging";
        for (size_t i = 0; i < options.targets.size(); i++)
            std::cerr << " " << options.targets[i] << " (network " << options.networks[i] << ")";
        std::cerr << " to mqtt" << (options.broker.address.tls ? "s" : "") << "://"
                  << options.broker.address.host << ":" << options.broker.address.port << " as "
                  << options.name << "; "
                  << (options.accept_events || options.accept_commands
                        ? std::string("accepting") + (options.accept_events ? " events" : "") +
                            (options.accept_events && options.accept_commands ? " and" : "") +
                            (options.accept_commands ? " commands" : "")
                        : std::string("read-only (publishes only)"))
                  << std::endl;
        Bridge bridge(line.options, std::cerr);
        auto deadline =
          client::Clock::now() + std::chrono::duration_cast<client::Clock::duration>(
                                   std::chrono::duration<double>(line.duration_seconds));
        bridge.run([&] {
            return stop_flag != 0 ||
                   (line.duration_seconds > 0 && client::Clock::now() >= deadline);
        });
    } catch (const client::TransportError &error) {
        command_line::print_usage_error("aseba-mqtt", error.what());
        return command_line::EXIT_USAGE;
    } catch (const std::exception &error) {
        std::cerr << "aseba-mqtt: " << error.what() << "\n";
        return command_line::EXIT_FAILED;
    }
    return command_line::EXIT_OK;
}
