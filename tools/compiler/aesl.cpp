// A small XML reader, just enough for .aesl files: elements, attributes,
// text, comments, CDATA, processing instructions, DOCTYPE and entities.

#include "aesl.hpp"

#include <cstdlib>
#include <map>
#include <stdexcept>

#include "lexer.hpp"

namespace aseba
{

namespace
{

constexpr long MAX_EVENT_WORDS = 258; // protocol.md §2
constexpr long INT16_MIN_VALUE = -32768;
constexpr long INT16_MAX_VALUE = 32767;
constexpr long NODE_ID_MAX = 0xFFFF;

struct XmlError : std::runtime_error {
    XmlError(unsigned where, const std::string &message)
      : std::runtime_error(message)
      , line(where)
    {
    }
    unsigned line;
};

class XmlReader
{
  public:
    explicit XmlReader(std::string_view document)
      : text(document)
    {
    }

    AeslProject read()
    {
        AeslProject project;
        skip_prolog();
        std::string root;
        std::map<std::string, std::string> attributes;
        bool empty = false;
        if (!read_start_tag(root, attributes, empty) || root != "network")
            throw XmlError(line, "the document element must be <network>");
        if (empty)
            return project;
        while (true) {
            skip_misc_text();
            if (at_end())
                throw XmlError(line, "missing </network>");
            if (starts_with("</")) {
                read_end_tag("network");
                return project;
            }
            std::string name;
            attributes.clear();
            unsigned element_line = line;
            if (!read_start_tag(name, attributes, empty))
                throw XmlError(line, "expected an element");
            if (name == "event")
                project.definitions.events.push_back(event(attributes, element_line));
            else if (name == "constant")
                project.definitions.constants.push_back(constant(attributes, element_line));
            else if (name == "node")
                project.nodes.push_back(node(attributes, empty));
            if (name != "node" && !empty)
                skip_content(name);
        }
    }

  private:
    std::string_view text;
    size_t position = 0;
    unsigned line = 1;

    bool at_end() const
    {
        return position >= text.size();
    }
    bool starts_with(std::string_view prefix) const
    {
        return text.substr(position, prefix.size()) == prefix;
    }
    void advance(size_t count = 1)
    {
        for (size_t i = 0; i < count && position < text.size(); ++i)
            if (text[position++] == '\n')
                ++line;
    }
    // Skips to just after `terminator`.
    void skip_past(std::string_view terminator)
    {
        size_t found = text.find(terminator, position);
        if (found == std::string_view::npos)
            throw XmlError(line, "unterminated markup, missing " + std::string(terminator));
        advance(found + terminator.size() - position);
    }
    void skip_spaces()
    {
        while (!at_end() && (text[position] == ' ' || text[position] == '\t' ||
                             text[position] == '\n' || text[position] == '\r'))
            advance();
    }
    // Whitespace, comments, processing instructions and stray text between elements.
    void skip_misc_text()
    {
        while (!at_end()) {
            if (starts_with("<!--"))
                skip_past("-->");
            else if (starts_with("<?"))
                skip_past("?>");
            else if (text[position] != '<')
                advance();
            else
                return;
        }
    }
    void skip_prolog()
    {
        while (!at_end()) {
            skip_spaces();
            if (starts_with("<?"))
                skip_past("?>");
            else if (starts_with("<!--"))
                skip_past("-->");
            else if (starts_with("<!DOCTYPE"))
                skip_past(">");
            else
                return;
        }
    }

    static bool is_name_character(char c)
    {
        return c != ' ' && c != '\t' && c != '\n' && c != '\r' && c != '/' && c != '>' &&
               c != '=' && c != '<';
    }

    std::string read_name()
    {
        size_t start = position;
        while (!at_end() && is_name_character(text[position]))
            advance();
        return std::string(text.substr(start, position - start));
    }

    bool read_start_tag(std::string &name,
                        std::map<std::string, std::string> &attributes,
                        bool &empty)
    {
        if (at_end() || text[position] != '<' || starts_with("</"))
            return false;
        advance();
        name = read_name();
        if (name.empty())
            throw XmlError(line, "bad element name");
        while (true) {
            skip_spaces();
            if (at_end())
                throw XmlError(line, "unterminated tag <" + name + ">");
            if (starts_with("/>")) {
                advance(2);
                empty = true;
                return true;
            }
            if (text[position] == '>') {
                advance();
                empty = false;
                return true;
            }
            std::string attribute = read_name();
            skip_spaces();
            if (attribute.empty() || at_end() || text[position] != '=')
                throw XmlError(line, "bad attribute in <" + name + ">");
            advance();
            skip_spaces();
            if (at_end() || (text[position] != '"' && text[position] != '\''))
                throw XmlError(line, "attribute values must be quoted");
            char quote = text[position];
            advance();
            size_t end = text.find(quote, position);
            if (end == std::string_view::npos)
                throw XmlError(line, "unterminated attribute value");
            attributes[attribute] = decode_entities(text.substr(position, end - position));
            advance(end + 1 - position);
        }
    }

    void read_end_tag(const std::string &name)
    {
        advance(2);
        std::string closing = read_name();
        skip_spaces();
        if (closing != name || at_end() || text[position] != '>')
            throw XmlError(line, "expected </" + name + ">");
        advance();
    }

