#pragma once
// Problems found in input files, located as `file:line: problem`.
#include <stdexcept>
#include <string>
#include <vector>

namespace dfrecon {

/// A defect that stops loading. what() is "file:line: problem" ("file:
/// problem" when no line applies). The CLI exits with code 2 for these.
class InputError : public std::runtime_error {
  public:
    InputError(std::string file, int line, std::string problem);
    const std::string& file() const { return file_; }
    int line() const { return line_; }
    const std::string& problem() const { return problem_; }

  private:
    std::string file_;
    int line_;
    std::string problem_;
};

/// Something repaired while loading; reported, never fatal.
struct InputWarning {
    std::string file;
    int line = 0;
    std::string message;
    std::string roi;  // the ROI it is about; empty: the file as a whole
    std::string toString() const;
};

}  // namespace dfrecon
