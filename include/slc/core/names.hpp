/// @file
/// The names of an enumeration's values as options and files spell them, written once for the
/// library, the command line and Python: reading a name (InvalidInput naming the choices) and
/// writing one.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "slc/core/error.hpp"

namespace slc {

/// One value of an enumeration and its name.
template <class Enum>
struct Named {
    const char* name;
    Enum value;
};

/// The value named `name`; InvalidInput "WHAT must be one of a, b, c, got 'name'" for another.
template <class Enum>
Enum value_named(std::span<const Named<Enum>> names, std::string_view name, const char* what) {
    std::string choices;
    for (const Named<Enum>& n : names) {
        if (name == n.name) return n.value;
        choices += (choices.empty() ? "" : ", ") + std::string(n.name);
    }
    throw InvalidInput(std::string(what) + " must be one of " + choices + ", got '" +
                       std::string(name) + "'");
}

/// The name of `value` (the first listed for it).
template <class Enum>
const char* name_of(std::span<const Named<Enum>> names, Enum value) {
    for (const Named<Enum>& n : names)
        if (n.value == value) return n.name;
    throw InvalidInput("no name for the value " + std::to_string(static_cast<long long>(value)));
}

/// The names, in the order listed.
template <class Enum>
std::vector<std::string> names_of(std::span<const Named<Enum>> names) {
    std::vector<std::string> out;
    for (const Named<Enum>& n : names) out.emplace_back(n.name);
    return out;
}

}  // namespace slc
