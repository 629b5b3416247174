// The lexer of language.md §2. Positions reproduce the reference's counting
// (§11.1): tabs in comments count 4 columns, the line after a `#` comment
// starts one column late, and the end of stream sits at column 0 after a
// final line break.

#include "lexer.hpp"

#include <algorithm>
#include <cstdio>
#include <locale>

#include "diagnostics.hpp"

namespace aseba
{

namespace
{

constexpr unsigned TAB_WIDTH_IN_COMMENTS = 4;
constexpr int64_t LITERAL_LIMIT = 65536;         // literals must be below this in any base
constexpr int64_t INT16_LIMIT = 32768;           // hex and binary literals above wrap negative
constexpr int64_t SATURATED_LITERAL = 1LL << 40; // keeps huge spellings from overflowing
constexpr size_t BYTES_PER_TOKEN_GUESS = 4;      // to reserve the tokens: regrowing cost more

struct Keyword {
    std::string_view spelling;
    TokenType type;
};

constexpr Keyword keywords[] = {
    { "when", TokenType::WHEN },
    { "emit", TokenType::EMIT },
    { "_emit", TokenType::HIDDEN_EMIT },
    { "for", TokenType::FOR },
    { "in", TokenType::IN },
    { "step", TokenType::STEP },
    { "while", TokenType::WHILE },
    { "do", TokenType::DO },
    { "if", TokenType::IF },
    { "then", TokenType::THEN },
    { "else", TokenType::ELSE },
    { "elseif", TokenType::ELSEIF },
    { "end", TokenType::END },
    { "var", TokenType::VAR },
    { "const", TokenType::CONST },
    { "call", TokenType::CALL },
    { "sub", TokenType::SUB },
    { "callsub", TokenType::CALLSUB },
    { "onevent", TokenType::ONEVENT },
    { "abs", TokenType::ABS },
    { "return", TokenType::RETURN },
    { "or", TokenType::OR },
    { "and", TokenType::AND },
    { "not", TokenType::NOT },
};

// The type of the word `word`: a keyword's or IDENTIFIER. A plain scan,
// comparing lengths and first letters before the whole spellings, is
// cheaper than a map's string comparisons, and every name goes through it.
TokenType word_type(std::string_view word)
{
    for (const Keyword &keyword : keywords)
        if (keyword.spelling.size() == word.size() && keyword.spelling[0] == word[0] &&
            keyword.spelling == word)
            return keyword.type;
    return TokenType::IDENTIFIER;
}

// Non-ASCII letters and digits as the reference sees them (its en_US.UTF-8
// locale); from U+00C0 on, all letters if that locale is not installed.
bool is_non_ascii_alphanumeric(char32_t c)
{
    static const std::ctype<wchar_t> *classifier = []() -> const std::ctype<wchar_t> * {
        try {
            static const std::locale locale("en_US.UTF-8");
            return &std::use_facet<std::ctype<wchar_t>>(locale);
        } catch (const std::exception &) {
            return nullptr;
        }
    }();
    if (classifier == nullptr)
        return c >= 0xC0; // without the locale, take non-ASCII text as letters
    return classifier->is(std::ctype_base::alnum, static_cast<wchar_t>(c));
}

// Letters and digits as the reference sees them. The ASCII test stays apart
// from the locale's, so that it is inlined where names are read.
bool is_alphanumeric(char32_t c)
{
    if (c < 0x80)
        return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    return is_non_ascii_alphanumeric(c);
}

bool is_word_start(char32_t c)
{
    return c == '_' || is_alphanumeric(c);
}

bool is_word_continuation(char32_t c)
{
    return c == '_' || c == '.' || is_alphanumeric(c);
}

int digit_value(char32_t c)
{
    if (c >= '0' && c <= '9')
        return static_cast<int>(c - '0');
    if (c >= 'a' && c <= 'f')
        return static_cast<int>(c - 'a' + 10);
    if (c >= 'A' && c <= 'F')
        return static_cast<int>(c - 'A' + 10);
    return -1;
}

// The byte offset of the first byte of `text` that is not valid UTF-8
// (overlong forms, surrogates and code points above U+10FFFF included), or
// text.size() if all is valid.
size_t first_invalid_utf8(std::string_view text)
{
    size_t i = 0;
    while (i < text.size()) {
        auto byte = static_cast<unsigned char>(text[i]);
        if (byte < 0x80) {
            ++i;
            continue;
        }
        unsigned length = (byte >> 5) == 0x6    ? 2
                          : (byte >> 4) == 0xE  ? 3
                          : (byte >> 3) == 0x1E ? 4
                                                : 0;
        if (length == 0 || i + length > text.size())
            return i;
        char32_t code = byte & (0x7F >> length);
        for (unsigned k = 1; k < length; ++k) {
            auto continuation = static_cast<unsigned char>(text[i + k]);
            if ((continuation & 0xC0) != 0x80)
                return i;
            code = (code << 6) | (continuation & 0x3F);
        }
        static const char32_t smallest[] = { 0, 0, 0x80, 0x800, 0x10000 };
        if (code < smallest[length] || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF)
            return i;
        i += length;
    }
    return i;
}

// The length of the UTF-8 sequence that starts with `byte`, in valid text.
unsigned sequence_length(unsigned char byte)
{
    return byte < 0x80 ? 1 : (byte >> 5) == 0x6 ? 2 : (byte >> 4) == 0xE ? 3 : 4;
}

// Refuses text that is not UTF-8, at the line and column of the bad byte.
void check_utf8(std::string_view text)
{
    size_t bad = first_invalid_utf8(text);
    if (bad == text.size())
        return;
    size_t line_start = text.rfind('\n', bad == 0 ? 0 : bad - 1);
    line_start = line_start == std::string_view::npos || bad == 0 ? 0 : line_start + 1;
    SourcePosition where;
    where.line = 1 + static_cast<unsigned>(std::count(text.begin(), text.begin() + bad, '\n'));
    where.column =
      1 + static_cast<unsigned>(decode_utf8(text.substr(line_start, bad - line_start)).size());
    char hex[8];
    snprintf(hex, sizeof hex, "%02x", static_cast<unsigned char>(text[bad]));
    fail(where,
         std::string("Invalid UTF-8 byte 0x") + hex + ": the program must be saved as UTF-8 text");
}

// A literal out of range, named as it is written (with its minus sign), and
// for a hexadecimal or binary spelling the `value` it stands for.
std::string out_of_range_message(std::string_view spelling, int64_t value, bool negated)
{
    std::string written = (negated ? "-" : "");
    written += spelling;
    bool decimal = spelling.size() < 2 || (spelling[1] != 'x' && spelling[1] != 'b');
    if (!decimal && value < SATURATED_LITERAL)
        written += " (" + std::to_string(value) + ")";
    return "Integer value " + written + " out of [-32768;32767] range";
}

// Reads the UTF-8 text in place: most of it is ASCII, and decoding it
// whole, then encoding each name back, cost more than the rest of the lexer.
// Columns count characters, not bytes.
class Lexer
{
  public:
    explicit Lexer(std::string_view source)
      : text(source)
    {
        check_utf8(text);
    }