    // Skips everything up to and including the end tag of `name`.
    void skip_content(const std::string &name)
    {
        std::string ignored;
        collect_content(name, ignored, false);
    }

    // Reads the content of element `name` up to its end tag; direct text
    // children are appended to `collected` when `keep_text`.
    void collect_content(const std::string &name, std::string &collected, bool keep_text)
    {
        while (true) {
            if (at_end())
                throw XmlError(line, "missing </" + name + ">");
            if (starts_with("<!--")) {
                skip_past("-->");
            } else if (starts_with("<![CDATA[")) {
                advance(9);
                size_t end = text.find("]]>", position);
                if (end == std::string_view::npos)
                    throw XmlError(line, "unterminated CDATA section");
                if (keep_text)
                    collected += text.substr(position, end - position);
                advance(end + 3 - position);
            } else if (starts_with("<?")) {
                skip_past("?>");
            } else if (starts_with("</")) {
                read_end_tag(name);
                return;
            } else if (text[position] == '<') {
                std::string child;
                std::map<std::string, std::string> attributes;
                bool empty = false;
                read_start_tag(child, attributes, empty);
                if (!empty)
                    skip_content(child);
            } else {
                size_t end = text.find('<', position);
                if (end == std::string_view::npos)
                    end = text.size();
                if (keep_text)
                    collected += decode_entities(text.substr(position, end - position));
                advance(end - position);
            }
        }
    }

    std::string decode_entities(std::string_view raw) const
    {
        std::string result;
        size_t i = 0;
        while (i < raw.size()) {
            if (raw[i] != '&') {
                result += raw[i++];
                continue;
            }
            size_t end = raw.find(';', i);
            if (end == std::string_view::npos)
                throw XmlError(line, "unterminated entity");
            std::string entity(raw.substr(i + 1, end - i - 1));
            if (entity == "lt")
                result += '<';
            else if (entity == "gt")
                result += '>';
            else if (entity == "amp")
                result += '&';
            else if (entity == "quot")
                result += '"';
            else if (entity == "apos")
                result += '\'';
            else if (entity.size() > 1 && entity[0] == '#') {
                bool hex = entity[1] == 'x';
                char *stop = nullptr;
                unsigned long code =
                  std::strtoul(entity.c_str() + (hex ? 2 : 1), &stop, hex ? 16 : 10);
                if (*stop != '\0' || code == 0 || code > 0x10FFFF)
                    throw XmlError(line, "bad character reference &" + entity + ";");
                result += encode_utf8(std::u32string(1, static_cast<char32_t>(code)));
            } else {
                throw XmlError(line, "unknown entity &" + entity + ";");
            }
            i = end + 1;
        }
        return result;
    }

    static long number(const std::map<std::string, std::string> &attributes,
                       const char *key,
                       long low,
                       long high,
                       unsigned where,
                       const char *element)
    {
        auto found = attributes.find(key);
        if (found == attributes.end())
            throw XmlError(where, std::string("<") + element + "> needs a " + key + " attribute");
        char *stop = nullptr;
        long value = std::strtol(found->second.c_str(), &stop, 10);
        if (found->second.empty() || *stop != '\0' || value < low || value > high)
            throw XmlError(where,
                           std::string("<") + element + "> " + key + " must be a number in [" +
                             std::to_string(low) + ", " + std::to_string(high) + "]");
        return value;
    }

    static std::string name_of(const std::map<std::string, std::string> &attributes,
                               unsigned where,
                               const char *element)
    {
        auto found = attributes.find("name");
        if (found == attributes.end() || found->second.empty())
            throw XmlError(where, std::string("<") + element + "> needs a name attribute");
        return found->second;
    }

    static GlobalEvent event(const std::map<std::string, std::string> &attributes, unsigned where)
    {
        return { name_of(attributes, where, "event"),
                 static_cast<uint16_t>(
                   number(attributes, "size", 0, MAX_EVENT_WORDS, where, "event")) };
    }

    static Constant constant(const std::map<std::string, std::string> &attributes, unsigned where)
    {
        return { name_of(attributes, where, "constant"),
                 static_cast<int16_t>(number(
                   attributes, "value", INT16_MIN_VALUE, INT16_MAX_VALUE, where, "constant")) };
    }

    AeslNode node(const std::map<std::string, std::string> &attributes, bool empty)
    {
        AeslNode result;
        result.name = name_of(attributes, line, "node");
        if (attributes.count("nodeId"))
            result.node_id =
              static_cast<uint16_t>(number(attributes, "nodeId", 0, NODE_ID_MAX, line, "node"));
        result.first_line = line;
        size_t line_start = text.rfind('\n', position == 0 ? 0 : position - 1);
        result.first_column = static_cast<unsigned>(
          line_start == std::string_view::npos ? position : position - line_start - 1);
        if (!empty)
            collect_content("node", result.source, true);
        return result;
    }
};

} // namespace

AeslReadResult read_aesl(std::string_view text)
{
    AeslReadResult result;
    try {
        result.project = XmlReader(text).read();
        result.ok = true;
    } catch (const XmlError &error) {
        result.error_line = error.line;
        result.error = error.what();
    }
    return result;
}

} // namespace aseba
