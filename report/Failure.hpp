#pragma once
// What a failure means to the user: one mapping from exceptions to exit
// codes (report/ExitCodes.hpp) and messages, used by main() for the command and
// by commands that carry on past a failing item (reconstruct --all).
#include <exception>
#include <string>

namespace dfrecon {

struct Failure {
    int exitCode = 0;
    std::string message;  // without the "dfrecon: " prefix
};

/// The exit code and message for `error`: InvalidResult 4, ItemsFailed its
/// own, InputError 2,
/// OpenCL errors 3 ("OpenCL: ..."), out of memory 3 (naming the file being
/// read or the inputs being processed, io/files/InputsInUse), std::invalid_argument
/// 1 (a usage error) except the distance fields' id limits, which are bad
/// input naming the file (2), any other std::exception 3, anything else 3
/// ("unknown error"). CLI11's parse errors are main()'s own business.
Failure describeFailure(std::exception_ptr error);

}  // namespace dfrecon
