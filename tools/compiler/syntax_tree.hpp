// The tree the parser builds and the later phases rewrite (language.md §9):
// parse → size check → rewriting of op=, ++, -- → vector expansion → type
// check → optimisation → code generation.

#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "compiler.hpp"

namespace aseba
{

enum class NodeKind {
    // statements
    Block,               // children: statements
    Assignment,          // children: target (Memory, or Store/ArrayWrite after expansion), value
    CompoundAssignment,  // operation = binary operator; children: target, value
    IncrementAssignment, // operation = ADD or SUB (++ / --); children: target
    If,    // is_when, has_else; children: condition, true block, else block (Block, maybe empty)
    While, // children: condition, body
    Emit,  // event_id, address, size; children: optional Block filling a temporary
    Call,  // native_id; children: CallArgument each
    CallArgument, // address_kind; children: filling code (Block) or index expression
    CallSub,      // name
    FunctionCall, // name; children: arguments (scalar words after expansion); a statement
                  // or an expression (the subroutine's value)
    Return,       // children: the value, if any; address: where the value goes
    EventStart,   // event_id: the following statements handle this event
    SubStart,     // name: the following statements form this subroutine
    // expressions
    Binary,    // operation; children: left, right
    Unary,     // operation; children: operand
    Immediate, // value
    Memory,    // a variable reference: name, address, variable_size, index form
    Tuple,     // children: elements
    // scalar forms produced by the expansion
    Load,       // address
    Store,      // address
    ArrayRead,  // address, variable_size; children: index
    ArrayWrite, // address, variable_size; children: index
};

// How a Memory node selects words of its variable.
enum class IndexForm {
    Whole,      // v
    Constant,   // v[c] or v[i:j]: first_index, index_count
    Expression, // v[e]: children[0] = e (may still fold to a constant)
};

// How a native-call argument's address is found (language.md §8.7).
enum class ArgumentAddress {
    Direct,    // a variable, constant element or slice: address is known
    Computed,  // v[e]: children[0] = e, temporary = address of the 1-word scratch
    Temporary, // children[0] = code filling the temporary at address
};

// The variable name of temporaries: no identifier can spell it.
inline constexpr const char *TEMPORARY_NAME = "#temporary";

// The unary operator known only to the compiler (vm_opcodes.h: never emitted).
constexpr int UNARY_NOT = 3;

struct Node {
    NodeKind kind;
    SourcePosition position;
    std::vector<std::unique_ptr<Node>> children;

    int operation = 0;           // Binary / Unary / CompoundAssignment operator code
    int64_t value = 0;           // Immediate: value in 32-bit folding arithmetic
    bool is_when = false;        // If: a `when`
    bool is_hidden = false;      // Emit: `_emit`
    bool has_else = false;       // If: an `else` was written (even with nothing after) or an
                                 // `elseif` whose statement survives the optimisation
    bool else_is_elseif = false; // If: the else block holds the `elseif` statement

    std::string name;           // Memory: variable; CallSub/SubStart: subroutine
    unsigned address = 0;       // Memory/Load/Store/Array*/Emit/CallArgument
    unsigned variable_size = 0; // Memory/Array*: declared size of the variable
    IndexForm index_form = IndexForm::Whole;
    int first_index = 0;    // Memory with a constant index
    int index_count = 0;    // Memory with a constant index: words selected
    bool is_slice = false;  // Memory written v[i:j]
    unsigned event_id = 0;  // Emit / EventStart
    unsigned size = 0;      // Emit: words emitted
    unsigned native_id = 0; // Call
    ArgumentAddress address_kind = ArgumentAddress::Direct;
    unsigned indexed_address = 0;     // CallArgument Computed: base of the indexed variable
    std::vector<unsigned> size_words; // Call: sizes pushed before the addresses (§8.7)
    int frame = -1; // >= 0: `address` is an offset in the locals of that frame (handler or
                    // subroutine), made absolute once the locals area is laid out
    bool has_reserved_temporary = false; // Assignment: its vector temporary is at `address`
    bool is_statement = false;           // FunctionCall: a statement (any value dropped)
    unsigned height = 1;                 // expressions: levels below and including this one
    unsigned end_line = 0; // If: line of its `end` (the reference's line after the if)

    Node(NodeKind node_kind, SourcePosition where)
      : kind(node_kind)
      , position(where)
    {
    }
};

using NodePointer = std::unique_ptr<Node>;

// A new node of `kind` at `position`.
inline NodePointer make_node(NodeKind kind, SourcePosition position)
{
    return std::make_unique<Node>(kind, position);
}

// A deep copy of `node`.
NodePointer clone(const Node &node);

} // namespace aseba
