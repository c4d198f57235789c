// Lookups shared by the plugin registries (internal header): names in registration order,
// and finding by name with an error that lists the known names.
#pragma once
#include "radiosity/error.hpp"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

template <class T> std::vector<std::string> names_of(std::span<const T* const> all) {
    std::vector<std::string> names;
    for (const auto* item : all) names.emplace_back(item->name());
    return names;
}

// `what` names the kind of thing in the message: "unknown solver 'x' (use gs, jacobi)".
template <class T>
const T& find_named(std::span<const T* const> all, std::string_view name, std::string_view what) {
    std::string known;
    for (const auto* item : all) {
        if (item->name() == name) return *item;
        known += (known.empty() ? "" : ", ") + std::string(item->name());
    }
    throw InputError("unknown " + std::string(what) + " '" + std::string(name) + "' (use " + known +
                     ")");
}

} // namespace rad
