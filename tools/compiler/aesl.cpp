// .aesl projects over pugixml: its parser does not recurse, so no nesting
// depth can exhaust the stack, and it reports where a document is malformed.

#include "aesl.hpp"

#include <algorithm>
#include <charconv>
#include <sstream>
#include <stdexcept>

#include <pugixml.hpp>

namespace aseba
{

namespace
{

constexpr long INT16_MIN_VALUE = -32768;
constexpr long INT16_MAX_VALUE = 32767;
constexpr long NODE_ID_MAX = 0xFFFF;
// Entities and character references decoded, line ends normalised as XML
// says, DOCTYPE and comments skipped: what Studio's Qt reader does.
constexpr unsigned PARSE_OPTIONS = pugi::parse_default;

struct AeslError : std::runtime_error {
    AeslError(unsigned where, const std::string &message)
      : std::runtime_error(message)
      , line(where)
    {
    }
    unsigned line;
};

// Line (from 1) and column (from 0) of a byte of the text.
struct Position {
    unsigned line = 1;
    unsigned column = 0;
};

// Where each line of a text starts, found once, so that placing every node
// of a project costs a binary search, not a scan of the text before it.
class LineStarts
{
  public:
    explicit LineStarts(std::string_view text)
    {
        starts_.push_back(0);
        for (size_t i = 0; i < text.size(); ++i)
            if (text[i] == '\n')
                starts_.push_back(i + 1);
        size_ = text.size();
    }

    Position position_of(ptrdiff_t offset) const
    {
        size_t at = std::min(size_, size_t(std::max<ptrdiff_t>(offset, 0)));
        auto line = std::upper_bound(starts_.begin(), starts_.end(), at) - 1;
        return { unsigned(line - starts_.begin() + 1), unsigned(at - *line) };
    }

  private:
    std::vector<size_t> starts_;
    size_t size_ = 0;
};

class ProjectReader
{
  public:
    explicit ProjectReader(std::string_view text)
      : text_(text)
      , lines_(text)
    {
    }

    AeslProject read()
    {
        pugi::xml_document document;
        pugi::xml_parse_result parsed =
          document.load_buffer(text_.data(), text_.size(), PARSE_OPTIONS, pugi::encoding_utf8);
        if (!parsed)
            throw AeslError(lines_.position_of(parsed.offset).line,
                            std::string("not well-formed XML: ") + parsed.description());
        pugi::xml_node root = document.document_element();
        if (!root || std::string_view(root.name()) != "network")
            throw AeslError(root ? line_of(root) : 1, "the document element must be <network>");
        for (pugi::xml_node other = root.next_sibling(); other; other = other.next_sibling())
            if (other.type() == pugi::node_element)
                throw AeslError(line_of(other), "only one document element is allowed");
        AeslProject project;
        for (pugi::xml_node element : root.children()) {
            if (element.type() != pugi::node_element)
                continue;
            std::string_view name = element.name();
            if (name == "event")
                project.definitions.events.push_back(event(element));
            else if (name == "constant")
                project.definitions.constants.push_back(constant(element));
            else if (name == "keywords")
                project.show_keywords =
                  std::string_view(element.attribute("flag").value()) != "false";
            else if (name == "node")
                project.nodes.push_back(node(element));
            // Other elements are ignored, as by every reader (aesl.md §2).
        }
        return project;
    }

  private:
    unsigned line_of(pugi::xml_node node) const
    {
        return lines_.position_of(node.offset_debug()).line;
    }

    long number(pugi::xml_node element, const char *key, long low, long high) const
    {
        pugi::xml_attribute attribute = element.attribute(key);
        std::string where = std::string("<") + element.name() + "> ";
        if (!attribute)
            throw AeslError(line_of(element), where + "needs a " + key + " attribute");
        std::string_view text = attribute.value();
        long value = 0;
        auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
            value < low || value > high)
            throw AeslError(line_of(element),
                            where + key + " must be a number in [" + std::to_string(low) + ", " +
                              std::to_string(high) + "], not '" + std::string(text) + "'");
        return value;
    }

    std::string name_of(pugi::xml_node element) const
    {
        std::string name = element.attribute("name").value();
        if (name.empty())
            throw AeslError(line_of(element),
                            std::string("<") + element.name() + "> needs a name attribute");
        return name;
    }

    GlobalEvent event(pugi::xml_node element) const
    {
        return { name_of(element),
                 static_cast<uint16_t>(number(element, "size", 0, MAX_EVENT_WORDS)) };
    }

    Constant constant(pugi::xml_node element) const
    {
        return { name_of(element),
                 static_cast<int16_t>(number(element, "value", INT16_MIN_VALUE, INT16_MAX_VALUE)) };
    }

