#include "urdf_messages.hpp"

#include <console_bridge/console.h>

#include <mutex>

namespace hullcheck::detail {
namespace {

class CaptureHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
           int /*line*/) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_WARN) return;
    if (!messages.empty()) messages += "; ";
    messages += text;
  }
  std::string messages;
};

}  // namespace

std::string capture_urdf_messages(const std::function<void()>& parse) {
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  CaptureHandler handler;
  console_bridge::useOutputHandler(&handler);
  try {
    parse();
  } catch (...) {
    console_bridge::restorePreviousOutputHandler();
    throw;
  }
  console_bridge::restorePreviousOutputHandler();
  return handler.messages;
}

}  // namespace hullcheck::detail
