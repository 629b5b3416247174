// The phases between parsing and optimisation (language.md §9): vector size
// check, rewriting of op=/++/--, expansion of vector statements into scalar
// ones (with the temporaries of self-referencing assignments, §8.1) and type
// check (§5).

#include "compilation.hpp"
#include "diagnostics.hpp"
#include "vm_opcodes.h"

namespace aseba
{

NodePointer clone(const Node &node)
{
    auto copy = std::make_unique<Node>(node.kind, node.position);
    copy->operation = node.operation;
    copy->value = node.value;
    copy->is_when = node.is_when;
    copy->is_hidden = node.is_hidden;
    copy->has_else = node.has_else;
    copy->else_is_elseif = node.else_is_elseif;
    copy->name = node.name;
    copy->address = node.address;
    copy->variable_size = node.variable_size;
    copy->index_form = node.index_form;
    copy->first_index = node.first_index;
    copy->index_count = node.index_count;
    copy->is_slice = node.is_slice;
    copy->event_id = node.event_id;
    copy->size = node.size;
    copy->native_id = node.native_id;
    copy->address_kind = node.address_kind;
    copy->indexed_address = node.indexed_address;
    copy->size_words = node.size_words;
    copy->frame = node.frame;
    copy->has_reserved_temporary = node.has_reserved_temporary;
    copy->is_statement = node.is_statement;
    copy->height = node.height;
    copy->end_line = node.end_line;
    copy->children.reserve(node.children.size());
    for (const auto &child : node.children)
        copy->children.push_back(clone(*child));
    return copy;
}

bool mentions(const Node &expression, const std::string &name)
{
    if (expression.kind == NodeKind::Memory && expression.name == name)
        return true;
    for (const auto &child : expression.children)
        if (mentions(*child, name))
            return true;
    return false;
}

bool contains_call(const Node &node)
{
    if (node.kind == NodeKind::FunctionCall)
        return true;
    for (const auto &child : node.children)
        if (contains_call(*child))
            return true;
    return false;
}

unsigned vector_size(const Node &expression)
{
    switch (expression.kind) {
    case NodeKind::Memory:
        switch (expression.index_form) {
        case IndexForm::Whole: return expression.variable_size;
        case IndexForm::Constant: return static_cast<unsigned>(expression.index_count);
        case IndexForm::Expression: return 1;
        }
        return 1;
    case NodeKind::Tuple: {
        unsigned total = 0;
        for (const auto &element : expression.children)
            total += vector_size(*element);
        return total;
    }
    case NodeKind::Binary: {
        unsigned left = vector_size(*expression.children[0]);
        unsigned right = vector_size(*expression.children[1]);
        if (left != right)
            fail_size(expression.position, left, right);
        return left;
    }
    case NodeKind::Unary: return vector_size(*expression.children[0]);
    default: return 1;
    }
}

namespace
{

// Throws the §6 bounds error if `index` is outside the variable of `memory`.
void check_bounds(const Node &memory, int64_t index)
{
    if (index < 0 || index >= static_cast<int64_t>(memory.variable_size))
        fail(memory.position,
             "Access of array " + memory.name + " out of bounds: accessing index " +
               std::to_string(index) + " while array is of size " +
               std::to_string(memory.variable_size));
}

// The size of `expression`, checking on the way (children first) that
// operands agree in size and that constant indexes are within bounds, as
// the reference's size-check phase does.
unsigned checked_size(const Node &expression)
{
    switch (expression.kind) {
    case NodeKind::Memory:
        // The reference checks here only the end of slices; single constant
        // indexes and slice starts are checked while expanding.
        if (expression.is_slice)
            check_bounds(expression,
                         static_cast<int64_t>(expression.first_index) + expression.index_count - 1);
        for (const auto &child : expression.children)
            checked_size(*child);
        return vector_size(expression);
    case NodeKind::Tuple: {
        unsigned total = 0;
        for (const auto &element : expression.children)
            total += checked_size(*element);
        return total;
    }
    case NodeKind::Binary: {
        unsigned left = checked_size(*expression.children[0]);
        unsigned right = checked_size(*expression.children[1]);
        if (left != right)
            fail_size(expression.position, left, right);
        return left;
    }
    case NodeKind::Unary: return checked_size(*expression.children[0]);
    case NodeKind::FunctionCall:
        for (const auto &argument : expression.children)
            checked_size(*argument);
        return 1;
    default: return 1;
    }
}

void check_statement_sizes(Node &statement)
{
    switch (statement.kind) {
    case NodeKind::Block:
        for (auto &child : statement.children)
            check_statement_sizes(*child);
        break;
    case NodeKind::Assignment:
    case NodeKind::CompoundAssignment: {
        unsigned left = checked_size(*statement.children[0]);
        unsigned right = checked_size(*statement.children[1]);
        if (left != right)
            fail_size(statement.position, left, right);
        break;
    }
    // `++` and `--` have nothing to compare; their target is checked when expanded
    case NodeKind::FunctionCall:
    case NodeKind::Return:
        for (const auto &child : statement.children)
            checked_size(*child);
        break;
    case NodeKind::If:
    case NodeKind::While:
        if (checked_size(*statement.children[0]) != 1)
            fail(statement.position,
                 statement.kind == NodeKind::While ? "Condition of the while cannot be a vector"
                                                   : "Condition of the if cannot be a vector");
        for (size_t i = 1; i < statement.children.size(); ++i)
            check_statement_sizes(*statement.children[i]);
        break;
    case NodeKind::Emit:
    case NodeKind::Call:
    case NodeKind::CallArgument:
        for (auto &child : statement.children) {
            if (child->kind == NodeKind::Memory)
                checked_size(*child);
            else
                check_statement_sizes(*child);
        }
        break;
    default: break;
    }
}

} // namespace

void check_constant_index(const Node &memory)
{
    if (memory.index_form != IndexForm::Constant)
        return;
    check_bounds(memory, static_cast<int64_t>(memory.first_index) + memory.index_count - 1);
    check_bounds(memory, memory.first_index);
}

namespace
{

// The value of `index` if the optimisation rules make it a constant; errors
// of the attempt are left for the optimisation phase to report in order.
std::optional<int64_t> folded_index(const Node &index)
{
    try {
        NodePointer folded = optimize(clone(index));
        if (folded && folded->kind == NodeKind::Immediate)
            return folded->value;
    } catch (const CompileFailure &) {
    }
    return std::nullopt;
}

// Scalar nodes the expansion may create: far more than any bytecode can
// hold, few enough to keep memory bounded on hostile inputs.
constexpr unsigned long MAX_EXPANDED_NODES = 4000000;

class Expander
{
  public:
    explicit Expander(Compilation &state)
      : compilation(state)
    {
    }

