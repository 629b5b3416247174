// Target strings, variable references, program helpers and text for
// terminals of the client library, against the syntax of protocol.md §8 and
// language.md.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <sstream>
#include <stdlib.h>
#include <unistd.h>

#include "tools/client/terminal_text.hpp"
#include "tools/client/transport.hpp"
#include "tools/client/variables.hpp"
#include "tools/compiler/target_presets.hpp"

using namespace aseba;
using namespace aseba::client;

TEST(Targets, DashelAndShortForms)
{
    TargetAddress positional = parse_target("tcp:robots.local;33334");
    EXPECT_EQ(positional.kind, TargetAddress::Kind::tcp);
    EXPECT_EQ(positional.host, "robots.local");
    EXPECT_EQ(positional.port, 33334);

    TargetAddress named = parse_target("tcp:host=127.0.0.1;port=1234");
    EXPECT_EQ(named.host, "127.0.0.1");
    EXPECT_EQ(named.port, 1234);

    TargetAddress host_only = parse_target("tcp:localhost");
    EXPECT_EQ(host_only.port, 33333);

    TargetAddress short_form = parse_target("localhost:40000");
    EXPECT_EQ(short_form.kind, TargetAddress::Kind::tcp);
    EXPECT_EQ(short_form.host, "localhost");
    EXPECT_EQ(short_form.port, 40000);

    TargetAddress serial = parse_target("ser:device=/dev/ttyUSB0");
    EXPECT_EQ(serial.kind, TargetAddress::Kind::serial);
    EXPECT_EQ(serial.device, "/dev/ttyUSB0");
    EXPECT_EQ(serial.baud, 115200u);

    TargetAddress path = parse_target("/dev/rfcomm0");
    EXPECT_EQ(path.kind, TargetAddress::Kind::serial);
    EXPECT_EQ(path.device, "/dev/rfcomm0");

    EXPECT_EQ(parse_target("ser:device=/dev/ttyS1;baud=57600").baud, 57600u);
    EXPECT_EQ(target_text(parse_target("localhost:40000")), "tcp:localhost;40000");
}

TEST(Targets, BadStringsAreExplained)
{
    for (const char *text : { "",
                              "tcp:localhost;0",
                              "tcp:localhost;70000",
                              "tcp:localhost;x",
                              "ser:",
                              "ser:baud=9600",
                              "nowhere",
                              "tcp:colour=blue",
                              "tcp:;33333" })
        EXPECT_THROW(parse_target(text), TransportError) << text;
}

TEST(Targets, UnreachableTcpFailsWithReason)
{
    // Port 1 on the loopback: nothing listens there on a test machine.
    try {
        open_transport(parse_target("tcp:127.0.0.1;1"), 500);
        FAIL() << "connected to port 1";
    } catch (const TransportError &error) {
        EXPECT_NE(std::string(error.what()).find("cannot connect"), std::string::npos);
    }
}

TEST(Targets, MissingSerialDeviceFailsWithReason)
{
    EXPECT_THROW(open_transport(parse_target("ser:device=/nonexistent/tty"), 100), TransportError);
}

TEST(VariableReferences, Syntax)
{
    VariableReference whole = parse_variable_reference("camR");
    EXPECT_EQ(whole.name, "camR");
    EXPECT_FALSE(whole.first.has_value());

    VariableReference one = parse_variable_reference("leds[3]");
    EXPECT_EQ(one.name, "leds");
    EXPECT_EQ(one.first, 3u);
    EXPECT_EQ(one.last, 3u);

    VariableReference range = parse_variable_reference("camR[0:9]");
    EXPECT_EQ(range.first, 0u);
    EXPECT_EQ(range.last, 9u);

    for (const char *bad : { "", "[1]", "a[", "a[1", "a[x]", "a[3:1]", "a[-1]", "a[1:]" })
        EXPECT_THROW(parse_variable_reference(bad), VariableError) << bad;
}

// The e-puck's named variables in memory order (hardware/epuck1.md §6.1,
// robots/epuck/epuck_description.h): id, source, args[32], leftSpeed,
// rightSpeed, leds[8], prox[8], ambiant[8], acc[3], camLine, camR[60] ...
TEST(VariableReferences, ResolvedOnTheEpuck)
{
    auto map = variable_map(epuck_target(), nullptr);
    auto resolve = [&](const char *text) {
        return resolve_variable(parse_variable_reference(text), map);
    };
    EXPECT_EQ(resolve("id").address, 0);
    EXPECT_EQ(resolve("args").length, 32);
    EXPECT_EQ(resolve("leftSpeed").address, 34);
    EXPECT_EQ(resolve("leds").address, 36);
    VariableSlice camera = resolve("camR[0:9]");
    EXPECT_EQ(camera.address, 1 + 1 + 32 + 1 + 1 + 8 + 8 + 8 + 3 + 1);
    EXPECT_EQ(camera.length, 10); // inclusive, as in the language
    EXPECT_EQ(camera.text, "camR[0:9]");
    EXPECT_EQ(resolve("leds[7]").address, 36 + 7);
    EXPECT_THROW(resolve("leds[8]"), VariableError);
    EXPECT_THROW(resolve("counter"), VariableError);
}

