#include "report/Failure.hpp"

#include <new>
#include <stdexcept>
#include <string>

#include "cl/ClError.hpp"
#include "contours/InputError.hpp"
#include "field/PrimitiveId.hpp"
#include "io/files/InputsInUse.hpp"
#include "report/ExitCodes.hpp"

namespace dfrecon {

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
    } catch (const PrimitiveLimitExceeded& e) {
        // Valid input too large for this program: bad input naming the file.
        const std::string file = lastInput().empty() ? "" : lastInput() + ": ";
        return {kExitBadInput, file + e.what() +
                                   ", the most the distance fields can index (--contour-error "
                                   "simplifies contours first)"};
    } catch (const std::invalid_argument& e) {
        return {kExitUsage, e.what()};
    } catch (const std::exception& e) {
        return {kExitRuntime, e.what()};
    } catch (...) {
        return {kExitRuntime, "unknown error"};
    }
}

}  // namespace dfrecon
