// `fovea devices`: every Vulkan device with the index --device takes, then the device fovea opens
// by default (discrete GPU first) with its driver and API version. The first thing a GPU check
// records (scripts/gpu-check.sh).
#include <iostream>

#include "apps/fovea/Commands.h"
#include "core/vk/Context.h"

namespace fovea::app {

void addDevicesCommand(CLI::App& app, DevicesOptions& o) {
    auto* cmd = app.add_subcommand(
        "devices", "list the Vulkan devices (--device INDEX|NAME) and the one used by default");
    cmd->add_flag("--json", o.json, "machine-readable output");
}

int devicesCommand(const DevicesOptions& o) {
    const std::vector<std::string> devices = gpu::Context::listDevices();
    // Opening the default device checks that it really works (queue, features), not just lists.
    gpu::Context ctx;
    const auto& p = ctx.properties();
    const std::string api = std::to_string(VK_API_VERSION_MAJOR(p.apiVersion)) + "." +
                            std::to_string(VK_API_VERSION_MINOR(p.apiVersion)) + "." +
                            std::to_string(VK_API_VERSION_PATCH(p.apiVersion));
    if (o.json) {
        nlohmann::json out = {{"devices", devices},
                              {"default",
                               {{"name", ctx.deviceName()},
                                {"type", ctx.deviceTypeName()},
                                {"driver", ctx.driverName()},
                                {"driver_info", ctx.driverInfo()},
                                {"api_version", api}}}};
        std::cout << out.dump(2) << "\n";
        return kExitOk;
    }
    for (const auto& d : devices) std::cout << d << "\n";
    std::cout << "default: " << ctx.deviceName() << " [" << ctx.deviceTypeName() << "], driver "
              << ctx.driverName() << " " << ctx.driverInfo() << ", Vulkan " << api << "\n";
    return kExitOk;
}

}  // namespace fovea::app