    // Replaces vector statements of `block` by their scalar expansion.
    void expand_block(Node &block)
    {
        for (auto &statement : block.children)
            statement = expand_statement(std::move(statement));
    }

  private:
    Compilation &compilation;
    unsigned long expanded_nodes = 0;

    // What an expression is called in "Expecting an assignment to a variable".
    static const char *node_description(const Node &node)
    {
        switch (node.kind) {
        case NodeKind::Binary: return "binary function";
        case NodeKind::Unary: return "unary function";
        case NodeKind::Tuple:
        case NodeKind::Immediate: return "array of constants";
        default: return "expression";
        }
    }

    NodePointer expand_statement(NodePointer statement)
    {
        bool is_assignment = statement->kind == NodeKind::Assignment ||
                             statement->kind == NodeKind::CompoundAssignment ||
                             statement->kind == NodeKind::IncrementAssignment;
        if (is_assignment && statement->children[0]->kind != NodeKind::Memory)
            fail(statement->position,
                 std::string("Expecting an assignment to a variable, found ") +
                   node_description(*statement->children[0]) + " instead");
        switch (statement->kind) {
        case NodeKind::Block: expand_block(*statement); return statement;
        case NodeKind::Assignment:
            return expand_assignment(
              std::move(statement->children[0]), std::move(statement->children[1]), *statement);
        case NodeKind::CompoundAssignment: {
            auto sum = make_node(NodeKind::Binary, statement->position);
            sum->operation = statement->operation;
            sum->children.reserve(2);
            sum->children.push_back(clone(*statement->children[0]));
            sum->children.push_back(std::move(statement->children[1]));
            return expand_assignment(std::move(statement->children[0]), std::move(sum), *statement);
        }
        case NodeKind::FunctionCall: expand_arguments(*statement); return statement;
        case NodeKind::Return:
            if (!statement->children.empty())
                statement->children[0] = element(*statement->children[0], 0);
            return statement;
        case NodeKind::IncrementAssignment: {
            unsigned size = vector_size(*statement->children[0]);
            auto ones = make_node(NodeKind::Tuple, statement->position);
            for (unsigned k = 0; k < size; ++k) {
                auto one = make_node(NodeKind::Immediate, statement->position);
                one->value = 1;
                ones->children.push_back(std::move(one));
            }
            auto sum = make_node(NodeKind::Binary, statement->position);
            sum->operation = statement->operation;
            sum->children.push_back(clone(*statement->children[0]));
            sum->children.push_back(std::move(ones));
            return expand_assignment(std::move(statement->children[0]), std::move(sum), *statement);
        }
        case NodeKind::If:
        case NodeKind::While:
            statement->children[0] = element(*statement->children[0], 0);
            for (size_t i = 1; i < statement->children.size(); ++i)
                statement->children[i] = expand_statement(std::move(statement->children[i]));
            return statement;
        case NodeKind::Emit:
            if (!statement->children.empty()) {
                Node &argument = *statement->children[0];
                if (argument.kind == NodeKind::Memory) {
                    check_constant_index(argument);
                    statement->address =
                      argument.address +
                      static_cast<unsigned>(
                        argument.index_form == IndexForm::Constant ? argument.first_index : 0);
                    statement->children.clear();
                } else {
                    statement->children[0] = expand_statement(std::move(statement->children[0]));
                }
            }
            return statement;
        case NodeKind::Call:
            for (auto &argument : statement->children)
                expand_call_argument(*argument);
            return statement;
        default: return statement;
        }
    }

