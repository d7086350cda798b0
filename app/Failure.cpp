#include "app/Failure.hpp"

#include <new>
#include <stdexcept>

#include "app/ExitCodes.hpp"
#include "cl/ClError.hpp"
#include "io/InputError.hpp"

namespace dfrecon::app {

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
        return {kExitRuntime, "out of memory"};
    } catch (const std::invalid_argument& e) {
        return {kExitUsage, e.what()};
    } catch (const std::exception& e) {
        return {kExitRuntime, e.what()};
    } catch (...) {
        return {kExitRuntime, "unknown error"};
    }
}

}  // namespace dfrecon::app
