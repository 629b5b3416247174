// The tree simplifications of language.md §9: constant folding in 32-bit
// arithmetic, neutral and absorbing elements, power-of-two strength
// reduction, De Morgan's laws, constant indexes, and removal of statements
// that do nothing.

#include <optional>

#include "compilation.hpp"
#include "diagnostics.hpp"
#include "vm_opcodes.h"

namespace aseba
{

namespace
{

constexpr int SHIFT_COUNT_MASK = 31; // x86 takes shift counts modulo 32
constexpr int64_t INT16_MIN_VALUE = -32768;

// Wraps to a 32-bit two's complement value, as the reference's C `int`.
int64_t wrap32(int64_t value)
{
    return static_cast<int32_t>(static_cast<uint32_t>(static_cast<uint64_t>(value)));
}

bool is_immediate(const Node &node)
{
    return node.kind == NodeKind::Immediate;
}

bool is_immediate(const Node &node, int64_t value)
{
    return node.kind == NodeKind::Immediate && node.value == value;
}

NodePointer make_immediate(int64_t value, SourcePosition where)
{
    auto node = make_node(NodeKind::Immediate, where);
    node->value = value;
    return node;
}

// The binary operation on two constants, as the reference folds it.
int64_t fold_binary(int operation, int64_t a, int64_t b, SourcePosition where)
{
    auto a32 = static_cast<int32_t>(a);
    auto b32 = static_cast<int32_t>(b);
    auto ua = static_cast<uint32_t>(a32);
    auto ub = static_cast<uint32_t>(b32);
    switch (operation) {
    case VM_BINARY_SHIFT_LEFT: return wrap32(ua << (b32 & SHIFT_COUNT_MASK));
    case VM_BINARY_SHIFT_RIGHT: return a32 >> (b32 & SHIFT_COUNT_MASK);
    case VM_BINARY_ADD: return wrap32(int64_t{ ua } + ub);
    case VM_BINARY_SUB: return wrap32(int64_t{ ua } - ub);
    case VM_BINARY_MULT: return wrap32(static_cast<int64_t>(ua * ub));
    case VM_BINARY_DIV:
    case VM_BINARY_MOD:
        if (b32 == 0)
            fail(where, "Division by zero");
        if (b32 == -1) // INT_MIN / -1 would trap; the quotient wraps
            return operation == VM_BINARY_DIV ? wrap32(-int64_t{ a32 }) : 0;
        return operation == VM_BINARY_DIV ? a32 / b32 : a32 % b32;
    case VM_BINARY_BIT_OR: return a32 | b32;
    case VM_BINARY_BIT_XOR: return a32 ^ b32;
    case VM_BINARY_BIT_AND: return a32 & b32;
    case VM_BINARY_EQUAL: return a32 == b32;
    case VM_BINARY_NOT_EQUAL: return a32 != b32;
    case VM_BINARY_BIGGER_THAN: return a32 > b32;
    case VM_BINARY_BIGGER_EQUAL_THAN: return a32 >= b32;
    case VM_BINARY_SMALLER_THAN: return a32 < b32;
    case VM_BINARY_SMALLER_EQUAL_THAN: return a32 <= b32;
    case VM_BINARY_OR: return a32 || b32;
    case VM_BINARY_AND: return a32 && b32;
    default: return 0;
    }
}

// s if value = 2^s with s >= 1.
std::optional<int> power_of_two(int64_t value)
{
    for (int s = 1; s < SHIFT_COUNT_MASK; ++s)
        if (value == (int64_t{ 1 } << s))
            return s;
    return std::nullopt;
}

NodePointer optimize_binary(NodePointer node)
{
    node->children[0] = optimize(std::move(node->children[0]));
    node->children[1] = optimize(std::move(node->children[1]));
    Node &left = *node->children[0];
    Node &right = *node->children[1];
    int operation = node->operation;
    if (is_immediate(left) && is_immediate(right))
        return make_immediate(fold_binary(operation, left.value, right.value, node->position),
                              node->position);
    if ((operation == VM_BINARY_DIV || operation == VM_BINARY_MOD) && is_immediate(right, 0) &&
        operation == VM_BINARY_DIV)
        fail(node->position, "Division by zero");

    // neutral elements: keep the other operand; absorbing ones drop an
    // operand, but never a call of a subroutine (docs/language.md)
    auto keep = [&node](size_t index) { return std::move(node->children[index]); };
    bool may_absorb = !contains_call(left) && !contains_call(right);
    switch (operation) {
    case VM_BINARY_MULT:
        if (is_immediate(right, 1))
            return keep(0);
        if (is_immediate(left, 1))
            return keep(1);
        if (may_absorb && (is_immediate(right, 0) || is_immediate(left, 0)))
            return make_immediate(0, node->position);
        break;
    case VM_BINARY_DIV:
        if (is_immediate(right, 1))
            return keep(0);
        break;
    case VM_BINARY_ADD:
        if (is_immediate(right, 0))
            return keep(0);
        if (is_immediate(left, 0))
            return keep(1);
        break;
    case VM_BINARY_SUB:
        if (is_immediate(right, 0))
            return keep(0);
        break;
    case VM_BINARY_BIT_OR:
        if (is_immediate(right, 0))
            return keep(0);
        if (is_immediate(left, 0))
            return keep(1);
        if (may_absorb && (is_immediate(right, -1) || is_immediate(left, -1)))
            return make_immediate(-1, node->position);
        break;
    case VM_BINARY_BIT_AND:
        if (is_immediate(right, -1))
            return keep(0);
        if (is_immediate(left, -1))
            return keep(1);
        if (may_absorb && (is_immediate(right, 0) || is_immediate(left, 0)))
            return make_immediate(0, node->position);
        break;
    case VM_BINARY_OR:
        if (is_immediate(right, 0))
            return keep(0);
        if (is_immediate(left, 0))
            return keep(1);
        if (may_absorb && (is_immediate(right) || is_immediate(left)))
            return make_immediate(1, node->position);
        break;
    case VM_BINARY_AND:
        if (is_immediate(right, 0) || is_immediate(left, 0))
            return may_absorb ? make_immediate(0, node->position) : std::move(node);
        if (is_immediate(right))
            return keep(0);
        if (is_immediate(left))
            return keep(1);
        break;
    default: break;
    }

    // strength reduction by a constant power of two on the right
    if (is_immediate(right) && (operation == VM_BINARY_MULT || operation == VM_BINARY_DIV)) {
        if (std::optional<int> shift = power_of_two(right.value)) {
            node->operation =
              operation == VM_BINARY_MULT ? VM_BINARY_SHIFT_LEFT : VM_BINARY_SHIFT_RIGHT;
            right.value = *shift;
        }
    }
    return node;
}

// `not` over an optimised boolean expression, pushed down by De Morgan.
NodePointer negate(NodePointer operand, SourcePosition where)
{
    if (is_immediate(*operand))
        return make_immediate(operand->value == 0 ? 1 : 0, where);
    if (operand->kind == NodeKind::Unary && operand->operation == UNARY_NOT)
        return std::move(operand->children[0]);
    if (operand->kind == NodeKind::Binary) {
        switch (operand->operation) {
        case VM_BINARY_EQUAL: operand->operation = VM_BINARY_NOT_EQUAL; return operand;
        case VM_BINARY_NOT_EQUAL: operand->operation = VM_BINARY_EQUAL; return operand;
        case VM_BINARY_BIGGER_THAN:
            operand->operation = VM_BINARY_SMALLER_EQUAL_THAN;
            return operand;
        case VM_BINARY_SMALLER_EQUAL_THAN:
            operand->operation = VM_BINARY_BIGGER_THAN;
            return operand;
        case VM_BINARY_BIGGER_EQUAL_THAN:
            operand->operation = VM_BINARY_SMALLER_THAN;
            return operand;
        case VM_BINARY_SMALLER_THAN:
            operand->operation = VM_BINARY_BIGGER_EQUAL_THAN;
            return operand;
        case VM_BINARY_AND:
        case VM_BINARY_OR:
            operand->operation = operand->operation == VM_BINARY_AND ? VM_BINARY_OR : VM_BINARY_AND;
            operand->children[0] = negate(std::move(operand->children[0]), where);
            operand->children[1] = negate(std::move(operand->children[1]), where);
            return operand;
        default: break;
        }
    }
    auto node = make_node(NodeKind::Unary, where);
    node->operation = UNARY_NOT;
    node->children.push_back(std::move(operand));
    return node;
}

NodePointer optimize_unary(NodePointer node)
{
    node->children[0] = optimize(std::move(node->children[0]));
    if (node->operation == UNARY_NOT)
        return negate(std::move(node->children[0]), node->position);
    Node &operand = *node->children[0];
    if (!is_immediate(operand))
        return node;
    int64_t value = operand.value;
    switch (node->operation) {
    case VM_UNARY_SUB: return make_immediate(wrap32(-value), node->position);
    case VM_UNARY_ABS:
        if (value == INT16_MIN_VALUE)
            fail(node->position, "-32768 has no positive correspondance in 16 bits integers");
        return make_immediate(wrap32(value < 0 ? -value : value), node->position);
    case VM_UNARY_BIT_NOT: return make_immediate(wrap32(~value), node->position);
    default: return node;
    }
}

// An indexed access whose index became constant turns into a direct one.
NodePointer optimize_array_access(NodePointer node)
{
    node->children[0] = optimize(std::move(node->children[0]));
    const Node &index = *node->children[0];
    if (!is_immediate(index))
        return node;
    bool is_read = node->kind == NodeKind::ArrayRead;
    if (index.value < 0 || index.value >= static_cast<int64_t>(node->variable_size))
        fail(node->position,
             std::string("Out of bound static array access. Trying to ") +
               (is_read ? "read" : "write") + " index " + std::to_string(index.value) +
               " of array " + node->name + " of size " + std::to_string(node->variable_size));
    auto direct = make_node(is_read ? NodeKind::Load : NodeKind::Store, node->position);
    direct->address = node->address + static_cast<unsigned>(index.value);
    return direct;
}

bool is_empty_block(const Node *node)
{
    return node == nullptr || (node->kind == NodeKind::Block && node->children.empty());
}

NodePointer optimize_block(NodePointer block)
{
    std::vector<NodePointer> kept;
    kept.reserve(block->children.size());
    for (auto &statement : block->children) {
        NodePointer optimized = optimize(std::move(statement));
        if (optimized && !is_empty_block(optimized.get()))
            kept.push_back(std::move(optimized));
    }
    block->children = std::move(kept);
    return block;
}

// Blocks stay blocks even when emptied: `if` and `while` keep their shape.
NodePointer optimize_child_block(NodePointer block)
{
    NodePointer optimized = optimize(std::move(block));
    return optimized ? std::move(optimized) : make_node(NodeKind::Block, {});
}

NodePointer optimize_if(NodePointer node)
{
    node->children[0] = optimize(std::move(node->children[0]));
    node->children[1] = optimize_child_block(std::move(node->children[1]));
    if (node->else_is_elseif) {
        // The `elseif` keeps its jump unless its statement disappears
        // entirely; folded to an (even empty) block, it keeps it.
        Node &else_block = *node->children[2];
        NodePointer nested = optimize(std::move(else_block.children[0]));
        node->has_else = nested != nullptr;
        else_block.children.clear();
        if (nested && !is_empty_block(nested.get()))
            else_block.children.push_back(std::move(nested));
    } else {
        node->children[2] = optimize_child_block(std::move(node->children[2]));
    }
    if (is_empty_block(node->children[1].get()) && is_empty_block(node->children[2].get()))
        return nullptr;
    // A constant condition leaves the chosen part: a block, even empty, still
    // counts as a statement for an enclosing `elseif`; an absent else does not.
    const Node &condition = *node->children[0];
    if (is_immediate(condition)) {
        if (condition.value != 0)
            return std::move(node->children[1]);
        return node->has_else ? std::move(node->children[2]) : nullptr;
    }
    return node;
}

NodePointer optimize_while(NodePointer node)
{
    node->children[0] = optimize(std::move(node->children[0]));
    node->children[1] = optimize_child_block(std::move(node->children[1]));
    const Node &condition = *node->children[0];
    if (is_immediate(condition)) {
        if (condition.value != 0)
            fail(node->position, "Infinite loops not allowed");
        return nullptr;
    }
    if (is_empty_block(node->children[1].get()))
        return nullptr;
    return node;
}

} // namespace

NodePointer optimize(NodePointer node)
{
    if (!node)
        return node;
    switch (node->kind) {
    case NodeKind::Binary: return optimize_binary(std::move(node));
    case NodeKind::Unary: return optimize_unary(std::move(node));
    case NodeKind::ArrayRead:
    case NodeKind::ArrayWrite: return optimize_array_access(std::move(node));
    case NodeKind::Block: return optimize_block(std::move(node));
    case NodeKind::If: return optimize_if(std::move(node));
    case NodeKind::While: return optimize_while(std::move(node));
    case NodeKind::Assignment:
        node->children[0] = optimize(std::move(node->children[0]));
        node->children[1] = optimize(std::move(node->children[1]));
        return node;
    case NodeKind::Emit:
        for (auto &child : node->children)
            child = optimize_child_block(std::move(child));
        return node;
    case NodeKind::Call:
        for (auto &argument : node->children)
            for (auto &child : argument->children)
                child = optimize(std::move(child));
        return node;
    case NodeKind::Tuple:
    case NodeKind::FunctionCall:
    case NodeKind::Return:
        for (auto &child : node->children)
            child = optimize(std::move(child));
        return node;
    default: return node;
    }
}

std::optional<int64_t> evaluate_constant(const Node &expression, bool report_errors)
{
    switch (expression.kind) {
    case NodeKind::Immediate: return expression.value;
    case NodeKind::Tuple: // the reference takes a tuple's first element (§9)
        if (expression.children.empty())
            return std::nullopt;
        return evaluate_constant(*expression.children[0], report_errors);
    case NodeKind::Binary:
    case NodeKind::Unary: {
        for (const auto &child : expression.children)
            if (!evaluate_constant(*child, report_errors))
                return std::nullopt;
        try {
            NodePointer folded = optimize(clone(expression));
            if (folded && folded->kind == NodeKind::Immediate)
                return folded->value;
        } catch (const CompileFailure &) {
            if (report_errors)
                throw;
            // else left for the optimisation phase to report in source order
        }
        return std::nullopt;
    }
    default: return std::nullopt;
    }
}

} // namespace aseba
