#include "app/Failure.hpp"

#include <new>
#include <stdexcept>
#include <string>

#include "app/ExitCodes.hpp"
#include "cl/ClError.hpp"
#include "field/PrimitiveId.hpp"
#include "io/InputError.hpp"
#include "io/InputsInUse.hpp"

namespace dfrecon::app {

namespace {

// Memory running out names the file it ran out on: the one being read, or
// the inputs being processed (docs/cli.md: every error names the file).
std::string outOfMemory() {
    const InputsInUse in = inputsInUse();
    if (!in.reading.empty()) return in.reading + ": out of memory while reading it";
    if (in.inputs.empty()) return "out of memory";
    std::string files;
    for (const std::string& f : in.inputs) files += (files.empty() ? "" : ", ") + f;
    return files + ": out of memory while processing " + (in.inputs.size() == 1 ? "it" : "them");
}

// Whether `e` is the distance fields refusing a contour or a plane over
// what their 32-bit ids index (field/SliceFields checkLimits, which states
// these limits): valid input too large for this program, so bad input
// naming the file, not a usage error. (A type of its own thrown by field/
// would be better than the words; tests/app/test_cli_hostile holds them.)
bool isFieldIdLimit(const std::invalid_argument& e) {
    const std::string what = e.what();
    return what.find("has over " + std::to_string(kMaxPrimitivesPerContour - 1) + " points") !=
               std::string::npos ||
           what.find("has over " + std::to_string(kMaxContoursPerSlice - 1) + " contours") !=
               std::string::npos;
}

}  // namespace

Failure describeFailure(std::exception_ptr error) {
    try {
        std::rethrow_exception(error);
    } catch (const InvalidResult& e) {
        return {kExitInvalidResult, e.what()};
    } catch (const ItemsFailed& e) {
        return {e.exitCode(), e.what()};
    } catch (const InputError& e) {
        return {kExitBadInput, e.what()};
    } catch (const ocl::ClError& e) {
        return {kExitRuntime, std::string("OpenCL: ") + e.what()};
    } catch (const cl::Error& e) {
        return {kExitRuntime, std::string("OpenCL: ") + ocl::toClError(e).what()};
    } catch (const std::bad_alloc&) {
        return {kExitRuntime, outOfMemory()};
    } catch (const std::length_error& e) {  // a container asked for more than can exist
        return {kExitRuntime, outOfMemory() + " (" + e.what() + ")"};
    } catch (const std::invalid_argument& e) {
        if (isFieldIdLimit(e) && !lastInput().empty())
            return {kExitBadInput,
                    lastInput() + ": " + e.what() +
                        ", the most the distance fields can index (--contour-error simplifies "
                        "contours first)"};
        return {kExitUsage, e.what()};
    } catch (const std::exception& e) {
        return {kExitRuntime, e.what()};
    } catch (...) {
        return {kExitRuntime, "unknown error"};
    }
}

}  // namespace dfrecon::app
