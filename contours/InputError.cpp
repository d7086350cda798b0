#include "contours/InputError.hpp"

namespace dfrecon {

static std::string located(const std::string& file, int line, const std::string& text) {
    return line > 0 ? file + ":" + std::to_string(line) + ": " + text : file + ": " + text;
}

InputError::InputError(std::string file, int line, std::string problem)
    : std::runtime_error(located(file, line, problem)),
      file_(std::move(file)),
      line_(line),
      problem_(std::move(problem)) {}

std::string InputWarning::toString() const {
    return located(file, line, "warning: " + message);
}

}  // namespace dfrecon
