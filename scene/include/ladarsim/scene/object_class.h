#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

namespace ladarsim::scene {

/// What an object is, for ground truth and for the detector's evaluation.
enum class ObjectClass : std::uint8_t { background, drone, bird, plane, building, terrain, tree, cloud };

std::string_view to_string(ObjectClass c);
/// Inverse of to_string; nullopt for an unknown name.
std::optional<ObjectClass> object_class_from_string(std::string_view name);

}  // namespace ladarsim::scene
