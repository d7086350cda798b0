#include "cl/Runtime.hpp"

#include "cl/ClError.hpp"
#include "kernels/EmbeddedKernels.hpp"

namespace dfrecon::ocl {

Runtime::Runtime(const std::string& deviceSpec) : Runtime(chooseDevice(deviceSpec)) {}

Runtime::Runtime(DeviceInfo device) : device_(std::move(device)) {
    try {
        context_ = cl::Context(device_.device);
        queue_ = cl::CommandQueue(context_, device_.device);
    } catch (const cl::Error& e) {
        throw toClError(e, "while opening device '" + device_.deviceName + "'");
    }
}

Runtime::Runtime(Runtime& other, ShareContext)
    : device_(other.device_), context_(other.context_), programs_(other.programs_) {
    try {
        queue_ = cl::CommandQueue(context_, device_.device);
    } catch (const cl::Error& e) {
        throw toClError(e, "while opening a queue on device '" + device_.deviceName + "'");
    }
}

const cl::Program& Runtime::program(const std::vector<std::string>& sourceFiles,
                                    const std::string& options) {
    std::string key = options;
    for (const std::string& file : sourceFiles) key += "|" + file;

    // Held through the build: a worker asking for a program another is
    // building waits for it instead of building it again.
    std::lock_guard<std::mutex> lock(programs_->mutex);
    if (auto found = programs_->programs.find(key); found != programs_->programs.end())
        return found->second;

    std::string source;
    for (const std::string& file : sourceFiles) {
        try {
            source += kernels::kernelSource(file);
        } catch (const std::out_of_range& e) {
            throw ClError(e.what());
        }
        source += "\n";
    }
    std::string label;
    for (const std::string& file : sourceFiles) label += (label.empty() ? "" : ", ") + file;
    cl::Program program = buildProgram(source, label, options);
    return programs_->programs.emplace(key, std::move(program)).first->second;
}

cl::Program Runtime::buildProgram(const std::string& source, const std::string& label,
                                  const std::string& options) {
    cl::Program program;
    try {
        program = cl::Program(context_, source);
    } catch (const cl::Error& e) {
        throw toClError(e, label);
    }
    try {
        program.build(std::vector<cl::Device>{device_.device}, options.c_str());
    } catch (const cl::Error& e) {
        std::string log;
        try {
            log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_.device);
        } catch (const cl::Error&) {
            log = "(build log unavailable)";
        }
        throw toClError(e, "building " + label + " for " + device_.deviceName + ":\n" + log);
    }
    return program;
}

cl::Kernel Runtime::kernel(const std::vector<std::string>& sourceFiles, const std::string& name) {
    const cl::Program& built = program(sourceFiles);
    try {
        return cl::Kernel(built, name.c_str());
    } catch (const cl::Error& e) {
        throw toClError(e, "kernel '" + name + "'");
    }
}

}  // namespace dfrecon::ocl