    void expand_call_argument(Node &argument)
    {
        Node &content = *argument.children[0];
        switch (argument.address_kind) {
        case ArgumentAddress::Direct:
            check_constant_index(content);
            argument.address =
              content.address + static_cast<unsigned>(content.index_form == IndexForm::Constant
                                                        ? content.first_index
                                                        : 0);
            argument.children.clear();
            break;
        case ArgumentAddress::Computed: {
            // keep the variable's place and size, the index becomes the child
            NodePointer index = element(*content.children[0], 0);
            argument.variable_size = content.variable_size;
            argument.name = content.name;
            argument.indexed_address = content.address;
            argument.children[0] = std::move(index);
            break;
        }
        case ArgumentAddress::Temporary:
            argument.children[0] = expand_statement(std::move(argument.children[0]));
            break;
        }
    }

    // The arguments of a call, word by word: parameter after parameter.
    void expand_arguments(Node &call)
    {
        std::vector<NodePointer> words;
        for (const auto &argument : call.children) {
            unsigned size = vector_size(*argument);
            for (unsigned k = 0; k < size; ++k)
                words.push_back(element(*argument, k));
        }
        call.children = std::move(words);
    }

    // x = e, element by element, through a temporary if e reads x (§8.1).
    // `statement` is the assignment written, which may hold its temporary.
    NodePointer expand_assignment(NodePointer target, NodePointer value, const Node &statement)
    {
        SourcePosition where = statement.position;
        unsigned size = vector_size(*target);
        auto block = make_node(NodeKind::Block, where);
        block->children.reserve(size);
        if (size > 1 && mentions(*value, target->name)) {
            unsigned temporary = statement.has_reserved_temporary
                                   ? statement.address
                                   : compilation.allocate_temporary(size, where);
            for (unsigned k = 0; k < size; ++k) {
                auto store = make_node(NodeKind::Store, where);
                store->address = temporary + k;
                block->children.push_back(
                  scalar_assignment(std::move(store), element(*value, k), where));
            }
            for (unsigned k = 0; k < size; ++k) {
                auto load = make_node(NodeKind::Load, where);
                load->address = temporary + k;
                block->children.push_back(
                  scalar_assignment(store_element(*target, k), std::move(load), where));
            }
            return block;
        }
        for (unsigned k = 0; k < size; ++k) {
            NodePointer scalar_value = element(*value, k);
            block->children.push_back(
              scalar_assignment(store_element(*target, k), std::move(scalar_value), where));
        }
        return block;
    }

