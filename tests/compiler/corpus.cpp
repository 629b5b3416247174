// Reads the corpus files. Kept apart from the runners so that the corpus and
// prefix tests read the manifest the same way.

#include "corpus.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace compiler_tests
{

namespace
{

constexpr std::size_t manifest_columns = 5;

CorpusMode parse_mode(const std::string &mode)
{
    if (mode == "memcmp")
        return CorpusMode::memcmp;
    if (mode == "event_memcmp")
        return CorpusMode::event_memcmp;
    if (mode == "run_ok")
        return CorpusMode::run_ok;
    if (mode == "exec_fail")
        return CorpusMode::exec_fail;
    if (mode == "comp_fail")
        return CorpusMode::comp_fail;
    throw std::runtime_error("corpus manifest: unknown mode " + mode);
}

std::string read_whole_file(const std::string &path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
        throw std::runtime_error("cannot read " + path +
                                 " (tests must run from the repository root)");
    std::ostringstream content;
    content << file.rdbuf();
    return content.str();
}

std::vector<std::string> split_tabs(const std::string &line)
{
    std::vector<std::string> fields;
    std::string field;
    std::istringstream stream(line);
    while (std::getline(stream, field, '\t'))
        fields.push_back(field);
    return fields;
}

} // namespace

std::vector<CorpusCase> read_corpus_manifest()
{
    std::istringstream manifest(read_whole_file(std::string(corpus_folder) + "/manifest.tsv"));
    std::vector<CorpusCase> cases;
    std::string line;
    bool header = true;
    while (std::getline(manifest, line)) {
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        if (header || line.empty()) {
            header = false;
            continue;
        }
        const std::vector<std::string> fields = split_tabs(line);
        if (fields.size() != manifest_columns)
            throw std::runtime_error("corpus manifest: malformed row: " + line);
        CorpusCase row;
        row.test_name = fields[0];
        row.mode = parse_mode(fields[1]);
        row.script = fields[2];
        row.dump = fields[3] == "-" ? "" : fields[3];
        row.extra_args = fields[4] == "-" ? "" : fields[4];
        cases.push_back(row);
    }
    return cases;
}

std::string read_corpus_file(const std::string &file_name)
{
    return read_whole_file(std::string(corpus_folder) + "/data/" + file_name);
}

std::vector<int> parse_dump(const std::string &text)
{
    std::istringstream stream(text);
    std::vector<int> values;
    int value = 0;
    while (stream >> value)
        values.push_back(value);
    if (!stream.eof())
        throw std::runtime_error("dump file holds something that is not an integer");
    return values;
}

std::string test_identifier(const std::string &name)
{
    std::string identifier;
    for (char c : name) {
        const bool keep =
          (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        identifier += keep ? c : '_';
    }
    return identifier;
}

} // namespace compiler_tests
