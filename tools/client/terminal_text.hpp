// Text from the network on a terminal. A network member names its nodes,
// variables, events and natives, and writes the messages of its errors: any
// control character in them would act on the terminal of whoever prints
// them (clear the screen, move the cursor, set the window's title, fake
// other output). Such text is shown escaped, never raw.

#pragma once

#include <ostream>
#include <streambuf>
#include <string>
#include <string_view>

namespace aseba::client
{

// `text` as a terminal may show it: control characters (C0 and DEL, C1 as
// UTF-8), the marks that reorder a line (bidirectional controls, line and
// paragraph separators) and bytes that are not UTF-8 are written as \x1b,
// \u202e or \xff, the rest unchanged. Line ends and tabs are kept: this is
// for whole lines of output.
std::string terminal_safe(std::string_view text);

// The same for a name shown inside a line: line ends, tabs and backslashes
// are escaped too (\n, \t, \\), so that it stays on its line and its
// escapes read back unambiguously.
std::string escaped_name(std::string_view text);

// Everything a program writes through `stream` (std::cout, std::cerr),
// passed through terminal_safe() a line at a time (or what a flush ends)
// on its way to the stream's buffer; the stream gets its buffer back when
// the filter goes. A program's own control sequences go around it with
// write_control.
class TerminalFilter : public std::streambuf
{
  public:
    explicit TerminalFilter(std::ostream &stream);
    ~TerminalFilter() override;
    TerminalFilter(const TerminalFilter &) = delete;
    TerminalFilter &operator=(const TerminalFilter &) = delete;

    // Writes `control` (clearing the screen, say) to `stream` as it is,
    // after what waits, whether a filter is in front of it or not.
    static void write_control(std::ostream &stream, std::string_view control);

  protected:
    int_type overflow(int_type character) override;
    std::streamsize xsputn(const char *text, std::streamsize count) override;
    int sync() override;

  private:
    // Writes what waits up to its last line end (all of it when `all`);
    // false when the stream's buffer did not take it.
    bool drain(bool all);

    std::ostream &stream_;
    std::streambuf *original_;
    std::string pending_;
};

} // namespace aseba::client
