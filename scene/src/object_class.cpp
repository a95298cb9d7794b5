#include "ladarsim/scene/object_class.h"

#include <array>
#include <utility>

namespace ladarsim::scene {

namespace {
constexpr std::array<std::pair<ObjectClass, std::string_view>, 8> kNames{{
    {ObjectClass::background, "background"},
    {ObjectClass::drone, "drone"},
    {ObjectClass::bird, "bird"},
    {ObjectClass::plane, "plane"},
    {ObjectClass::building, "building"},
    {ObjectClass::terrain, "terrain"},
    {ObjectClass::tree, "tree"},
    {ObjectClass::cloud, "cloud"},
}};
}  // namespace

std::string_view to_string(ObjectClass c) {
    for (const auto& [cls, name] : kNames) {
        if (cls == c) return name;
    }
    return "unknown";
}

std::optional<ObjectClass> object_class_from_string(std::string_view name) {
    for (const auto& [cls, n] : kNames) {
        if (n == name) return cls;
    }
    return std::nullopt;
}

}  // namespace ladarsim::scene