    std::vector<Token> run()
    {
        std::vector<Token> tokens;
        tokens.reserve(text.size() / BYTES_PER_TOKEN_GUESS);
        while (index < text.size()) {
            char c = text[index];
            if (c == ' ' || c == '\t') {
                advance();
            } else if (c == '\n') {
                ++index;
                ++line;
                column = 0;
            } else if (c == '\r') {
                ++index;
                column = 0;
            } else if (c == '#') {
                skip_comment();
            } else {
                tokens.push_back(read_token());
            }
        }
        Token end;
        end.type = TokenType::END_OF_STREAM;
        end.position = { line, column + (ended_in_line_comment ? 1u : 0u) };
        tokens.push_back(end);
        return tokens;
    }

  private:
    std::string_view text; // valid UTF-8
    size_t index = 0;      // in bytes, at the start of a character
    unsigned line = 1;
    unsigned column = 0; // columns used so far on this line
    bool ended_in_line_comment = false;

    // The character at `index`, or 0 at the end.
    char32_t current() const
    {
        if (index >= text.size())
            return 0;
        auto first = static_cast<unsigned char>(text[index]);
        unsigned length = sequence_length(first);
        if (length == 1)
            return first;
        char32_t code = first & (0x7F >> length);
        for (unsigned k = 1; k < length; ++k)
            code = (code << 6) | (static_cast<unsigned char>(text[index + k]) & 0x3F);
        return code;
    }

    // The byte `offset` bytes after `index`, or 0 at the end. Compared with
    // ASCII characters only, it tells the character there: bytes of longer
    // UTF-8 sequences are never ASCII.
    char peek(size_t offset = 0) const
    {
        return index + offset < text.size() ? text[index + offset] : 0;
    }

    // Moves past the character at `index`.
    void advance()
    {
        index += sequence_length(static_cast<unsigned char>(text[index]));
        ++column;
    }

