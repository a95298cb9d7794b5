#pragma once
// One quantity of a campaign spec as a distribution: a plain value (fixed), {"uniform": [lo, hi]},
// {"log_uniform": [lo, hi]} (numbers), or {"choice": [v, ...], "weights": [w, ...]} (any values).
// Reading checks that every value it can give is allowed where it goes, naming the spec's key.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladarsim/campaign/spec_fields.h"

namespace ladarsim::campaign {

class Distribution {
public:
    enum class Kind { fixed, uniform, log_uniform, choice };

    /// A number from `min` to `max` (`whole`: a whole number, drawn from lo to hi inclusive):
    /// fixed, uniform, log_uniform (lo above 0) or a choice among numbers. Throws InputError
    /// naming the key (and its part: "range_m.uniform") for a bound outside [min, max], lo above
    /// hi, a malformed or unknown part, or bad weights.
    static Distribution number(SpecFields& fields, const std::string& key, double min, double max, bool whole = false);
    /// number() with a fixed `fallback` when the key is absent.
    static Distribution number(SpecFields& fields, const std::string& key, double min, double max, double fallback,
                               bool whole = false);
    /// Any other value (a string, a boolean, an object): fixed, or a choice. `check(value, path)`
    /// throws InputError naming `path` (the key, or "key.choice[2]") for a value not allowed there.
    /// An object holding "choice" is the distribution; any other object is a fixed value.
    static Distribution value(SpecFields& fields, const std::string& key,
                              const std::function<void(const nlohmann::json& value, const std::string& path)>& check);
    static Distribution fixed(nlohmann::json value);

    Kind kind() const { return kind_; }
    /// The value at `u` in [0, 1): the same u always gives the same value.
    nlohmann::json draw(double u) const;
    /// Which of values() a fixed value or a choice gives at `u`.
    std::size_t draw_index(double u) const;
    /// draw() for a number.
    double draw_number(double u) const { return draw(u).get<double>(); }
    /// The values a draw can take: [lo, hi] for uniform and log_uniform; the choices (the fixed
    /// value alone) otherwise, with their probabilities.
    double lo() const { return lo_; }
    double hi() const { return hi_; }
    const std::vector<nlohmann::json>& values() const { return values_; }
    std::vector<double> probabilities() const;

private:
    Kind kind_ = Kind::fixed;
    bool whole_ = false;
    double lo_ = 0.0, hi_ = 0.0;
    std::vector<nlohmann::json> values_;
    std::vector<double> cumulative_;  ///< choice: running sums of the weights, the last their total
};

}  // namespace ladarsim::campaign
