// compiler/builtins_color.h: RenderMan's color spaces (RI Spec 3.2, section 15.4): the
// conversions behind ctransform and `color "space" (a, b, c)`, composed of IR operations.
#pragma once

#include <string_view>

#include "compiler/value_ops.h"

namespace affray::compiler {

/// One of "rgb", "hsv", "hsl", "xyz" (also "XYZ"), "xyY", "YIQ".
bool IsColorSpace(std::string_view space);
/// The color `c`, given in `space`, in rgb.
Value ColorToRgb(ValueOps& ops, std::string_view space, const Value& c);
/// The rgb color `c` in `space`.
Value RgbToColor(ValueOps& ops, std::string_view space, const Value& c);

}  // namespace affray::compiler
