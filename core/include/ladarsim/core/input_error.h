#pragma once
// The one error type for bad user input: it always names the file, the field and the problem,
// so the command line can print it as a single line and exit non-zero.
#include <stdexcept>
#include <string>

namespace ladarsim {

class InputError : public std::runtime_error {
public:
    InputError(std::string file, std::string field, std::string problem)
        : std::runtime_error(file + ": " + field + ": " + problem),
          file_(std::move(file)), field_(std::move(field)), problem_(std::move(problem)) {}

    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }
    const std::string& problem() const { return problem_; }

private:
    std::string file_;
    std::string field_;
    std::string problem_;
};

}  // namespace ladarsim