// A user variable of a compiled program follows the named ones.
TEST(VariableReferences, UserVariablesOfTheProgram)
{
    ProgramFile file;
    file.file_name = "test.aseba";
    file.script = "var counter = 0\nvar table[4]\n\nonevent ir_sensors\n  counter = counter + 1\n";
    CompiledProgram program = compile_program(file, epuck_target(), 1);
    auto map = variable_map(epuck_target(), &program);
    VariableSlice counter = resolve_variable(parse_variable_reference("counter"), map);
    VariableSlice table = resolve_variable(parse_variable_reference("table[1:3]"), map);
    // The named variables of the e-puck take 1+1+32+1+1+8*3+3+1+60*3 words.
    const uint16_t named_words = 1 + 1 + 32 + 1 + 1 + 8 * 3 + 3 + 1 + 60 * 3;
    EXPECT_GE(counter.address, named_words);
    EXPECT_EQ(table.length, 3);
    EXPECT_NE(counter.address, table.address);
    EXPECT_EQ(source_line_of(program, *address_of_line(program, 5)), 5u);
    EXPECT_EQ(source_line_text(program, 5), "  counter = counter + 1");
    EXPECT_FALSE(address_of_line(program, 3).has_value()); // an empty line
}

TEST(Programs, CompileErrorsNameFileLineAndColumn)
{
    ProgramFile file;
    file.file_name = "broken.aseba";
    file.script = "var x = 0\nx = y + 1\n";
    try {
        compile_program(file, epuck_target(), 1);
        FAIL() << "compiled a program using an undefined variable";
    } catch (const ProgramError &error) {
        EXPECT_EQ(std::string(error.what()).rfind("broken.aseba:2:5:", 0), 0u) << error.what();
    }
}

// A pseudo-terminal stands in for the e-puck's serial link: the transport
// opens it as a serial device, and bytes cross in both directions intact.
TEST(Targets, SerialDeviceCarriesFrames)
{
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    ASSERT_GE(master, 0);
    ASSERT_EQ(grantpt(master), 0);
    ASSERT_EQ(unlockpt(master), 0);
    std::string device = ptsname(master);
    std::unique_ptr<Transport> link = open_transport(parse_target("ser:device=" + device), 500);
    EXPECT_EQ(link->name(), "ser:device=" + device);

    const std::vector<uint8_t> frame{ 0x02, 0x00, 0x01, 0x00, 0x0c, 0x90, 0x05, 0x00 };
    ASSERT_EQ(write(master, frame.data(), frame.size()), ssize_t(frame.size()));
    std::vector<uint8_t> received;
    for (int attempt = 0; attempt < 100 && received.size() < frame.size(); attempt++) {
        pollfd waiting{ link->fd(), POLLIN, 0 };
        poll(&waiting, 1, 10);
        uint8_t buffer[64];
        size_t count = link->read(buffer, sizeof buffer);
        received.insert(received.end(), buffer, buffer + count);
    }
    EXPECT_EQ(received, frame); // raw mode: no byte translated or swallowed

    const std::vector<uint8_t> command{ 0x02, 0x00, 0x00, 0x00, 0x11, 0xa0, 0x05, 0x00 };
    link->write(command.data(), command.size(), 500);
    std::vector<uint8_t> sent(command.size());
    size_t total = 0;
    for (int attempt = 0; attempt < 100 && total < sent.size(); attempt++) {
        pollfd waiting{ master, POLLIN, 0 };
        if (poll(&waiting, 1, 10) > 0) {
            ssize_t count = read(master, sent.data() + total, sent.size() - total);
            if (count > 0)
                total += size_t(count);
        }
    }
    EXPECT_EQ(sent, command);
    link.reset();
    close(master);
}

// Text from the network as a terminal shows it: whole lines keep their line
// ends and tabs, names inside a line escape them and the backslash too;
// control characters (C0, DEL, C1 in UTF-8), the marks that reorder a line
// and bytes that are not UTF-8 (an overlong form, a lone continuation) are
// escapes; other characters pass.
struct Shown {
    const char *text;
    const char *line;  // terminal_safe
    const char *named; // escaped_name
};

const Shown shown_texts[] = {
    { "e-puck 1", "e-puck 1", "e-puck 1" },
    { "\x1b[2J\a", "\\x1b[2J\\x07", "\\x1b[2J\\x07" },
    { "a\tb\nc\\", "a\tb\nc\\", "a\\tb\\nc\\\\" },
    { "\r\x7f", "\\x0d\\x7f", "\\x0d\\x7f" },
    { "\xc2\x9b"
      "31m",
      "\\u009b31m",
      "\\u009b31m" },
    { "abc\xe2\x80\xae"
      "fed",
      "abc\\u202efed",
      "abc\\u202efed" },
    { "\xc3\xa9t\xc3\xa9 \xe2\x82\xac",
      "\xc3\xa9t\xc3\xa9 \xe2\x82\xac",
      "\xc3\xa9t\xc3\xa9 \xe2\x82\xac" },
    { "\xff\xc0\xaf\x80", "\\xff\\xc0\\xaf\\x80", "\\xff\\xc0\\xaf\\x80" },
};

TEST(TerminalText, ControlsAndInvalidBytesAreEscaped)
{
    for (const Shown &shown : shown_texts) {
        SCOPED_TRACE(shown.line);
        EXPECT_EQ(terminal_safe(shown.text), shown.line);
        EXPECT_EQ(escaped_name(shown.text), shown.named);
    }
}

// The filter in front of a stream: what is written through it reaches the
// stream's buffer escaped, a line at a time and at each flush; a program's
// own control sequence goes around it.
TEST(TerminalText, AFilterEscapesWhatAStreamWrites)
{
    std::ostringstream output;
    {
        TerminalFilter filter(output);
        output << "node \x1b]0;title\x07";
        EXPECT_EQ(output.str(), "") << "written before its line ended";
        output << " ok\n";
        TerminalFilter::write_control(output, "\x1b[2J");
        output << "left \x1b[K" << std::flush;
    }
    EXPECT_EQ(output.str(), "node \\x1b]0;title\\x07 ok\n\x1b[2Jleft \\x1b[K");
}
