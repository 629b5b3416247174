// libFuzzer target for the console's command line (CLI11,
// tools/console/options.cpp) and target strings (parse_target): any argv is
// parsed into Options or refused with a UsageError, any text is a target or
// a TransportError; nothing else escapes, nothing crashes.
//
// Input: the arguments, separated by NUL bytes (argv[0] is "aseba").
//
// Built and run by `make fuzz` (scripts/fuzz.sh).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "tools/client/transport.hpp"
#include "tools/console/console.hpp"

namespace
{

[[noreturn]] void fail(const char *why)
{
    std::fprintf(stderr, "command_line_fuzzer: %s\n", why);
    __builtin_trap();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    std::vector<std::string> arguments{ "aseba" };
    std::string current;
    for (size_t i = 0; i < size; i++) {
        if (data[i] == 0) {
            arguments.push_back(current);
            current.clear();
        } else {
            current += char(data[i]);
        }
    }
    arguments.push_back(current);
    std::vector<char *> argv;
    for (std::string &argument : arguments)
        argv.push_back(argument.data());
    try {
        aseba::console::Options options =
          aseba::console::parse_command_line(int(argv.size()), argv.data());
        if (options.command == "help")
            aseba::console::help_text(options.arguments.empty() ? "" : options.arguments[0]);
        else if (options.targets.empty())
            fail("a command without a target, not even the default");
    } catch (const aseba::console::UsageError &) {
    } catch (...) {
        fail("an exception other than UsageError escaped the command line");
    }
    for (const std::string &argument : arguments) {
        try {
            aseba::client::TargetAddress address = aseba::client::parse_target(argument);
            // The canonical form names the same target.
            aseba::client::TargetAddress again =
              aseba::client::parse_target(aseba::client::target_text(address));
            if (aseba::client::target_text(again) != aseba::client::target_text(address))
                fail("a target's canonical form is another target");
        } catch (const aseba::client::TransportError &) {
        } catch (...) {
            fail("an exception other than TransportError escaped parse_target");
        }
    }
    return 0;
}
