// dfrecon devices: the OpenCL platforms and devices this machine offers.
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "cl/Devices.hpp"
#include "io/files/JsonText.hpp"

namespace dfrecon::app {

namespace {

void runDevices(const GlobalOptions& global, bool json) {
    const std::vector<ocl::DeviceInfo> devices = ocl::listDevices();
    const ocl::DeviceInfo chosen = ocl::chooseDevice(global.device, devices);
    if (json) {
        nlohmann::ordered_json list = nlohmann::ordered_json::array();
        for (const ocl::DeviceInfo& d : devices)
            list.push_back({{"index", d.index},
                            {"name", d.deviceName},
                            {"platform", d.platformName},
                            {"vendor", d.vendor},
                            {"type", ocl::toString(d.kind)},
                            {"version", d.openclVersion},
                            {"computeUnits", d.computeUnits},
                            {"globalMemoryBytes", d.globalMemoryBytes},
                            {"maxWorkGroupSize", d.maxWorkGroupSize},
                            {"doublePrecision", d.doublePrecision},
                            {"selected", d.index == chosen.index}});
        std::cout << jsonText(nlohmann::ordered_json{{"command", "devices"}, {"devices", list}}, 2)
                  << "\n";
        return;
    }
    for (const ocl::DeviceInfo& d : devices) {
        std::cout << (d.index == chosen.index ? "* " : "  ") << d.index << ": " << d.deviceName
                  << "\n      type " << ocl::toString(d.kind) << ", platform " << d.platformName
                  << ", " << d.openclVersion << "\n      " << d.computeUnits << " compute units, "
                  << d.globalMemoryBytes / (1024 * 1024) << " MiB, fp64 "
                  << (d.doublePrecision ? "yes" : "no") << "\n";
    }
    std::cout << "* = the device dfrecon uses with the current --device / DFRECON_DEVICE\n";
}

}  // namespace

void addDevicesCommand(CLI::App& root, const GlobalOptions& global) {
    auto json = std::make_shared<bool>(false);
    CLI::App* cmd = root.add_subcommand("devices", "List OpenCL devices and mark the one in use");
    cmd->add_flag("--json", *json, "Print a JSON report instead of text");
    cmd->callback([&global, json] { runDevices(global, *json); });
}

}  // namespace dfrecon::app
