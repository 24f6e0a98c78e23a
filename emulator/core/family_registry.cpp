#include "emulator/core/family_registry.hpp"

#include <stdexcept>
#include <utility>

namespace rigsim {

void FamilyRegistry::add(Family family)
{
    if (find(family.name))
        throw std::invalid_argument("protocol family \"" + family.name + "\" registered twice");
    families_.push_back(std::move(family));
}

const Family* FamilyRegistry::find(std::string_view name) const
{
    for (const auto& f : families_)
        if (f.name == name)
            return &f;
    return nullptr;
}

std::string FamilyRegistry::quoted_names() const
{
    std::string names;
    for (std::size_t i = 0; i < families_.size(); ++i) {
        if (i > 0)
            names += i + 1 == families_.size() ? " or " : ", ";
        names += "\"" + families_[i].name + "\"";
    }
    return names;
}

} // namespace rigsim