    // Skips a character inside a comment, counting positions as the
    // reference does.
    void skip_comment_character()
    {
        char c = text[index];
        if (c == '\n') {
            ++index;
            ++line;
            column = 0;
        } else if (c == '\r') {
            ++index;
            column = 0;
        } else if (c == '\t') {
            ++index;
            column += TAB_WIDTH_IN_COMMENTS;
        } else {
            advance();
        }
    }

    void skip_comment()
    {
        SourcePosition start{ line, column + 1 };
        if (peek(1) == '*') {
            advance();
            advance();
            while (true) {
                if (index >= text.size())
                    fail(start, "Unbalanced comment block");
                if (peek() == '*' && peek(1) == '#') {
                    advance();
                    advance();
                    return;
                }
                skip_comment_character();
            }
        }
        advance();
        while (index < text.size() && peek() != '\n' && peek() != '\r')
            skip_comment_character();
        if (index >= text.size()) {
            ended_in_line_comment = true;
            return;
        }
        // The reference starts the following line one column late.
        if (peek() == '\n')
            ++line;
        ++index;
        column = 1;
    }

    Token read_token()
    {
        Token token;
        token.position = { line, column + 1 };
        char32_t c = current();
        if (is_word_start(c)) {
            size_t start = index;
            while (index < text.size() && is_word_continuation(current()))
                advance();
            std::string_view word = text.substr(start, index - start);
            token.text = word;
            if (c >= '0' && c <= '9') {
                token.type = TokenType::INTEGER;
                token.value = number_value(word, token.position);
            } else {
                token.type = word_type(word);
            }
            return token;
        }
        token.type = read_symbol(token.position);
        if (token.type == TokenType::SHIFT_LEFT || token.type == TokenType::SHIFT_RIGHT ||
            token.type == TokenType::SHIFT_LEFT_EQUAL || token.type == TokenType::SHIFT_RIGHT_EQUAL)
            ++token.position.column; // the reference places shifts on their second character
        return token;
    }

    // The value of a number word; hex and binary above 32767 wrap negative.
    static int32_t number_value(std::string_view word, SourcePosition position)
    {
        int base = 10;
        size_t first_digit = 0;
        const char *base_error = "Error in number";
        if (word.size() > 1 && word[0] == '0' && word[1] == 'x') {
            base = 16;
            first_digit = 2;
            base_error = "Error in hexadecimal number";
        } else if (word.size() > 1 && word[0] == '0' && word[1] == 'b') {
            base = 2;
            first_digit = 2;
            base_error = "Error in binary number";
        } else if (word.size() > 1 && word[0] == '0' && !(word[1] >= '0' && word[1] <= '9')) {
            fail(position, "Error in number, invalid base");
        }
        int64_t value = 0;
        for (size_t i = first_digit; i < word.size(); ++i) {
            int digit = digit_value(static_cast<unsigned char>(word[i]));
            if (digit < 0 || digit >= base)
                fail(position, base_error);
            value = value * base + digit;
            if (value > SATURATED_LITERAL)
                value = SATURATED_LITERAL;
        }
        if (value >= LITERAL_LIMIT)
            fail(position, out_of_range_message(word, value, false));
        if (base != 10 && value >= INT16_LIMIT)
            value -= LITERAL_LIMIT;
        return static_cast<int32_t>(value);
    }