    static NodePointer scalar_assignment(NodePointer store, NodePointer value, SourcePosition where)
    {
        auto assignment = make_node(NodeKind::Assignment, where);
        assignment->children.reserve(2);
        assignment->children.push_back(std::move(store));
        assignment->children.push_back(std::move(value));
        return assignment;
    }

    // The scalar access to word k of a Memory node, as a load or a store.
    NodePointer memory_element(const Node &memory, unsigned k, bool is_store)
    {
        NodeKind direct = is_store ? NodeKind::Store : NodeKind::Load;
        switch (memory.index_form) {
        case IndexForm::Whole: {
            auto node = make_node(direct, memory.position);
            node->address = memory.address + k;
            node->name = memory.name;
            return node;
        }
        case IndexForm::Constant: {
            check_constant_index(memory);
            auto node = make_node(direct, memory.position);
            node->address = memory.address + static_cast<unsigned>(memory.first_index) + k;
            node->name = memory.name;
            return node;
        }
        case IndexForm::Expression: {
            NodePointer index = element(*memory.children[0], 0);
            if (std::optional<int64_t> constant = folded_index(*index)) {
                check_bounds(memory, *constant);
                auto node = make_node(direct, memory.position);
                node->address = memory.address + static_cast<unsigned>(*constant);
                node->name = memory.name;
                return node;
            }
            auto node =
              make_node(is_store ? NodeKind::ArrayWrite : NodeKind::ArrayRead, memory.position);
            node->address = memory.address;
            node->variable_size = memory.variable_size;
            node->name = memory.name;
            node->height = index->height + 1;
            node->children.push_back(std::move(index));
            return node;
        }
        }
        return nullptr;
    }

    NodePointer store_element(const Node &memory, unsigned k)
    {
        return memory_element(memory, k, true);
    }

