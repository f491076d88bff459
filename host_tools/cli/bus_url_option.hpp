#pragma once
// The --bus / URL check every program with a bus option shares: a URL that does not parse
// (hal/linux/open_bus.hpp: loopback[:NAME], socketcan:IFACE, udp:127.0.0.1:PORT) is a usage error
// (exit 2, one line naming the option, as host_tools/cli/command_line.hpp states); a URL that
// parses but does not open is a runtime failure (exit 1), found when the program opens it.
// A function, not a constant, so a program that never asks for it need not link curio_hal_linux.

#include <string>

#include <CLI/CLI.hpp>

#include "hal/linux/open_bus.hpp"

namespace curio::cli {

inline CLI::Validator bus_url_check() {
  return CLI::Validator(
      [](std::string& url) {
        hal::BusUrl parsed;
        std::string error;
        return hal::parse_bus_url(url, &parsed, &error) ? std::string() : error;
      },
      "URL");
}

}  // namespace curio::cli
