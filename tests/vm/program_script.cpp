// The interpreter of the `#` lines of tests/vm/programs/*.asm. Setup lines
// (memory, set, budget, trace) apply before the program starts; actions and
// expectations then run in file order, after the implicit start: load the
// image with SET_BYTECODE, RUN, and run `init` within the budget.

#include "tests/vm/program_script.hpp"

#include <algorithm>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>

#include "tests/support/assembler.hpp"
#include "tests/support/vm_harness.hpp"

namespace vm_tests
{

namespace
{

using test_support::VmHarness;
using test_support::VmMessage;

constexpr uint16_t DEFAULT_BUDGET = 10000;

struct Directive {
    unsigned line;
    std::string keyword;
    std::string rest;
};

const std::string keywords[] = { "memory", "set",  "budget", "trace",    "run",  "receive",
                                 "reset",  "stop", "pause",  "continue", "step", "expect" };

std::string trim(const std::string &text)
{
    size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos)
        return "";
    size_t last = text.find_last_not_of(" \t\r");
    return text.substr(first, last - first + 1);
}

// Collapses runs of blanks, so that expectations may be spaced freely.
std::string normalize(const std::string &text)
{
    std::string result;
    bool blank = false;
    for (char c : trim(text)) {
        if (c == ' ' || c == '\t') {
            blank = true;
            continue;
        }
        if (blank && !result.empty())
            result += ' ';
        blank = false;
        result += c;
    }
    return result;
}

int64_t parse_value(const std::string &text)
{
    std::string t = trim(text);
    bool negative = !t.empty() && t[0] == '-';
    if (negative)
        t = t.substr(1);
    size_t used = 0;
    bool hex = t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X');
    int64_t value = std::stoll(t, &used, hex ? 16 : 10);
    if (used != t.size())
        throw std::invalid_argument("bad number '" + text + "'");
    return negative ? -value : value;
}

int16_t as_word(int64_t value)
{
    return static_cast<int16_t>(static_cast<uint16_t>(value & 0xFFFF));
}

// "v" or "[v, v, ...]".
std::vector<int64_t> parse_values(const std::string &text)
{
    std::string t = trim(text);
    std::vector<int64_t> values;
    if (!t.empty() && t[0] == '[') {
        if (t.back() != ']')
            throw std::invalid_argument("unclosed list '" + text + "'");
        std::stringstream items(t.substr(1, t.size() - 2));
        std::string item;
        while (std::getline(items, item, ','))
            if (!trim(item).empty())
                values.push_back(parse_value(item));
    } else {
        values.push_back(parse_value(t));
    }
    return values;
}

// Whether `text` matches `pattern`, where `*` stands for any run of
// characters other than a blank.
bool glob_match(const char *pattern, const char *text)
{
    if (*pattern == '\0')
        return *text == '\0';
    if (*pattern == '*') {
        for (const char *rest = text;; rest++) {
            if (glob_match(pattern + 1, rest))
                return true;
            if (*rest == '\0' || *rest == ' ')
                return false;
        }
    }
    return *pattern == *text && glob_match(pattern + 1, text + 1);
}

// An expected message: `*` stands for any one token (e.g. a pc the spec
// leaves open); a node-specific error given without its text matches any text.
bool matches(const std::string &actual, const std::string &expected)
{
    std::string text = normalize(actual);
    if (expected.rfind("error node_specific", 0) == 0 && expected.find('"') == std::string::npos)
        text = text.substr(0, text.find(" \""));
    return glob_match(expected.c_str(), text.c_str());
}

// Splits "name[index] = values" (blanks optional) into its three parts.
bool split_indexed(const std::string &text,
                   std::string *name,
                   std::string *index,
                   std::string *values)
{
    size_t open = text.find('['), close = text.find(']'), equal = text.find('=');
    if (open == std::string::npos || close == std::string::npos || equal == std::string::npos ||
        !(open < close && close < equal))
        return false;
    *name = trim(text.substr(0, open));
    *index = trim(text.substr(open + 1, close - open - 1));
    *values = trim(text.substr(equal + 1));
    return trim(text.substr(close + 1, equal - close - 1)).empty();
}

std::vector<std::string> split_blanks(const std::string &text)
{
    std::istringstream in(text);
    std::vector<std::string> words;
    std::string word;
    while (in >> word)
        words.push_back(word);
    return words;
}

class ScriptRunner
{
  public:
    ScriptRunner(const std::string &name, const std::string &text)
      : name_(name)
      , text_(text)
    {
    }
    std::vector<std::string> run();