    AeslNode node(pugi::xml_node element) const
    {
        AeslNode result;
        result.name = name_of(element);
        if (element.attribute("nodeId"))
            result.node_id = static_cast<uint16_t>(number(element, "nodeId", 0, NODE_ID_MAX));
        // The program is the node's direct text (Studio joins every piece);
        // the position is where its first piece starts in the file.
        bool positioned = false;
        for (pugi::xml_node child : element.children()) {
            if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
                if (!positioned) {
                    Position start = lines_.position_of(child.offset_debug());
                    result.first_line = start.line;
                    result.first_column = start.column;
                    positioned = true;
                }
                result.source += child.value();
            } else if (child.type() == pugi::node_element &&
                       std::string_view(child.name()) == "toolsPlugins") {
                std::ostringstream plugins;
                child.print(plugins, "", pugi::format_raw);
                result.tools_plugins = plugins.str();
            }
        }
        if (!positioned)
            result.first_line = line_of(element);
        return result;
    }

    std::string_view text_;
    LineStarts lines_;
};

// Every element on a line of its own, two blank lines and a comment before
// each group, as Studio lays files out.
void open_group(pugi::xml_node network, const std::string &comment)
{
    network.append_child(pugi::node_pcdata).set_value("\n\n");
    network.append_child(pugi::node_comment).set_value(comment.c_str());
    network.append_child(pugi::node_pcdata).set_value("\n");
}

void require_name(const std::string &name, const char *what)
{
    if (name.empty())
        throw std::invalid_argument(std::string("an .aesl ") + what + " needs a name");
}

} // namespace

AeslReadResult read_aesl(std::string_view text)
{
    AeslReadResult result;
    try {
        result.project = ProjectReader(text).read();
        result.ok = true;
    } catch (const AeslError &error) {
        result.error_line = error.line;
        result.error = error.what();
    }
    return result;
}

std::string write_aesl(const AeslProject &project)
{
    pugi::xml_document document;
    document.append_child(pugi::node_doctype).set_value("aesl-source");
    document.append_child(pugi::node_pcdata).set_value("\n");
    pugi::xml_node network = document.append_child("network");
    network.append_child(pugi::node_pcdata).set_value("\n");

    open_group(network, "list of global events");
    for (const GlobalEvent &event : project.definitions.events) {
        require_name(event.name, "event");
        if (event.size > MAX_EVENT_WORDS)
            throw std::invalid_argument("event " + event.name + " has " +
                                        std::to_string(event.size) + " words of arguments, " +
                                        "more than the protocol's " +
                                        std::to_string(MAX_EVENT_WORDS));
        pugi::xml_node element = network.append_child("event");
        element.append_attribute("size").set_value(unsigned(event.size));
        element.append_attribute("name").set_value(event.name.c_str());
        network.append_child(pugi::node_pcdata).set_value("\n");
    }
    open_group(network, "list of constants");
    for (const Constant &constant : project.definitions.constants) {
        require_name(constant.name, "constant");
        pugi::xml_node element = network.append_child("constant");
        element.append_attribute("value").set_value(int(constant.value));
        element.append_attribute("name").set_value(constant.name.c_str());
        network.append_child(pugi::node_pcdata).set_value("\n");
    }
    open_group(network, "show keywords state");
    network.append_child("keywords").append_attribute("flag").set_value(project.show_keywords);
    network.append_child(pugi::node_pcdata).set_value("\n");

    for (const AeslNode &node : project.nodes) {
        require_name(node.name, "node");
        open_group(network, "node " + node.name);
        pugi::xml_node element = network.append_child("node");
        element.append_attribute("nodeId").set_value(unsigned(node.node_id));
        element.append_attribute("name").set_value(node.name.c_str());
        // One text child, first (asebamassloader reads only the first child).
        if (!node.source.empty())
            element.append_child(pugi::node_pcdata).set_value(node.source.c_str());
        if (!node.tools_plugins.empty()) {
            pugi::xml_document plugins;
            if (!plugins.load_buffer(node.tools_plugins.data(), node.tools_plugins.size()) ||
                std::string_view(plugins.document_element().name()) != "toolsPlugins")
                throw std::invalid_argument("the plugin state of node " + node.name +
                                            " is not a <toolsPlugins> element");
            element.append_copy(plugins.document_element());
        }
        network.append_child(pugi::node_pcdata).set_value("\n");
    }
    network.append_child(pugi::node_pcdata).set_value("\n\n");
    document.append_child(pugi::node_pcdata).set_value("\n");

    std::ostringstream out;
    document.save(out, "", pugi::format_raw | pugi::format_no_declaration, pugi::encoding_utf8);
    return out.str();
}

} // namespace aseba
