// The upstream compiler corpus in tests/vectors/upstream-compiler: its
// manifest, scripts and memory dumps (format in that folder's README.md).

#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace compiler_tests
{

// Folder of the corpus, relative to the repository root (tests run there).
inline constexpr const char *corpus_folder = "tests/vectors/upstream-compiler";

// How a row is judged (README §3).
enum class CorpusMode { memcmp, event_memcmp, run_ok, exec_fail, comp_fail };

struct CorpusCase {
    std::string test_name;
    CorpusMode mode = CorpusMode::run_ok;
    std::string script; // file name in data/
    std::string dump;   // file name in data/, empty when the row has none
    std::string extra_args;
};

// The rows of manifest.tsv, header skipped. Throws std::runtime_error when
// the file is missing or a row is malformed.
std::vector<CorpusCase> read_corpus_manifest();

// The whole content of data/<file_name>. Throws when it cannot be read.
std::string read_corpus_file(const std::string &file_name);

// The integers of a dump file, every one of them (README §2.7: unlike
// upstream's reader, a last value without a final newline is kept).
std::vector<int> parse_dump(const std::string &text);

// A name usable in a GoogleTest parameter name: letters, digits and '_'.
std::string test_identifier(const std::string &name);

} // namespace compiler_tests
