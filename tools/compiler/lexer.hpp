// Turns Aseba source text into tokens (language.md §2), with the positions
// the reference compiler reports, quirks included (§11.1).

#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "compiler.hpp"

namespace aseba
{

// TOKEN(identifier, name used in messages)
#define ASEBA_TOKEN_LIST(X)                                                                        \
    X(END_OF_STREAM, "end of stream")                                                              \
    X(WHEN, "when keyword")                                                                        \
    X(EMIT, "emit keyword")                                                                        \
    X(HIDDEN_EMIT, "_emit keyword")                                                                \
    X(FOR, "for keyword")                                                                          \
    X(IN, "in keyword")                                                                            \
    X(STEP, "step keyword")                                                                        \
    X(WHILE, "while keyword")                                                                      \
    X(DO, "do keyword")                                                                            \
    X(IF, "if keyword")                                                                            \
    X(THEN, "then keyword")                                                                        \
    X(ELSE, "else keyword")                                                                        \
    X(ELSEIF, "elseif keyword")                                                                    \
    X(END, "end keyword")                                                                          \
    X(VAR, "var keyword")                                                                          \
    X(CONST, "const keyword")                                                                      \
    X(CALL, "call keyword")                                                                        \
    X(SUB, "sub keyword")                                                                          \
    X(CALLSUB, "callsub keyword")                                                                  \
    X(ONEVENT, "onevent keyword")                                                                  \
    X(ABS, "abs keyword")                                                                          \
    X(RETURN, "return keyword")                                                                    \
    X(IDENTIFIER, "identifier")                                                                    \
    X(INTEGER, "integer")                                                                          \
    X(PAREN_OPEN, "( (open parenthesis)")                                                          \
    X(PAREN_CLOSE, ") (close parenthesis)")                                                        \
    X(BRACKET_OPEN, "[ (open bracket)")                                                            \
    X(BRACKET_CLOSE, "] (close bracket)")                                                          \
    X(COLON, ": (colon)")                                                                          \
    X(COMMA, ", (comma)")                                                                          \
    X(ASSIGN, "= (assignation)")                                                                   \
    X(OR, "or")                                                                                    \
    X(AND, "and")                                                                                  \
    X(NOT, "not")                                                                                  \
    X(BIT_OR, "binary or")                                                                         \
    X(BIT_XOR, "binary xor")                                                                       \
    X(BIT_AND, "binary and")                                                                       \
    X(BIT_NOT, "binary not")                                                                       \
    X(BIT_OR_EQUAL, "binary or equal")                                                             \
    X(BIT_XOR_EQUAL, "binary xor equal")                                                           \
    X(BIT_AND_EQUAL, "binary and equal")                                                           \
    X(EQUAL, "== (equal to)")                                                                      \
    X(NOT_EQUAL, "!= (not equal to)")                                                              \
    X(BIGGER, "> (bigger than)")                                                                   \
    X(BIGGER_EQUAL, ">= (bigger or equal than)")                                                   \
    X(SMALLER, "< (smaller than)")                                                                 \
    X(SMALLER_EQUAL, "<= (smaller or equal than)")                                                 \
    X(SHIFT_LEFT, "<< (shift left)")                                                               \
    X(SHIFT_RIGHT, ">> (shift right)")                                                             \
    X(SHIFT_LEFT_EQUAL, "<<= (shift left equal)")                                                  \
    X(SHIFT_RIGHT_EQUAL, ">>= (shift right equal)")                                                \
    X(PLUS, "+ (plus)")                                                                            \
    X(MINUS, "- (minus)")                                                                          \
    X(PLUS_EQUAL, "+= (plus equal)")                                                               \
    X(MINUS_EQUAL, "-= (minus equal)")                                                             \
    X(PLUS_PLUS, "++ (plus plus)")                                                                 \
    X(MINUS_MINUS, "-- (minus minus)")                                                             \
    X(MULT, "* (time)")                                                                            \
    X(DIV, "/ (divide)")                                                                           \
    X(MOD, "modulo")                                                                               \
    X(MULT_EQUAL, "*= (time equal)")                                                               \
    X(DIV_EQUAL, "/= (divide equal)")                                                              \
    X(MOD_EQUAL, "modulo equal")

enum class TokenType {
#define ASEBA_TOKEN_ENUM(identifier, name) identifier,
    ASEBA_TOKEN_LIST(ASEBA_TOKEN_ENUM)
#undef ASEBA_TOKEN_ENUM
};

struct Token {
    TokenType type = TokenType::END_OF_STREAM;
    std::string text;  // identifier name (UTF-8) or number spelling
    int32_t value = 0; // numbers: value, hex/binary already made negative above 32767
    SourcePosition position;
};

// The name of a token type as the reference prints it in messages.
const char *token_type_name(TokenType type);

// The error for an integer literal out of the 16-bit range, naming it as
// written (`negated`: with a minus sign folded into it).
std::string literal_range_message(const Token &literal, bool negated);

// Splits `source` (UTF-8) into tokens ending with END_OF_STREAM; throws
// CompileFailure on a lexical error.
std::vector<Token> tokenize(std::string_view source);

// Decodes UTF-8 into code points; invalid bytes are taken as Latin-1 (the
// lexer refuses them first; this is for showing text).
std::u32string decode_utf8(std::string_view text);

// Encodes code points as UTF-8.
std::string encode_utf8(std::u32string_view text);

} // namespace aseba
