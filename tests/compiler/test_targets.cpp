// Targets described in the specifications, written out as data.

#include "test_targets.hpp"

namespace compiler_tests
{

namespace
{

// Sizes of native parameters (language.md §13.1): > 0 fixed, < 0 template.
constexpr int16_t template_1 = -1;
constexpr int16_t template_2 = -2;

aseba::NativeFunction native(const char *name,
                             const char *description,
                             std::vector<aseba::NativeParameter> parameters)
{
    return aseba::NativeFunction{ name, description, std::move(parameters) };
}

} // namespace

std::vector<aseba::NativeFunction> standard_natives()
{
    const int16_t n = template_1;
    const int16_t m = template_2;
    return {
        native(
          "math.copy", "copies src to dest element by element", { { "dest", n }, { "src", n } }),
        native("math.fill", "fills dest with constant value", { { "dest", n }, { "value", 1 } }),
        native("math.addscalar",
               "add scalar to each element of src and store result to dest",
               { { "dest", n }, { "src", n }, { "scalar", 1 } }),
        native("math.add",
               "adds src1 and src2, write to dest, element by element",
               { { "dest", n }, { "src1", n }, { "src2", n } }),
        native("math.sub",
               "substracts src2 from src1 to dest, element by element",
               { { "dest", n }, { "src1", n }, { "src2", n } }),
        native("math.mul",
               "multiplies src1 and src2 to dest, element by element",
               { { "dest", n }, { "src1", n }, { "src2", n } }),
        native("math.div",
               "divides src1 by src2 to dest, element by element",
               { { "dest", n }, { "src1", n }, { "src2", n } }),
        native("math.min",
               "writes the minimum of src1 and src2 to dest, element by element",
               { { "dest", n }, { "src1", n }, { "src2", n } }),
        native("math.max",
               "writes the maximum of src1 and src2 to dest, element by element",
               { { "dest", n }, { "src1", n }, { "src2", n } }),
        native("math.clamp",
               "clamp src to low/high bounds into dest, element by element",
               { { "dest", n }, { "src", n }, { "low", n }, { "high", n } }),
        native("math.dot",
               "writes the dot product of src1 and src2 to dest, after a shift",
               { { "dest", 1 }, { "src1", n }, { "src2", n }, { "shift", 1 } }),
        native("math.stat",
               "performs statistics on src",
               { { "src", n }, { "min", 1 }, { "max", 1 }, { "mean", 1 } }),
        native("math.argbounds",
               "get the indices (argmin, argmax) of the limit values of src",
               { { "src", n }, { "argmin", 1 }, { "argmax", 1 } }),
        native("math.sort", "sort array in place", { { "array", n } }),
        native("math.muldiv",
               "performs dest = (a*b)/c in 32 bits element by element",
               { { "dest", n }, { "a", n }, { "b", n }, { "c", n } }),
        native("math.atan2",
               "performs dest = atan2(y,x) element by element",
               { { "dest", n }, { "y", n }, { "x", n } }),
        native(
          "math.sin", "performs dest = sin(x) element by element", { { "dest", n }, { "x", n } }),
        native(
          "math.cos", "performs dest = cos(x) element by element", { { "dest", n }, { "x", n } }),
        native(
          "math.rot2", "rotates v of angle a to dest", { { "dest", 2 }, { "v", 2 }, { "a", 1 } }),
        native(
          "math.sqrt", "performs dest = sqrt(x) element by element", { { "dest", n }, { "x", n } }),
        native("math.rand", "fill array with random values", { { "dest", n } }),
        native("deque.size", "report size of dest", { { "deque", n }, { "size", 1 } }),
        native("deque.get",
               "fill dest from deque at index",
               { { "deque", n }, { "dest", m }, { "index", 1 } }),
        native("deque.set",
               "copies src to deque at index",
               { { "deque", n }, { "src", m }, { "index", 1 } }),
        native("deque.insert",
               "shift deque at index by len(src) and insert src",
               { { "deque", n }, { "src", m }, { "index", 1 } }),
        native("deque.erase",
               "shift deque at index by len to erase",
               { { "deque", n }, { "index", 1 }, { "len", 1 } }),
        native("deque.push_front",
               "insert src before the front of deque",
               { { "deque", n }, { "src", m } }),
        native("deque.push_back",
               "insert src after the back of deque",
               { { "deque", n }, { "src", m } }),
        native("deque.pop_front",
               "fill dest from front of deque then erase elements",
               { { "deque", n }, { "dest", m } }),
        native("deque.pop_back",
               "fill dest from back of deque then erase elements",
               { { "deque", n }, { "dest", m } }),
    };
}

aseba::TargetDescription corpus_target(const std::vector<aseba::NativeFunction> &natives)
{
    aseba::TargetDescription target;
    target.name = "testvm";
    target.protocol_version = 5;
    target.bytecode_size = 512;
    target.stack_size = 64;
    target.variables_size = 256;
    target.local_events = { { "test", "test local event" } };
    target.native_functions = natives;
    return target;
}

aseba::CommonDefinitions corpus_definitions()
{
    aseba::CommonDefinitions definitions;
    definitions.events = { { "event1", 0 }, { "event2", 3 } };
    definitions.constants = { { "FOO", 2 } };
    return definitions;
}

aseba::TargetDescription dummy_node_target()
{
    aseba::TargetDescription target;
    target.name = "dummynode";
    target.protocol_version = 5;
    target.bytecode_size = 512;
    target.stack_size = 64;
    target.variables_size = 1060;
    target.named_variables = {
        { "id", 1 }, { "source", 1 }, { "args", 32 }, { "_productId", 1 }, { "timer.period", 1 }
    };
    target.local_events = { { "timer", "periodic timer" } };
    target.native_functions = standard_natives();
    return target;
}

} // namespace compiler_tests
