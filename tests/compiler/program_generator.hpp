// Random Aseba programs for differential testing against the reference
// compiler. Valid programs are built from the grammar of language.md §4 so
// that (nearly) every one compiles; mutated programs are valid ones with one
// random corruption, to compare how the compilers reject bad input. Everything
// depends only on the seed, so a failing program can be regenerated.

#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "tools/compiler/target.hpp"

namespace compiler_tests
{

struct GeneratedProgram {
    std::string source;
    std::string mutation; // empty for a valid program, else what was corrupted
};

class ProgramGenerator
{
  public:
    // Programs for `target` and `definitions`: they use the target's named
    // variables, local events and natives, and the project's events and
    // constants.
    ProgramGenerator(uint32_t seed,
                     const aseba::TargetDescription &target,
                     const aseba::CommonDefinitions &definitions);

    // A program that follows every rule of the language (a few may still be
    // rejected, e.g. when an expression folds to a division by zero).
    GeneratedProgram valid_program();

    // A valid program with one random corruption (which may keep it valid).
    GeneratedProgram mutated_program();

  private:
    using Tokens = std::vector<std::string>;

    struct Variable {
        std::string name;
        int size = 1;
    };
    struct NamedValue {
        std::string name;
        int value = 0;
    };
    static constexpr int primary = 100;

    // An integer expression: its tokens, size in words and, when it folds
    // to a constant, its value with the compiler's 32-bit arithmetic.
    struct Expression {
        Tokens tokens;
        int size = 1;
        std::optional<int32_t> value;
        // How tightly the expression binds (language.md §4.1): a binary
        // operator's level, or `primary` for one syntactic unit (literal,
        // variable, tuple, parenthesised or unary expression).
        int binding = primary;
        bool atomic() const
        {
            return binding == primary;
        }
    };
    struct Line {
        int indent = 0;
        Tokens tokens;
        std::string comment;
    };

    // Randomness.
    unsigned below(unsigned bound);
    bool chance(unsigned percent);
    int between(int low, int high);
    template<class T>
    const T &pick(const std::vector<T> &items)
    {
        return items[below(unsigned(items.size()))];
    }

    // Program parts.
    void reset();
    void generate_program();
    void constant_definition();
    void variable_definition();
    void statement(int depth, int subroutine);
    void block(int depth, int subroutine, int count);
    void emit_line(Tokens tokens);

    void assignment();
    void compound_assignment();
    void increment();
    void if_statement(int depth, int subroutine);
    void when_statement(int depth, int subroutine);
    void while_statement(int depth, int subroutine);
    void for_statement(int depth, int subroutine);
    void emit_statement();
    void call_statement();

    // Expressions.
    Expression expression(int size, int depth);
    Expression scalar_leaf(int depth);
    Expression vector_leaf(int size, int depth);
    Expression literal();
    Expression constant_expression(int depth);
    Expression memory_reference(int size, int depth); // a variable, element or slice
    Expression element(const Variable &array, int depth);
    Expression binary(const Expression &left, const std::string &op, Expression right);
    Expression unary(const std::string &op, const Expression &operand);
    Expression tuple(int size, int depth);
    Tokens list_item(const Expression &item);
    Tokens condition(int depth);
    Tokens comparison(int depth);
    Tokens loop_variable(int depth);
    std::string literal_text(int value);

    std::vector<const Variable *> variables_of_size(int size) const;
    std::vector<const Variable *> arrays_of_at_least(int size) const;
    int max_variable_size() const;

    // Rendering and corruption.
    std::string render() const;
    std::string render_line(const Line &line) const;
    std::string mutate();

    std::mt19937 random_;
    const aseba::TargetDescription &target_;
    const aseba::CommonDefinitions &definitions_;

    std::vector<Variable> variables_; // named then user, declaration order
    std::vector<NamedValue> constants_;
    std::vector<NamedValue> global_events_; // name, size
    std::vector<std::string> subroutines_;
    std::vector<Line> lines_;
    int indent_ = 0;
    int name_counter_ = 0;
    bool spaced_ = true;         // tokens separated by spaces or packed where possible
    std::string newline_ = "\n"; // or "\r\n"
    std::string indent_text_ = "\t";
};

} // namespace compiler_tests
