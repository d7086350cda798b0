#pragma once
// Which input files this run has read and which one it is reading now, for
// the failures that carry no file of their own: memory running out (a
// std::bad_alloc from anywhere), or a limit met after loading. main() says
// which file it was working on (docs/cli.md: every error names the file).
#include <string>
#include <vector>

namespace dfrecon {

/// Marks `path` as being read while it lives; the file stays among the
/// inputs of the run afterwards. When the read ends in an exception the
/// file is remembered as the one whose reading failed. Readers in io/ hold
/// one for their whole read. Thread-safe.
class ReadingInput {
  public:
    explicit ReadingInput(const std::string& path);
    ~ReadingInput();
    ReadingInput(const ReadingInput&) = delete;
    ReadingInput& operator=(const ReadingInput&) = delete;

  private:
    int exceptions_;
};

/// What a run was doing with its inputs, for a message without a file of its
/// own: "FILE: ... (reading it)" style parts.
struct InputsInUse {
    std::string reading;              // the file whose read failed or goes on; "" if none
    std::vector<std::string> inputs;  // every file read so far, in order, once each
};
InputsInUse inputsInUse();

/// The file read most recently (or being read); "" before any.
std::string lastInput();

}  // namespace dfrecon
