#pragma once
// The MCS2 command tree (SmarAct MCS2 Programmer's Guide 1.0.6, 6.2.2-6.2.3): which keyword paths
// exist, each keyword's long and short form, the ones that take an index, the optional ones, and
// how a message's commands find their node:
// - "Only the exact long or the exact short form will be accepted", case-insensitive (6.2.2). The
//   short form is the upper-case letters of the guide's spelling (`CHANnel` -> `CHAN`).
// - A keyword written `#` in the guide takes an index (`:CHANnel#` -> `CHAN2`); the others take none.
// - A keyword in brackets may be left out (6.2.3): the root `[:PROPerty]` and leaves such as
//   `[:CURRent]`, `[:ENABled]`, `[:VALue]`.
// - A command that begins with ':' starts at the root; one that does not starts at the level of the
//   previous command of its message (the node above its last keyword), the first at the root.
// The paths are given as the guide prints them (`[:PROPerty]:CHANnel#:POSition[:CURRent]`, `*IDN`);
// the tree is built once from them. Resolution is linear in the command's keywords and the
// children it looks at.

#include "emulator/mcs2/message.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::mcs2 {

class CommandTree {
public:
    /// `paths`: one per command or property, as the guide prints them. std::invalid_argument for a
    /// path that is not one (an empty keyword, an unclosed bracket).
    explicit CommandTree(const std::vector<std::string_view>& paths);

    /// Where a command resolved to.
    struct Found {
        int node = -1;                     ///< the command's node (a path of the table)
        std::string name;                  ///< its path in long forms, `#` for an index: "PROPerty:CHANnel#:VELocity"
        std::vector<std::int64_t> indices; ///< the indices, in path order
    };

    /// Where a relative command of a message starts: the node above the previous command's last
    /// keyword, with the indices on the way there (`:CHAN0:MMOD 1;VEL 10` sets channel 0's velocity).
    struct Level {
        int node = 0;   ///< 0: the root
        std::vector<std::int64_t> indices;
    };

    /// The node of `c` (no syntax error), starting at `level` unless `c` is absolute or common;
    /// `level` becomes the level the next command of the message starts at. nullopt: no such
    /// command (SCPI -113, undefined header); `level` is then unchanged.
    std::optional<Found> resolve(const Command& c, Level& level) const;

    /// The path of node `node` as given (its name in long forms).
    const std::string& name_of(int node) const { return nodes_[static_cast<std::size_t>(node)].name; }
    std::size_t size() const { return nodes_.size(); }
    /// The node of the constructor's `paths[i]`.
    int node_of_path(std::size_t i) const { return path_nodes_[i]; }

private:
    struct Node {
        std::string long_form;    ///< upper-cased
        std::string short_form;   ///< upper-cased
        std::string spelling;     ///< as the guide writes it ("CHANnel")
        bool indexed = false;
        bool optional = false;
        bool command = false;     ///< a path of the table ends here
        int parent = -1;
        std::vector<int> children;
        std::string name;         ///< the path to here in long forms
    };

    int child(int parent, std::string_view spelling, bool indexed, bool optional);
    /// The child of `node` that keyword `k` names, looking through optional children (at most
    /// `depth` of them); -1: none.
    int match(int node, const Keyword& k, int depth) const;
    static bool matches(const Node& n, const Keyword& k);

    std::vector<Node> nodes_;   ///< nodes_[0]: the root
    std::vector<int> path_nodes_;   ///< per constructor path, its node
};

} // namespace rigsim::mcs2
