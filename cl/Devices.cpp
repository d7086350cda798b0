#include "cl/Devices.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "cl/ClError.hpp"

namespace dfrecon::ocl {

const char* toString(DeviceKind kind) {
    switch (kind) {
        case DeviceKind::Cpu:
            return "cpu";
        case DeviceKind::Gpu:
            return "gpu";
        case DeviceKind::Accelerator:
            return "accelerator";
        default:
            return "other";
    }
}

static DeviceKind kindOf(cl_device_type type) {
    if (type & CL_DEVICE_TYPE_GPU) return DeviceKind::Gpu;
    if (type & CL_DEVICE_TYPE_CPU) return DeviceKind::Cpu;
    if (type & CL_DEVICE_TYPE_ACCELERATOR) return DeviceKind::Accelerator;
    return DeviceKind::Other;
}

// Strings from clGetDeviceInfo may carry their terminating NUL.
static std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back()))))
        s.pop_back();
    return s;
}

static std::string lowercase(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

static const char* kNoPlatformHelp =
    "no OpenCL platform found: install pocl-opencl-icd (`make setup` does) "
    "or your GPU vendor's OpenCL driver";

std::vector<DeviceInfo> listDevices() {
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error& e) {
        // ocl-icd reports "no ICD installed" as CL_PLATFORM_NOT_FOUND_KHR.
        throw ClError(std::string(kNoPlatformHelp) + " [" + e.what() + ": " + errorName(e.err()) +
                      "]");
    }
    if (platforms.empty()) throw ClError(kNoPlatformHelp);

    std::vector<DeviceInfo> devices;
    try {
        for (const cl::Platform& platform : platforms) {
            std::vector<cl::Device> platformDevices;
            try {
                platform.getDevices(CL_DEVICE_TYPE_ALL, &platformDevices);
            } catch (const cl::Error& e) {
                if (e.err() == CL_DEVICE_NOT_FOUND) continue;  // a platform with no devices
                throw;
            }
            for (const cl::Device& device : platformDevices) {
                DeviceInfo info;
                info.index = static_cast<int>(devices.size());
                info.platform = platform;
                info.device = device;
                info.platformName = trimmed(platform.getInfo<CL_PLATFORM_NAME>());
                info.deviceName = trimmed(device.getInfo<CL_DEVICE_NAME>());
                info.vendor = trimmed(device.getInfo<CL_DEVICE_VENDOR>());
                info.openclVersion = trimmed(device.getInfo<CL_DEVICE_VERSION>());
                info.kind = kindOf(device.getInfo<CL_DEVICE_TYPE>());
                info.computeUnits = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
                info.globalMemoryBytes = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
                info.maxWorkGroupSize = device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
                info.doublePrecision = device.getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() != 0;
                devices.push_back(std::move(info));
            }
        }
    } catch (const cl::Error& e) {
        throw toClError(e);
    }
    if (devices.empty())
        throw ClError(std::string(kNoPlatformHelp) + " (platforms have no devices)");
    return devices;
}

static std::string availableList(const std::vector<DeviceInfo>& devices) {
    std::string list;
    for (const DeviceInfo& d : devices)
        list += "\n  " + std::to_string(d.index) + ": " + d.deviceName + " (" + toString(d.kind) +
                ", " + d.platformName + ")";
    return list;
}

static bool isIndex(const std::string& spec) {
    return !spec.empty() && spec.size() < 6 &&
           std::all_of(spec.begin(), spec.end(), [](char c) { return c >= '0' && c <= '9'; });
}

DeviceInfo chooseDevice(const std::string& requested, const std::vector<DeviceInfo>& devices) {
    std::string spec = requested;
    if (spec.empty()) {
        const char* env = std::getenv(kDeviceEnvVar);
        if (env) spec = env;
    }
    auto firstOfKind = [&](DeviceKind kind) -> const DeviceInfo* {
        for (const DeviceInfo& d : devices)
            if (d.kind == kind) return &d;
        return nullptr;
    };
    if (spec.empty()) {
        if (const DeviceInfo* gpu = firstOfKind(DeviceKind::Gpu)) return *gpu;
        if (const DeviceInfo* cpu = firstOfKind(DeviceKind::Cpu)) return *cpu;
        return devices.front();
    }
    const std::string wanted = lowercase(spec);
    if (wanted == "cpu" || wanted == "gpu") {
        if (const DeviceInfo* d = firstOfKind(wanted == "cpu" ? DeviceKind::Cpu : DeviceKind::Gpu))
            return *d;
    } else if (isIndex(wanted)) {
        const int index = std::stoi(wanted);
        if (index < static_cast<int>(devices.size()))
            return devices[static_cast<std::size_t>(index)];
    } else {
        for (const DeviceInfo& d : devices)
            if (lowercase(d.deviceName).find(wanted) != std::string::npos ||
                lowercase(d.platformName).find(wanted) != std::string::npos)
                return d;
    }
    throw ClError("no OpenCL device matches '" + spec + "'" +
                  (requested.empty() ? std::string(" (from ") + kDeviceEnvVar + ")" : "") +
                  "; available:" + availableList(devices));
}

DeviceInfo chooseDevice(const std::string& spec) {
    return chooseDevice(spec, listDevices());
}

}  // namespace dfrecon::ocl
