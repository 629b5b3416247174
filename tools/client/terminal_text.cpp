// Text from the network, escaped for terminals (see terminal_text.hpp).

#include "terminal_text.hpp"

#include <cstdio>

namespace aseba::client
{

namespace
{

void append_escape(std::string &out, const char *format, unsigned value)
{
    char escape[12];
    std::snprintf(escape, sizeof escape, format, value);
    out += escape;
}

// Code points that act on a terminal or on the order of a line.
bool is_control(char32_t code)
{
    return code < 0x20 || code == 0x7F || (code >= 0x80 && code < 0xA0) || code == 0x061C ||
           code == 0x200E || code == 0x200F || code == 0x2028 || code == 0x2029 ||
           (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069);
}

// The length of the UTF-8 sequence at `text[at]` and its code point; 0 when
// it is not a valid, shortest one.
size_t decode(std::string_view text, size_t at, char32_t &code)
{
    auto byte = static_cast<unsigned char>(text[at]);
    size_t length = byte < 0x80           ? 1
                    : (byte >> 5) == 0x6  ? 2
                    : (byte >> 4) == 0xE  ? 3
                    : (byte >> 3) == 0x1E ? 4
                                          : 0;
    static const char32_t shortest[] = { 0, 0, 0x80, 0x800, 0x10000 };
    if (length == 0 || at + length > text.size())
        return 0;
    code = length == 1 ? byte : byte & (0x7F >> length);
    for (size_t k = 1; k < length; k++) {
        auto continuation = static_cast<unsigned char>(text[at + k]);
        if ((continuation & 0xC0) != 0x80)
            return 0;
        code = (code << 6) | (continuation & 0x3F);
    }
    bool surrogate = code >= 0xD800 && code <= 0xDFFF;
    return code < shortest[length] || surrogate || code > 0x10FFFF ? 0 : length;
}

std::string escaped(std::string_view text, bool inside_a_line)
{
    std::string out;
    out.reserve(text.size());
    size_t at = 0;
    while (at < text.size()) {
        char32_t code = 0;
        size_t length = decode(text, at, code);
        if (length == 0) {
            append_escape(out, "\\x%02x", static_cast<unsigned char>(text[at]));
            at++;
            continue;
        }
        bool layout = code == '\n' || code == '\t';
        if (inside_a_line && (layout || code == '\\'))
            out += code == '\n' ? "\\n" : code == '\t' ? "\\t" : "\\\\";
        else if (is_control(code) && !layout)
            append_escape(out, code < 0x80 ? "\\x%02x" : "\\u%04x", unsigned(code));
        else
            out.append(text.substr(at, length));
        at += length;
    }
    return out;
}

} // namespace

std::string terminal_safe(std::string_view text)
{
    return escaped(text, false);
}

std::string escaped_name(std::string_view text)
{
    return escaped(text, true);
}

TerminalFilter::TerminalFilter(std::ostream &stream)
  : stream_(stream)
  , original_(stream.rdbuf(this))
{
}

TerminalFilter::~TerminalFilter()
{
    drain(true);
    stream_.rdbuf(original_);
}

void TerminalFilter::write_control(std::ostream &stream, std::string_view control)
{
    stream.flush();
    auto *filter = dynamic_cast<TerminalFilter *>(stream.rdbuf());
    std::streambuf *target = filter ? filter->original_ : stream.rdbuf();
    if (target->sputn(control.data(), std::streamsize(control.size())) !=
          std::streamsize(control.size()) ||
        target->pubsync() != 0)
        stream.setstate(std::ios::badbit);
}

TerminalFilter::int_type TerminalFilter::overflow(int_type character)
{
    if (traits_type::eq_int_type(character, traits_type::eof()))
        return traits_type::not_eof(character);
    pending_ += traits_type::to_char_type(character);
    if (character == '\n' && !drain(false))
        return traits_type::eof();
    return character;
}

std::streamsize TerminalFilter::xsputn(const char *text, std::streamsize count)
{
    pending_.append(text, size_t(count));
    return drain(false) ? count : 0;
}

int TerminalFilter::sync()
{
    return drain(true) && original_->pubsync() == 0 ? 0 : -1;
}

bool TerminalFilter::drain(bool all)
{
    size_t end = pending_.size();
    if (!all) {
        size_t last_line_end = pending_.rfind('\n');
        if (last_line_end == std::string::npos)
            return true;
        end = last_line_end + 1;
    }
    if (end == 0)
        return true;
    std::string safe = terminal_safe(std::string_view(pending_).substr(0, end));
    pending_.erase(0, end);
    return original_->sputn(safe.data(), std::streamsize(safe.size())) ==
           std::streamsize(safe.size());
}

} // namespace aseba::client
