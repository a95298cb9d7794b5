#pragma once
// One JSON object of a campaign spec: JsonFields (typed, checked keys; unknown keys refused by
// name) with the object itself beside it, for values that may be of several types (a number or
// a distribution, a value or a choice).
#include <string>

#include <nlohmann/json.hpp>

#include "ladarsim/core/json_fields.h"

namespace ladarsim::campaign {

class SpecFields : public JsonFields {
public:
    SpecFields(const nlohmann::json& object, std::string file, std::string path)
        : JsonFields(object, std::move(file), std::move(path)), object_(object) {}

    /// The value of a required key, whatever its type; marks the key as used.
    const nlohmann::json& raw(const std::string& key);

private:
    const nlohmann::json& object_;
};

}  // namespace ladarsim::campaign
