// Captures what urdfdom reports through console_bridge while it parses, for error messages.
#pragma once

#include <functional>
#include <string>

namespace hullcheck::detail {

/// Runs `parse` with console_bridge's output redirected into a string (errors and warnings,
/// one per line) and returns that string. Serialised by a mutex: console_bridge's handler is
/// process-global.
std::string capture_urdf_messages(const std::function<void()>& parse);

}  // namespace hullcheck::detail
