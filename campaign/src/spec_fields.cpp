#include "ladarsim/campaign/spec_fields.h"

#include <limits>

namespace ladarsim::campaign {

const nlohmann::json& SpecFields::raw(const std::string& key) {
    if (!has(key)) fail(key, "required field is missing");
    const nlohmann::json& v = object_.at(key);
    // JsonFields marks a key used when it is read as its type.
    if (v.is_number()) number(key, -std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
    else if (v.is_boolean()) boolean(key, false);
    else if (v.is_string()) string(key);
    else if (v.is_array()) array(key);
    else if (v.is_object()) object(key);
    else fail(key, "expected a value, found null");
    return v;
}

}  // namespace ladarsim::campaign
