// Robustness: our compiler must end cleanly (bytecode or a compile error) on
// every prefix of every corpus script, the way a program looks while someone
// types it (the intent of upstream's simulate-* tests, corpus README §6).
// A crash ends this test program, the sanitizers catch memory errors, and a
// watchdog aborts with the culprit when one compilation hangs.

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <sstream>
#include <thread>

#include "bytecode_listing.hpp"
#include "corpus.hpp"
#include "error_wording.hpp"
#include "reference_oracle.hpp"
#include "require_reference.hpp"
#include "test_targets.hpp"
#include "tools/compiler/compiler.hpp"

namespace compiler_tests
{
namespace
{

// Far above the time of one compilation, even under the sanitizers.
constexpr std::chrono::seconds hang_limit(20);
constexpr std::chrono::milliseconds watchdog_period(100);
constexpr std::size_t reported_mismatches = 3;

// Aborts the program, naming the input, when one compilation takes too long.
class HangWatchdog
{
  public:
    HangWatchdog()
      : thread_([this] { watch(); })
    {
    }

    ~HangWatchdog()
    {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        thread_.join();
    }

    void begin(std::string what)
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        what_ = std::move(what);
        started_ = std::chrono::steady_clock::now();
        busy_ = true;
    }

    void end()
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        busy_ = false;
    }

  private:
    void watch()
    {
        std::unique_lock<std::mutex> lock(mutex_);
        while (!stopping_) {
            wake_.wait_for(lock, watchdog_period);
            if (busy_ && std::chrono::steady_clock::now() - started_ > hang_limit) {
                std::fprintf(stderr, "the compiler hangs on %s\n", what_.c_str());
                std::abort();
            }
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::string what_;
    std::chrono::steady_clock::time_point started_;
    bool busy_ = false;
    bool stopping_ = false;
    std::thread thread_; // last: starts once the members above exist
};

bool is_utf8_continuation(char byte)
{
    return (static_cast<unsigned char>(byte) & 0xC0) == 0x80;
}

TEST(PrefixTest, EveryPrefixOfEveryCorpusScriptEndsCleanly)
{
    const aseba::TargetDescription target = corpus_target(standard_natives());
    const aseba::CommonDefinitions definitions = corpus_definitions();
    HangWatchdog watchdog;
    std::size_t prefixes = 0, failures = 0;
    std::ostringstream details;
    for (const CorpusCase &row : read_corpus_manifest()) {
        const std::string source = read_corpus_file(row.script);
        // Byte by byte: a prefix may also cut a UTF-8 character in two.
        for (std::size_t length = 0; length <= source.size(); ++length, ++prefixes) {
            const std::string prefix = source.substr(0, length);
            const std::string name = row.script + " cut after " + std::to_string(length) + " bytes";
            std::string problem;
            watchdog.begin(name);
            try {
                const aseba::CompileResult result = aseba::compile(prefix, target, definitions);
                if (!result.ok && result.error.message.empty())
                    problem = "an error without a message";
            } catch (const std::exception &error) {
                problem = std::string("the compiler threw ") + error.what();
            }
            watchdog.end();
            if (!problem.empty() && ++failures <= reported_mismatches)
                details << name << ": " << problem << "\n";
        }
    }
    EXPECT_EQ(failures, 0u) << failures << " prefixes did not end cleanly; the first ones:\n"
                            << details.str();
    EXPECT_GT(prefixes, 10000u) << "the corpus should give over 10,000 prefixes";
}

// Some of the same prefixes against the reference: same verdict, same error
// line, identical bytecode. The reference is slow under the sanitizers, so
// only prefixes ending a line and every few characters are compared.
constexpr std::size_t compared_prefix_period = 4;
TEST(PrefixTest, EveryPrefixCompilesAsWithTheReference)
{
    REQUIRE_REFERENCE();
    const aseba::TargetDescription target = corpus_target(standard_natives());
    const aseba::CommonDefinitions definitions = corpus_definitions();
    std::size_t mismatches = 0, compared = 0;
    std::ostringstream details;
    for (const CorpusCase &row : read_corpus_manifest()) {
        const std::string source = read_corpus_file(row.script);
        for (std::size_t length = 0; length <= source.size(); ++length) {
            const bool line_end = length > 0 && source[length - 1] == '\n';
            if (length < source.size() && is_utf8_continuation(source[length]))
                continue;
            if (!line_end && length % compared_prefix_period != 0)
                continue;
            const std::string prefix = source.substr(0, length);
            const reference::ReferenceResult theirs =
              reference::compile_with_reference(prefix, target, definitions);
            if (theirs.assertion_failed)
                continue;
            ++compared;
            aseba::CompileResult ours;
            try {
                ours = aseba::compile(prefix, target, definitions);
            } catch (const std::exception &) {
                continue; // reported by the test above
            }
            std::string problem;
            if (ours.ok != theirs.ok)
                problem = ours.ok ? "only the reference rejects it" : "only ours rejects it";
            else if (ours.ok && ours.bytecode != theirs.bytecode)
                problem = "different bytecode";
            else if (!ours.ok && !theirs.error.has_position && ours.error.has_position)
                problem = is_positioned_version(theirs.error.message, ours.error.message)
                            ? ""
                            : "a positioned error of another kind";
            else if (!ours.ok &&
                     (ours.error.has_position != theirs.error.has_position ||
                      (theirs.error.has_position && ours.error.position.line != theirs.error.line)))
                problem = "errors at different lines";
            if (problem.empty())
                continue;
            if (++mismatches <= reported_mismatches) {
                details << "=== " << row.script << " cut after " << length << " bytes: " << problem
                        << "\n"
                        << prefix << "\n=== ours: "
                        << (ours.ok ? std::to_string(ours.bytecode.size()) + " words"
                                    : ours.error.message + " at line " +
                                        std::to_string(ours.error.position.line))
                        << "\n=== reference: " << reference::describe(theirs) << "\n";
                if (ours.ok && theirs.ok)
                    details << compare_listings(ours.bytecode, theirs.bytecode);
            }
        }
    }
    EXPECT_EQ(mismatches, 0u) << mismatches << " of " << compared
                              << " prefixes compile differently; the first ones:\n"
                              << details.str();
}

} // namespace
} // namespace compiler_tests
