#include "emulator/mcs2/command_tree.hpp"

#include <cctype>
#include <stdexcept>

namespace rigsim::mcs2 {

namespace {

/// The root of the common commands (`*IDN`): node 1.
constexpr int kCommonRoot = 1;
/// Optional keywords a keyword may be looked for through (`[:PROPerty]` then the keyword).
constexpr int kOptionalDepth = 2;

std::string upper(std::string_view s)
{
    std::string out(s);
    for (auto& c : out)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

bool same(std::string_view a, std::string_view b)
{
    if (a.size() != b.size())
        return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::toupper(static_cast<unsigned char>(a[i])) != std::toupper(static_cast<unsigned char>(b[i])))
            return false;
    return true;
}

} // namespace

CommandTree::CommandTree(const std::vector<std::string_view>& paths)
{
    nodes_.push_back(Node{});                      // the root
    nodes_.push_back(Node{"*", "*", "*", false, false, false, 0, {}, "*"});   // the common commands
    for (const auto path : paths) {
        const auto bad = [&](const char* why) {
            throw std::invalid_argument("command tree path \"" + std::string(path) + "\": " + why);
        };
        if (!path.empty() && path[0] == '*') {
            if (path.size() < 2)
                bad("an empty common command");
            const int node = child(kCommonRoot, path.substr(1), false, false);
            nodes_[static_cast<std::size_t>(node)].command = true;
            path_nodes_.push_back(node);
            continue;
        }
        int node = 0;
        std::size_t i = 0;
        while (i < path.size()) {
            bool optional = false;
            std::string_view segment;
            if (path[i] == '[') {
                const auto close = path.find(']', i);
                if (close == std::string_view::npos)
                    bad("an unclosed bracket");
                segment = path.substr(i + 1, close - i - 1);
                optional = true;
                i = close + 1;
            } else {
                const auto end = path.find_first_of(":[", i + 1);
                segment = path.substr(i, (end == std::string_view::npos ? path.size() : end) - i);
                i += segment.size();
            }
            if (!segment.empty() && segment[0] == ':')
                segment.remove_prefix(1);
            const bool indexed = !segment.empty() && segment.back() == '#';
            if (indexed)
                segment.remove_suffix(1);
            if (segment.empty())
                bad("an empty keyword");
            node = child(node, segment, indexed, optional);
        }
        if (node == 0)
            bad("no keyword");
        nodes_[static_cast<std::size_t>(node)].command = true;
        path_nodes_.push_back(node);
    }
}

int CommandTree::child(int parent, std::string_view spelling, bool indexed, bool optional)
{
    for (const int c : nodes_[static_cast<std::size_t>(parent)].children) {
        const auto& n = nodes_[static_cast<std::size_t>(c)];
        if (n.spelling == spelling && n.indexed == indexed) {
            nodes_[static_cast<std::size_t>(c)].optional = n.optional || optional;
            return c;
        }
    }
    Node n;
    n.spelling = std::string(spelling);
    n.long_form = upper(spelling);
    for (const char ch : spelling)
        if (std::isupper(static_cast<unsigned char>(ch)) || std::isdigit(static_cast<unsigned char>(ch)))
            n.short_form += ch;
    n.indexed = indexed;
    n.optional = optional;
    n.parent = parent;
    const auto& p = nodes_[static_cast<std::size_t>(parent)];
    n.name = (parent <= kCommonRoot ? (parent == kCommonRoot ? "*" : "") : p.name + ":") + n.spelling + (indexed ? "#" : "");
    nodes_.push_back(std::move(n));
    const int id = static_cast<int>(nodes_.size() - 1);
    nodes_[static_cast<std::size_t>(parent)].children.push_back(id);
    return id;
}

bool CommandTree::matches(const Node& n, const Keyword& k)
{
    return (same(k.name, n.long_form) || same(k.name, n.short_form)) && n.indexed == k.index.has_value();
}

int CommandTree::match(int node, const Keyword& k, int depth) const
{
    const auto& n = nodes_[static_cast<std::size_t>(node)];
    for (const int c : n.children)
        if (matches(nodes_[static_cast<std::size_t>(c)], k))
            return c;
    if (depth == 0)
        return -1;
    for (const int c : n.children)
        if (nodes_[static_cast<std::size_t>(c)].optional && !nodes_[static_cast<std::size_t>(c)].indexed)
            if (const int found = match(c, k, depth - 1); found >= 0)
                return found;
    return -1;
}

std::optional<CommandTree::Found> CommandTree::resolve(const Command& c, Level& level) const
{
    if (c.error != ScpiError::None || c.path.empty())
        return std::nullopt;
    Found f;
    int node = 0;
    if (c.common)
        node = kCommonRoot;
    else if (!c.absolute) {
        node = level.node;
        f.indices = level.indices;
    }
    std::vector<std::int64_t> above;   // the indices up to the last keyword's parent
    for (const auto& k : c.path) {
        const int next = match(node, k, kOptionalDepth);
        if (next < 0)
            return std::nullopt;
        above = f.indices;
        if (k.index)
            f.indices.push_back(*k.index);
        node = next;
    }
    const int last = node;
    // A path may end above its command: its optional keywords complete it (`:POS?` is `:POS:CURR?`).
    for (int hops = 0; !nodes_[static_cast<std::size_t>(node)].command; ++hops) {
        int next = -1;
        for (const int ch : nodes_[static_cast<std::size_t>(node)].children)
            if (nodes_[static_cast<std::size_t>(ch)].optional && !nodes_[static_cast<std::size_t>(ch)].indexed) {
                next = ch;
                break;
            }
        if (next < 0 || hops == kOptionalDepth)
            return std::nullopt;
        node = next;
    }
    f.node = node;
    f.name = nodes_[static_cast<std::size_t>(node)].name;
    if (!c.common) {
        level.node = nodes_[static_cast<std::size_t>(last)].parent;
        level.indices = std::move(above);
    }
    return f;
}

} // namespace rigsim::mcs2
