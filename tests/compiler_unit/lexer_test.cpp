// The lexer against language.md §2 and the position rules of §11.1.

#include <gtest/gtest.h>

#include "unit_support.hpp"

#include "tools/compiler/diagnostics.hpp"
#include "tools/compiler/lexer.hpp"

namespace aseba
{
namespace
{

std::vector<TokenType> types_of(const std::string &source)
{
    std::vector<TokenType> types;
    for (const auto &token : tokenize(source))
        types.push_back(token.type);
    return types;
}

// The position of the first token of `type`.
SourcePosition position_of(const std::string &source, TokenType type)
{
    for (const auto &token : tokenize(source))
        if (token.type == type)
            return token.position;
    ADD_FAILURE() << "no such token";
    return {};
}

CompileError lexing_error(const std::string &source)
{
    try {
        tokenize(source);
    } catch (const CompileFailure &failure) {
        return failure.error;
    }
    ADD_FAILURE() << "no error for " << source;
    return {};
}

TEST(Lexer, LongestMatchOperators)
{
    using enum TokenType;
    EXPECT_EQ(
      types_of("<<= >>= <= >= << >> == != ++ -- += -= *= /= %= |= ^= &= = < >"),
      (std::vector<TokenType>{ SHIFT_LEFT_EQUAL, SHIFT_RIGHT_EQUAL, SMALLER_EQUAL, BIGGER_EQUAL,
                               SHIFT_LEFT,       SHIFT_RIGHT,       EQUAL,         NOT_EQUAL,
                               PLUS_PLUS,        MINUS_MINUS,       PLUS_EQUAL,    MINUS_EQUAL,
                               MULT_EQUAL,       DIV_EQUAL,         MOD_EQUAL,     BIT_OR_EQUAL,
                               BIT_XOR_EQUAL,    BIT_AND_EQUAL,     ASSIGN,        SMALLER,
                               BIGGER,           END_OF_STREAM }));
}

TEST(Lexer, KeywordsAndDottedIdentifiers)
{
    std::vector<Token> tokens = tokenize("onevent prox.horizontal _x. x..y when1 é");
    ASSERT_EQ(tokens.size(), 7u);
    EXPECT_EQ(tokens[0].type, TokenType::ONEVENT);
    for (size_t i = 1; i < 6; ++i)
        EXPECT_EQ(tokens[i].type, TokenType::IDENTIFIER) << i;
    EXPECT_EQ(tokens[1].text, "prox.horizontal");
    EXPECT_EQ(tokens[3].text, "x..y");
    EXPECT_EQ(tokens[5].text, "é");
}

TEST(Lexer, NumberValues)
{
    std::vector<Token> tokens = tokenize("0xFFFF 0x8000 0x 0b 0b101 007 32768 0x7fff");
    std::vector<int32_t> values;
    for (const auto &token : tokens)
        if (token.type == TokenType::INTEGER)
            values.push_back(token.value);
    // hex and binary above 32767 wrap negative; decimal 32768 waits for a minus
    EXPECT_EQ(values, (std::vector<int32_t>{ -1, -32768, 0, 0, 5, 7, 32768, 32767 }));
}

TEST(Lexer, NumberErrors)
{
    EXPECT_EQ(lexing_error("x = 0x1g").message, "Error in hexadecimal number");
    EXPECT_EQ(lexing_error("x = 0b12").message, "Error in binary number");
    EXPECT_EQ(lexing_error("x = 0X10").message, "Error in number, invalid base");
    EXPECT_EQ(lexing_error("x = 12ab").message, "Error in number");
    CompileError range = lexing_error("x = 0x10000");
    EXPECT_EQ(range.message, "Integer value 0x10000 (65536) out of [-32768;32767] range");
    EXPECT_EQ(range.position.column, 5u);
}

// The literal as written, never a value it was clipped to (issue: the
// message of a huge literal named 2^40).
TEST(Lexer, OutOfRangeLiteralsAreNamedAsWritten)
{
    EXPECT_EQ(unit::compile_for_dummy("var x\nx = 99999999999999\n").error.message,
              "Integer value 99999999999999 out of [-32768;32767] range");
    EXPECT_EQ(unit::compile_for_dummy("var x\nx = -40000\n").error.message,
              "Integer value -40000 out of [-32768;32767] range");
    EXPECT_EQ(unit::compile_for_dummy("var x\nx = 0b11111111111111111\n").error.message,
              "Integer value 0b11111111111111111 (131071) out of [-32768;32767] range");
    EXPECT_EQ(unit::compile_for_dummy("var x\nfor x in 0:-40000 step -1 do\nend\n").error.message,
              "Integer value -40000 out of [-32768;32767] range");
}

// Text that is not UTF-8 is refused where it starts, not taken as Latin-1.
TEST(Lexer, InvalidUtf8IsRefusedWithItsPosition)
{
    for (const char *bad : { "\xff", "\xc3", "\xc0\x80", "\xed\xa0\x80", "\xf4\x90\x80\x80" }) {
        CompileResult result =
          unit::compile_for_dummy(std::string("var x\nx = 1 # \xc3\xa9 ") + bad + "\n");
        ASSERT_FALSE(result.ok);
        EXPECT_EQ(result.error.position.line, 2u);
        EXPECT_EQ(result.error.position.column, 11u) << "after the 10 characters before it";
        EXPECT_EQ(result.error.message.rfind("Invalid UTF-8 byte 0x", 0), 0u)
          << result.error.message;
    }
    EXPECT_TRUE(unit::compile_for_dummy("var \xc3\xa9t\xc3\xa9 = 1\n").ok) << "valid UTF-8 letters";
}

TEST(Lexer, BadCharacters)
{
    EXPECT_EQ(lexing_error("x = 1 ! 2").message, "Syntax error");
    CompileError at = lexing_error("var x\nx = @");
    EXPECT_EQ(at.message,
              "Identifiers must begin with _ or an alphanumeric character, found "
              "unicode character 0x40 instead");
    EXPECT_EQ(at.position.line, 2u);
    EXPECT_EQ(at.position.column, 5u);
}

TEST(Lexer, BlockComments)
{
    // "#**#" is a whole comment; the first "*#" closes a block comment
    EXPECT_EQ(types_of("a #**# b"),
              (std::vector<TokenType>{
                TokenType::IDENTIFIER, TokenType::IDENTIFIER, TokenType::END_OF_STREAM }));
    EXPECT_EQ(types_of("#* a #* b *# y *#").size(), 3u); // y, *, then a line comment
    CompileError open = lexing_error("var x\n  #*# never closed");
    EXPECT_EQ(open.message, "Unbalanced comment block");
    EXPECT_EQ(open.position.line, 2u);
    EXPECT_EQ(open.position.column, 3u);
}

TEST(Lexer, ReferencePositionQuirks)
{
    // the line after a `#` comment starts one column late (§11.1)
    EXPECT_EQ(position_of("var b # c\nb = b > 1", TokenType::BIGGER).column, 8u);
    EXPECT_EQ(position_of("var b # c\r\nb = b > 1", TokenType::BIGGER).column, 7u);
    // a tab inside a comment counts four columns
    EXPECT_EQ(position_of("var b #* \t *# b = b > 1", TokenType::BIGGER).column, 24u);
    // a tab outside comments and a non-ASCII letter count one
    EXPECT_EQ(position_of("\té > 1", TokenType::BIGGER).column, 4u);
    // letters of two, three and four bytes count one column, and so does any
    // character in a comment
    EXPECT_EQ(position_of("é中𝒜 > 1", TokenType::BIGGER).column, 5u);
    EXPECT_EQ(position_of("#* é€😀 *# b > 1", TokenType::BIGGER).column, 13u);
}

TEST(Lexer, EndOfStreamPosition)
{
    SourcePosition after_line_feed = tokenize("var x\nx = 1 *\n").back().position;
    EXPECT_EQ(after_line_feed.line, 3u);
    EXPECT_EQ(after_line_feed.column, 0u);
    SourcePosition without = tokenize("var x\nx = 1 *").back().position;
    EXPECT_EQ(without.line, 2u);
    EXPECT_EQ(without.column, 7u);
}

} // namespace
} // namespace aseba
