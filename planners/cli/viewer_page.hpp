// The viewer's page template, viewer_page.html, embedded at build time (embed_resource.cmake).
#pragma once

#include <cstddef>
#include <string_view>

namespace hullcheck::cli {

/// The bytes of viewer_page.html followed by a 0, and their number (without the 0).
extern const char kViewerPage[];
extern const std::size_t kViewerPageSize;

/// The page template: HTML with the placeholders {{title}} (HTML-escaped text),
/// {{data}} (the scene as JSON), {{three.js}} and {{OrbitControls.js}} (the scripts).
inline std::string_view viewer_page() { return std::string_view(kViewerPage, kViewerPageSize); }

}  // namespace hullcheck::cli
