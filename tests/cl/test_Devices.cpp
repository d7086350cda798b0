// Device choice from a spec, on a synthetic device list and on this machine.
#include <gtest/gtest.h>

#include <cstdlib>

#include "cl/ClError.hpp"
#include "cl/Devices.hpp"

using namespace dfrecon::ocl;

namespace {

std::vector<DeviceInfo> fakeDevices() {
    std::vector<DeviceInfo> devices(3);
    devices[0].deviceName = "pthread-skylake";
    devices[0].platformName = "Portable Computing Language";
    devices[0].kind = DeviceKind::Cpu;
    devices[1].deviceName = "NVIDIA H100";
    devices[1].platformName = "NVIDIA CUDA";
    devices[1].kind = DeviceKind::Gpu;
    devices[2].deviceName = "Intel Arc";
    devices[2].platformName = "Intel OpenCL";
    devices[2].kind = DeviceKind::Gpu;
    for (int i = 0; i < 3; ++i) devices[i].index = i;
    return devices;
}

struct EnvGuard {
    EnvGuard() { unsetenv(kDeviceEnvVar); }
    ~EnvGuard() { unsetenv(kDeviceEnvVar); }
};

}  // namespace

TEST(Devices, DefaultPrefersTheFirstGpu) {
    EnvGuard env;
    EXPECT_EQ(chooseDevice("", fakeDevices()).index, 1);
    std::vector<DeviceInfo> cpuOnly = {fakeDevices()[0]};
    EXPECT_EQ(chooseDevice("", cpuOnly).index, 0);
}

TEST(Devices, SpecByKindIndexAndName) {
    EnvGuard env;
    const auto devices = fakeDevices();
    EXPECT_EQ(chooseDevice("cpu", devices).index, 0);
    EXPECT_EQ(chooseDevice("GPU", devices).index, 1);
    EXPECT_EQ(chooseDevice("2", devices).index, 2);
    EXPECT_EQ(chooseDevice("arc", devices).index, 2);
    EXPECT_EQ(chooseDevice("portable", devices).index, 0);  // platform name
}

TEST(Devices, EnvironmentVariableIsTheFallback) {
    EnvGuard env;
    setenv(kDeviceEnvVar, "intel", 1);
    EXPECT_EQ(chooseDevice("", fakeDevices()).index, 2);
    EXPECT_EQ(chooseDevice("cpu", fakeDevices()).index, 0);  // --device wins
}

TEST(Devices, NoMatchListsWhatExists) {
    EnvGuard env;
    try {
        chooseDevice("7", fakeDevices());
        FAIL();
    } catch (const ClError& e) {
        EXPECT_NE(std::string(e.what()).find("no OpenCL device matches '7'"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("1: NVIDIA H100 (gpu, NVIDIA CUDA)"),
                  std::string::npos);
    }
    std::vector<DeviceInfo> cpuOnly = {fakeDevices()[0]};
    EXPECT_THROW(chooseDevice("gpu", cpuOnly), ClError);
}

TEST(Devices, ThisMachineHasACpuDevice) {
    // make setup installs PoCL, so a CPU device always exists here and in CI.
    const auto devices = listDevices();
    ASSERT_FALSE(devices.empty());
    bool cpu = false;
    for (const DeviceInfo& d : devices) {
        EXPECT_FALSE(d.deviceName.empty());
        EXPECT_GT(d.computeUnits, 0u);
        cpu = cpu || d.kind == DeviceKind::Cpu;
    }
    EXPECT_TRUE(cpu);
}