  private:
    void fail(unsigned line, const std::string &message)
    {
        failures_.push_back(name_ + ":" + std::to_string(line) + ": " + message);
    }
    void apply_setup(const Directive &directive);
    void apply_step(const Directive &directive);
    void expect(const Directive &directive);
    void run_vm()
    {
        vm_run(&harness_->vm, budget_);
    }
    std::optional<VmMessage> next_message();

    std::string name_;
    std::string text_;
    std::vector<std::string> failures_;
    test_support::VmSizes sizes_;
    uint16_t budget_ = DEFAULT_BUDGET;
    bool trace_states_ = false;
    std::vector<std::pair<uint16_t, int16_t>> initial_values_;
    std::unique_ptr<VmHarness> harness_;
    size_t consumed_ = 0; // messages of the log already matched
};

std::optional<VmMessage> ScriptRunner::next_message()
{
    const std::vector<VmMessage> &log = harness_->log;
    while (consumed_ < log.size()) {
        const VmMessage &message = log[consumed_++];
        if (message.kind != VmMessage::STATE || trace_states_)
            return message;
    }
    return std::nullopt;
}

void ScriptRunner::apply_setup(const Directive &d)
{
    if (d.keyword == "memory") {
        for (const std::string &pair : split_blanks(d.rest)) {
            size_t equal = pair.find('=');
            if (equal == std::string::npos)
                throw std::invalid_argument("expected: memory area=size ...");
            std::string key = pair.substr(0, equal);
            uint16_t value = static_cast<uint16_t>(parse_value(pair.substr(equal + 1)));
            if (key == "bytecode")
                sizes_.bytecode = value;
            else if (key == "variables")
                sizes_.variables = value;
            else if (key == "stack")
                sizes_.stack = value;
            else if (key == "args")
                sizes_.args = value;
            else
                fail(d.line, "unknown memory area " + key);
        }
    } else if (d.keyword == "set") {
        std::string name, index, values;
        if (!split_indexed(d.rest, &name, &index, &values) || name != "var")
            throw std::invalid_argument("expected: set var[A] = value(s)");
        uint16_t address = static_cast<uint16_t>(parse_value(index));
        for (int64_t value : parse_values(values))
            initial_values_.emplace_back(address++, as_word(value));
    } else if (d.keyword == "budget") {
        budget_ = static_cast<uint16_t>(parse_value(d.rest));
    } else if (d.keyword == "trace") {
        if (trim(d.rest) != "states")
            throw std::invalid_argument("expected: trace states");
        trace_states_ = true;
    }
}

void ScriptRunner::apply_step(const Directive &d)
{
    vm_state *vm = &harness_->vm;
    if (d.keyword == "run") {
        std::vector<std::string> words = split_blanks(d.rest);
        if (words.empty()) {
            run_vm();
        } else if (words.size() == 2 && words[0] == "event") {
            vm_setup_event(vm, static_cast<uint16_t>(parse_value(words[1])));
            run_vm();
        } else {
            throw std::invalid_argument("expected: run [event E]");
        }
    } else if (d.keyword == "receive") {
        size_t bracket = d.rest.find('[');
        std::vector<std::string> words = split_blanks(d.rest.substr(0, bracket));
        if (words.size() != 3 || words[1] != "source")
            throw std::invalid_argument("expected: receive E source S [payload]");
        std::vector<int16_t> payload;
        if (bracket != std::string::npos)
            for (int64_t value : parse_values(d.rest.substr(bracket)))
                payload.push_back(as_word(value));
        vm_receive_event(vm,
                         static_cast<uint16_t>(parse_value(words[0])),
                         static_cast<uint16_t>(parse_value(words[2])),
                         payload.data(),
                         static_cast<uint16_t>(payload.size()));
        run_vm();
    } else if (d.keyword == "reset") {
        vm_reset(vm);
        vm_command_run(vm);
        run_vm();
    } else if (d.keyword == "stop") {
        vm_command_stop(vm);
    } else if (d.keyword == "continue") {
        vm_command_run(vm);
        run_vm();
    } else if (d.keyword == "pause") {
        vm_command_pause(vm);
    } else if (d.keyword == "step") {
        vm_command_step(vm);
    } else if (d.keyword == "expect") {
        expect(d);
    }
}

void ScriptRunner::expect(const Directive &d)
{
    const vm_state &vm = harness_->vm;
    std::string rest = normalize(d.rest);
    std::string first = rest.substr(0, rest.find(' '));

    std::vector<std::string> words = split_blanks(rest);
    std::string name, index, values;
    if (split_indexed(rest, &name, &index, &values) && (name == "var" || name == "bytecode")) {
        bool is_variable = name == "var";
        uint16_t address = static_cast<uint16_t>(parse_value(index));
        uint16_t size = is_variable ? harness_->sizes().variables : harness_->sizes().bytecode;
        for (int64_t expected : parse_values(values)) {
            if (address >= size) {
                fail(d.line, "address " + std::to_string(address) + " outside the memory");
                return;
            }
            int16_t actual = is_variable ? harness_->variables()[address]
                                         : static_cast<int16_t>(harness_->bytecode()[address]);
            if (actual != as_word(expected))
                fail(d.line,
                     name + "[" + std::to_string(address) + "] is " + std::to_string(actual) +
                       ", expected " + std::to_string(as_word(expected)));
            address++;
        }
    } else if (words.size() == 2 && (first == "flags" || first == "pc" || first == "sp")) {
        int64_t actual = first == "flags" ? vm.flags : first == "pc" ? vm.pc : vm.sp;
        int64_t expected = parse_value(words[1]);
        if (actual != expected)
            fail(d.line,
                 first + " is " + std::to_string(actual) + ", expected " +
                   std::to_string(expected));
    } else if (rest == "no message") {
        if (std::optional<VmMessage> message = next_message())
            fail(d.line, "unexpected message: " + describe(*message));
    } else if (first == "emit" || first == "error" || first == "killed" || first == "state") {
        std::optional<VmMessage> message = next_message();
        if (!message)
            fail(d.line, "expected '" + rest + "', no message was sent");
        else if (!matches(describe(*message), rest))
            fail(d.line, "expected '" + rest + "', got '" + describe(*message) + "'");
    } else {
        throw std::invalid_argument("unknown expectation '" + rest + "'");
    }
}

std::vector<std::string> ScriptRunner::run()
{
    std::vector<Directive> setup;
    std::vector<Directive> steps;
    std::istringstream lines(text_);
    std::string line;
    unsigned number = 0;
    while (std::getline(lines, line)) {
        number++;
        std::string t = trim(line);
        if (t.empty() || t[0] != '#')
            continue;
        std::istringstream words(t.substr(1));
        std::string keyword;
        words >> keyword;
        // A misspelt keyword must not turn a check into nothing.
        if (std::find(std::begin(keywords), std::end(keywords), keyword) == std::end(keywords))
            return { name_ + ":" + std::to_string(number) + ": unknown directive '# " + keyword +
                     "' (prose comments start with ';')" };
        std::string rest;
        std::getline(words, rest);
        Directive directive{ number, keyword, rest };
        bool is_setup =
          keyword == "memory" || keyword == "set" || keyword == "budget" || keyword == "trace";
        (is_setup ? setup : steps).push_back(directive);
    }

    test_support::Program program;
    try {
        program = test_support::assemble(text_);
        for (const Directive &d : setup)
            apply_setup(d);
    } catch (const std::exception &error) {
        return { name_ + ": " + error.what() };
    }
    if (program.words.size() > sizes_.bytecode)
        return { name_ + ": the image does not fit the bytecode memory" };

    harness_ = std::make_unique<VmHarness>(sizes_);
    for (auto [address, value] : initial_values_)
        harness_->variables()[address] = value;
    vm_set_bytecode(
      &harness_->vm, 0, program.words.data(), static_cast<uint16_t>(program.words.size()));
    vm_command_run(&harness_->vm);
    run_vm();

    for (const Directive &d : steps) {
        try {
            apply_step(d);
        } catch (const std::exception &error) {
            fail(d.line, error.what());
        }
    }
    if (std::optional<VmMessage> message = next_message())
        fail(number, "message not expected by the script: " + describe(*message));
    if (!harness_->guards_intact())
        fail(number, "memory outside the VM's arrays was written");
    return failures_;
}

} // namespace

std::vector<std::string> run_program_script(const std::string &name, const std::string &text)
{
    return ScriptRunner(name, text).run();
}

} // namespace vm_tests
