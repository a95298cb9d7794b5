#include "ladarsim/campaign/distribution.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "ladarsim/core/input_error.h"

namespace ladarsim::campaign {

namespace {

/// The shortest text that reads back as `x` ("300", not "300.0").
std::string number_text(double x) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, x).ptr;
    return std::string(text, end);
}

/// The weights of a choice of `n` values: all 1 without "weights".
std::vector<double> cumulative_weights(SpecFields& d, std::size_t n) {
    std::vector<double> cumulative;
    double total = 0.0;
    if (!d.has("weights")) {
        for (std::size_t i = 0; i < n; ++i) cumulative.push_back(total += 1.0);
        return cumulative;
    }
    const nlohmann::json& weights = d.array("weights");
    if (weights.size() != n)
        d.fail("weights", "has " + std::to_string(weights.size()) + " weights for " + std::to_string(n) + " choices");
    for (std::size_t i = 0; i < n; ++i) {
        if (!weights[i].is_number() || !(weights[i].get<double>() >= 0.0) || !std::isfinite(weights[i].get<double>()))
            d.fail("weights", "weight " + std::to_string(i) + " is " + weights[i].dump() + ", not a number of at least 0");
        cumulative.push_back(total += weights[i].get<double>());
    }
    if (!(total > 0.0)) d.fail("weights", "are all 0: nothing can be drawn");
    return cumulative;
}

/// The choices of `d` ("choice", "weights"), each passed to `check` with its path.
void read_choice(SpecFields& d, std::vector<nlohmann::json>& values, std::vector<double>& cumulative,
                 const std::function<void(const nlohmann::json&, const std::string&)>& check) {
    const nlohmann::json& choices = d.array("choice");
    if (choices.empty()) d.fail("choice", "is empty: nothing can be drawn");
    for (std::size_t i = 0; i < choices.size(); ++i) {
        check(choices[i], d.path_of("choice") + "[" + std::to_string(i) + "]");
        values.push_back(choices[i]);
    }
    cumulative = cumulative_weights(d, choices.size());
}

}  // namespace

Distribution Distribution::fixed(nlohmann::json value) {
    Distribution d;
    d.values_.push_back(std::move(value));
    d.cumulative_ = {1.0};
    if (d.values_[0].is_number()) d.lo_ = d.hi_ = d.values_[0].get<double>();
    return d;
}

Distribution Distribution::number(SpecFields& fields, const std::string& key, double min, double max, double fallback,
                                  bool whole) {
    return fields.has(key) ? number(fields, key, min, max, whole) : fixed(whole ? nlohmann::json(std::llround(fallback))
                                                                                 : nlohmann::json(fallback));
}

Distribution Distribution::number(SpecFields& fields, const std::string& key, double min, double max, bool whole) {
    const std::string allowed = whole ? "a whole number from " + number_text(min) + " to " + number_text(max)
                                      : "a number from " + number_text(min) + " to " + number_text(max);
    const auto check = [&](const nlohmann::json& v, const std::string& path) {
        const bool ok = v.is_number() && v.get<double>() >= min && v.get<double>() <= max &&
                        (!whole || v.is_number_integer());
        if (!ok) throw InputError(fields.file(), path, v.dump() + " is not " + allowed);
    };
    const nlohmann::json& v = fields.raw(key);
    if (!v.is_object()) {
        check(v, fields.path_of(key));
        return fixed(v);
    }
    Distribution d;
    d.whole_ = whole;
    SpecFields parts(v, fields.file(), fields.path_of(key));
    const int kinds = parts.has("uniform") + parts.has("log_uniform") + parts.has("choice");
    if (kinds != 1)
        throw InputError(fields.file(), fields.path_of(key),
                         "give a number or one of {\"uniform\": [lo, hi]}, {\"log_uniform\": [lo, hi]}, {\"choice\": [...]}");
    if (parts.has("choice")) {
        d.kind_ = Kind::choice;
        read_choice(parts, d.values_, d.cumulative_, check);
        d.lo_ = d.hi_ = d.values_[0].get<double>();
        for (const auto& x : d.values_) d.lo_ = std::min(d.lo_, x.get<double>()), d.hi_ = std::max(d.hi_, x.get<double>());
    } else {
        const std::string part = parts.has("uniform") ? "uniform" : "log_uniform";
        d.kind_ = part == "uniform" ? Kind::uniform : Kind::log_uniform;
        const nlohmann::json& bounds = parts.array(part);
        const std::string path = parts.path_of(part);
        if (bounds.size() != 2) throw InputError(fields.file(), path, "expected [lo, hi]");
        check(bounds[0], path + "[0]");
        check(bounds[1], path + "[1]");
        d.lo_ = bounds[0].get<double>();
        d.hi_ = bounds[1].get<double>();
        if (d.lo_ > d.hi_)
            throw InputError(fields.file(), path, "lo " + number_text(d.lo_) + " is above hi " + number_text(d.hi_));
        if (d.kind_ == Kind::log_uniform && !(d.lo_ > 0.0))
            throw InputError(fields.file(), path, "lo must be above 0 for a log-uniform distribution");
    }
    parts.reject_unknown_keys();
    return d;
}

Distribution Distribution::value(SpecFields& fields, const std::string& key,
                                 const std::function<void(const nlohmann::json&, const std::string&)>& check) {
    const nlohmann::json& v = fields.raw(key);
    if (!v.is_object() || !v.contains("choice")) {
        check(v, fields.path_of(key));
        return fixed(v);
    }
    Distribution d;
    d.kind_ = Kind::choice;
    SpecFields parts(v, fields.file(), fields.path_of(key));
    read_choice(parts, d.values_, d.cumulative_, check);
    parts.reject_unknown_keys();
    return d;
}

nlohmann::json Distribution::draw(double u) const {
    switch (kind_) {
        case Kind::fixed:
            return values_[0];
        case Kind::uniform:
            if (whole_) return static_cast<long long>(std::min(hi_, std::floor(lo_ + u * (hi_ - lo_ + 1.0))));
            return std::clamp(lo_ + u * (hi_ - lo_), lo_, hi_);
        case Kind::log_uniform: {
            const double x = std::exp(std::log(lo_) + u * (std::log(hi_) - std::log(lo_)));
            if (whole_) return static_cast<long long>(std::clamp(std::round(x), lo_, hi_));
            return std::clamp(x, lo_, hi_);
        }
        case Kind::choice:
            return values_[draw_index(u)];
    }
    return values_.at(0);
}

std::size_t Distribution::draw_index(double u) const {
    const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), u * cumulative_.back());
    return std::min(static_cast<std::size_t>(it - cumulative_.begin()), values_.size() - 1);
}

std::vector<double> Distribution::probabilities() const {
    std::vector<double> p;
    double previous = 0.0;
    for (const double c : cumulative_) {
        p.push_back((c - previous) / cumulative_.back());
        previous = c;
    }
    return p;
}

}  // namespace ladarsim::campaign
