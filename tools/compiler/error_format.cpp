// Error rendering shared by the command-line tools.

#include "error_format.hpp"

#include <algorithm>

#include "lexer.hpp"

namespace aseba
{

namespace
{

constexpr size_t SHOWN_LINE_LIMIT = 120; // longer source lines are cut around the error
constexpr size_t SHOWN_CONTEXT = 50;     // characters kept on each side of the column
constexpr char32_t REPLACEMENT_CHARACTER = 0xFFFD;

// Control characters would act on the terminal: each shows as one mark,
// so that columns still line up.
std::u32string printable(std::u32string text)
{
    for (char32_t &c : text)
        if ((c < 0x20 && c != '\t') || (c >= 0x7F && c < 0xA0))
            c = REPLACEMENT_CHARACTER;
    return text;
}

std::string printable(std::string_view text)
{
    return encode_utf8(printable(decode_utf8(text)));
}

} // namespace

std::string format_error(std::string_view file_name,
                         std::string_view source,
                         const CompileError &error,
                         unsigned line_offset,
                         unsigned column_offset)
{
    std::string out = printable(file_name);
    std::string message = printable(error.message);
    if (!error.has_position)
        return out + ": error: " + message + "\n";
    unsigned line = error.position.line;
    unsigned column = error.position.column;
    unsigned shown_column = column + (line == 1 ? column_offset : 0);
    out += ":" + std::to_string(line + line_offset) + ":" + std::to_string(shown_column) +
           ": error: " + message + "\n";

    // find the source line (LF ends lines, as the compiler counts them)
    size_t start = 0;
    for (unsigned l = 1; l < line && start != std::string_view::npos; ++l) {
        start = source.find('\n', start);
        if (start != std::string_view::npos)
            ++start;
    }
    if (start == std::string_view::npos || start >= source.size())
        return out + "  (at the end of the text)\n";
    size_t end = source.find('\n', start);
    std::string_view text = source.substr(start, end == std::string_view::npos ? end : end - start);
    if (!text.empty() && text.back() == '\r')
        text.remove_suffix(1);
    std::u32string characters = printable(decode_utf8(text));
    // very long lines are shown around the column only
    size_t first = 0;
    size_t last = characters.size();
    if (characters.size() > SHOWN_LINE_LIMIT) {
        size_t at = column > 0 ? column - 1 : 0;
        first = at > SHOWN_CONTEXT ? at - SHOWN_CONTEXT : 0;
        last = std::min(characters.size(), at + SHOWN_CONTEXT);
    }
    std::string prefix = first > 0 ? "..." : "";
    out += "  " + prefix + encode_utf8(characters.substr(first, last - first)) +
           (last < characters.size() ? "..." : "") + "\n  " + std::string(prefix.size(), ' ');
    // keep tabs so that the caret lines up under the same characters
    for (size_t i = first + 1; i < column && i - 1 < characters.size(); ++i)
        out += characters[i - 1] == '\t' ? '\t' : ' ';
    out += "^\n";
    return out;
}

} // namespace aseba
