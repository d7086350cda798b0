#pragma once
// Enumerating OpenCL devices and choosing one from a user's spec.
#include <cstdint>
#include <string>
#include <vector>

#include "cl/OpenCL.hpp"

namespace dfrecon::ocl {

enum class DeviceKind { Cpu, Gpu, Accelerator, Other };
const char* toString(DeviceKind kind);

struct DeviceInfo {
    int index = 0;  // position in listDevices(), the number `--device N` takes
    cl::Platform platform;
    cl::Device device;
    std::string platformName;
    std::string deviceName;
    std::string vendor;
    std::string openclVersion;  // CL_DEVICE_VERSION, e.g. "OpenCL 3.0 PoCL ..."
    DeviceKind kind = DeviceKind::Other;
    unsigned computeUnits = 0;
    std::uint64_t globalMemoryBytes = 0;
    std::size_t maxWorkGroupSize = 0;
    bool doublePrecision = false;
};

/// Every device of every platform, numbered in platform order.
/// Throws ClError with "install pocl-opencl-icd" when no platform exists.
std::vector<DeviceInfo> listDevices();

/// Environment variable consulted when no --device is given.
inline constexpr const char* kDeviceEnvVar = "DFRECON_DEVICE";

/// Chooses a device. `spec` is "cpu", "gpu", an index into listDevices(), or
/// a case-insensitive substring of the device or platform name. An empty spec
/// falls back to $DFRECON_DEVICE, then to the first GPU, then to the first
/// CPU device (PoCL's on a stock machine). Throws ClError listing the
/// available devices when nothing matches.
DeviceInfo chooseDevice(const std::string& spec, const std::vector<DeviceInfo>& devices);
DeviceInfo chooseDevice(const std::string& spec = {});

}  // namespace dfrecon::ocl