    // Word k of a vector expression, as a scalar expression (§6).
    NodePointer element(const Node &expression, unsigned k)
    {
        if (++expanded_nodes > MAX_EXPANDED_NODES)
            fail(expression.position,
                 "This program is too large to compile (its vector "
                 "operations expand to millions of instructions)");
        switch (expression.kind) {
        case NodeKind::Memory: return memory_element(expression, k, false);
        case NodeKind::Tuple:
            for (const auto &item : expression.children) {
                unsigned size = vector_size(*item);
                if (k < size)
                    return element(*item, k);
                k -= size;
            }
            break;
        case NodeKind::Binary:
        case NodeKind::Unary: {
            auto node = make_node(expression.kind, expression.position);
            node->operation = expression.operation;
            node->height = expression.height;
            node->children.reserve(expression.children.size());
            for (const auto &child : expression.children)
                node->children.push_back(element(*child, k));
            return node;
        }
        case NodeKind::FunctionCall: {
            NodePointer call = clone(expression);
            expand_arguments(*call);
            return call;
        }
        default: break;
        }
        return clone(expression);
    }
};

enum class Type { Unit, Bool, Integer };

const char *type_name(Type type)
{
    switch (type) {
    case Type::Unit: return "unit";
    case Type::Bool: return "bool";
    case Type::Integer: return "integer";
    }
    return "?";
}

void expect_type(Type expected, Type found, SourcePosition where)
{
    if (expected != found)
        fail(where,
             std::string("Expecting ") + type_name(expected) + " type, found " + type_name(found) +
               " type instead");
}

bool is_comparison(int operation)
{
    return operation >= VM_BINARY_EQUAL && operation <= VM_BINARY_SMALLER_EQUAL_THAN;
}

Type expression_type(const Node &expression)
{
    switch (expression.kind) {
    case NodeKind::Binary: {
        Type left = expression_type(*expression.children[0]);
        Type right = expression_type(*expression.children[1]);
        int operation = expression.operation;
        if (operation == VM_BINARY_OR || operation == VM_BINARY_AND) {
            expect_type(Type::Bool, left, expression.position);
            expect_type(Type::Bool, right, expression.position);
            return Type::Bool;
        }
        expect_type(Type::Integer, left, expression.position);
        expect_type(Type::Integer, right, expression.position);
        return is_comparison(operation) ? Type::Bool : Type::Integer;
    }
    case NodeKind::Unary: {
        Type operand = expression_type(*expression.children[0]);
        if (expression.operation == UNARY_NOT) {
            expect_type(Type::Bool, operand, expression.position);
            return Type::Bool;
        }
        expect_type(Type::Integer, operand, expression.position);
        return Type::Integer;
    }
    case NodeKind::ArrayRead:
        expect_type(Type::Integer, expression_type(*expression.children[0]), expression.position);
        return Type::Integer;
    case NodeKind::FunctionCall:
        for (const auto &argument : expression.children)
            expect_type(Type::Integer, expression_type(*argument), argument->position);
        return Type::Integer;
    default: return Type::Integer;
    }
}

// Types of every statement; subroutine names are resolved here too, where
// the reference reports unknown ones.
void check_statement_types(const Node &statement, const Compilation &compilation)
{
    switch (statement.kind) {
    case NodeKind::CallSub: {
        const Subroutine &subroutine = compilation.called_subroutine(
          statement.name, statement.position, "Subroutine " + statement.name + " does not exists");
        if (!subroutine.parameters.empty())
            fail(statement.position,
                 "Subroutine " + statement.name + " takes " +
                   std::to_string(subroutine.parameters.size()) +
                   " parameters: call it with its arguments, " + statement.name + "(...)");
        break;
    }
    case NodeKind::FunctionCall: expression_type(statement); break;
    case NodeKind::Return:
        if (!statement.children.empty())
            expect_type(Type::Integer, expression_type(*statement.children[0]), statement.position);
        break;
    case NodeKind::Block:
    case NodeKind::Emit:
        for (const auto &child : statement.children)
            check_statement_types(*child, compilation);
        break;
    case NodeKind::Assignment: {
        const Node &target = *statement.children[0];
        if (target.kind == NodeKind::ArrayWrite)
            expect_type(Type::Integer, expression_type(*target.children[0]), target.position);
        expect_type(Type::Integer, expression_type(*statement.children[1]), statement.position);
        break;
    }
    case NodeKind::If:
    case NodeKind::While:
        expect_type(Type::Bool, expression_type(*statement.children[0]), statement.position);
        for (size_t i = 1; i < statement.children.size(); ++i)
            check_statement_types(*statement.children[i], compilation);
        break;
    case NodeKind::Call:
        for (const auto &argument : statement.children) {
            if (argument->children.empty())
                continue;
            if (argument->address_kind == ArgumentAddress::Computed)
                expect_type(
                  Type::Integer, expression_type(*argument->children[0]), argument->position);
            else
                check_statement_types(*argument->children[0], compilation);
        }
        break;
    default: break;
    }
}

} // namespace

void check_sizes(Node &program)
{
    check_statement_sizes(program);
}

void expand_program(Node &program, Compilation &compilation)
{
    Expander(compilation).expand_block(program);
}

void check_types(Node &program, const Compilation &compilation)
{
    check_statement_types(program, compilation);
}

} // namespace aseba