    // Reads punctuation and operators, longest match first.
    TokenType read_symbol(SourcePosition position)
    {
        char32_t c = current();
        char next = peek(1);
        char after = peek(2);
        auto take = [this](unsigned count, TokenType type) {
            for (unsigned i = 0; i < count; ++i)
                advance();
            return type;
        };
        switch (c) {
        case '(': return take(1, TokenType::PAREN_OPEN);
        case ')': return take(1, TokenType::PAREN_CLOSE);
        case '[': return take(1, TokenType::BRACKET_OPEN);
        case ']': return take(1, TokenType::BRACKET_CLOSE);
        case ':': return take(1, TokenType::COLON);
        case ',': return take(1, TokenType::COMMA);
        case '~': return take(1, TokenType::BIT_NOT);
        case '=': return next == '=' ? take(2, TokenType::EQUAL) : take(1, TokenType::ASSIGN);
        case '!':
            if (next == '=')
                return take(2, TokenType::NOT_EQUAL);
            fail(position, "Syntax error");
        case '<':
            if (next == '<')
                return after == '=' ? take(3, TokenType::SHIFT_LEFT_EQUAL)
                                    : take(2, TokenType::SHIFT_LEFT);
            return next == '=' ? take(2, TokenType::SMALLER_EQUAL) : take(1, TokenType::SMALLER);
        case '>':
            if (next == '>')
                return after == '=' ? take(3, TokenType::SHIFT_RIGHT_EQUAL)
                                    : take(2, TokenType::SHIFT_RIGHT);
            return next == '=' ? take(2, TokenType::BIGGER_EQUAL) : take(1, TokenType::BIGGER);
        case '+':
            if (next == '+')
                return take(2, TokenType::PLUS_PLUS);
            return next == '=' ? take(2, TokenType::PLUS_EQUAL) : take(1, TokenType::PLUS);
        case '-':
            if (next == '-')
                return take(2, TokenType::MINUS_MINUS);
            return next == '=' ? take(2, TokenType::MINUS_EQUAL) : take(1, TokenType::MINUS);
        case '*': return next == '=' ? take(2, TokenType::MULT_EQUAL) : take(1, TokenType::MULT);
        case '/': return next == '=' ? take(2, TokenType::DIV_EQUAL) : take(1, TokenType::DIV);
        case '%': return next == '=' ? take(2, TokenType::MOD_EQUAL) : take(1, TokenType::MOD);
        case '|':
            return next == '=' ? take(2, TokenType::BIT_OR_EQUAL) : take(1, TokenType::BIT_OR);
        case '^':
            return next == '=' ? take(2, TokenType::BIT_XOR_EQUAL) : take(1, TokenType::BIT_XOR);
        case '&':
            return next == '=' ? take(2, TokenType::BIT_AND_EQUAL) : take(1, TokenType::BIT_AND);
        default: break;
        }
        char hex[16];
        snprintf(hex, sizeof hex, "%x", static_cast<unsigned>(c));
        fail(position,
             std::string("Identifiers must begin with _ or an alphanumeric character, "
                         "found unicode character 0x") +
               hex + " instead");
    }
};

} // namespace

std::string literal_range_message(const Token &literal, bool negated)
{
    int64_t value = literal.value;
    return out_of_range_message(literal.text, negated ? -value : value, negated);
}

const char *token_type_name(TokenType type)
{
    switch (type) {
#define ASEBA_TOKEN_NAME(identifier, name)                                                         \
    case TokenType::identifier: return name;
        ASEBA_TOKEN_LIST(ASEBA_TOKEN_NAME)
#undef ASEBA_TOKEN_NAME
    }
    return "?";
}

std::vector<Token> tokenize(std::string_view source)
{
    return Lexer(source).run();
}

std::u32string decode_utf8(std::string_view text)
{
    std::u32string result;
    result.reserve(text.size());
    size_t i = 0;
    while (i < text.size()) {
        auto byte = static_cast<unsigned char>(text[i]);
        unsigned length = byte < 0x80           ? 1
                          : (byte >> 5) == 0x6  ? 2
                          : (byte >> 4) == 0xE  ? 3
                          : (byte >> 3) == 0x1E ? 4
                                                : 0;
        char32_t code = length == 1   ? byte
                        : length == 2 ? (byte & 0x1F)
                        : length == 3 ? (byte & 0x0F)
                                      : (byte & 0x07);
        bool valid = length != 0 && i + length <= text.size();
        for (unsigned k = 1; valid && k < length; ++k) {
            auto continuation = static_cast<unsigned char>(text[i + k]);
            valid = (continuation & 0xC0) == 0x80;
            code = (code << 6) | (continuation & 0x3F);
        }
        if (!valid) {
            result.push_back(byte); // Latin-1 fallback keeps every input readable
            ++i;
        } else {
            result.push_back(code);
            i += length;
        }
    }
    return result;
}

std::string encode_utf8(std::u32string_view text)
{
    std::string result;
    for (char32_t c : text) {
        if (c < 0x80) {
            result.push_back(static_cast<char>(c));
        } else if (c < 0x800) {
            result.push_back(static_cast<char>(0xC0 | (c >> 6)));
            result.push_back(static_cast<char>(0x80 | (c & 0x3F)));
        } else if (c < 0x10000) {
            result.push_back(static_cast<char>(0xE0 | (c >> 12)));
            result.push_back(static_cast<char>(0x80 | ((c >> 6) & 0x3F)));
            result.push_back(static_cast<char>(0x80 | (c & 0x3F)));
        } else {
            result.push_back(static_cast<char>(0xF0 | (c >> 18)));
            result.push_back(static_cast<char>(0x80 | ((c >> 12) & 0x3F)));
            result.push_back(static_cast<char>(0x80 | ((c >> 6) & 0x3F)));
            result.push_back(static_cast<char>(0x80 | (c & 0x3F)));
        }
    }
    return result;
}

} // namespace aseba
