// scene/number_text.h: a double as text, the way `std::ostream << x` prints it by default
// (printf's "%g": six significant digits), without a stream. The scene's printing (ToString of
// patches, vectors and matrices) goes through it: a render's identity prints every primitive of
// the scene (renderer/render_identity.cpp), and an ostringstream per vector was most of the cost
// for a mesh of thousands of faces.
#pragma once

#include <charconv>
#include <string>

namespace affray::renderer {

/// Appends x to `out` as `std::ostream << x` writes it with default flags (tested to be the same
/// text: tests/scene/number_text_test.cpp).
inline void AppendNumber(std::string& out, double x) {
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, x, std::chars_format::general, 6);
    out.append(text, ec == std::errc() ? end : text);
}

}  // namespace affray::renderer
