// compiler/builtins_color.h: RenderMan's color spaces (RI Spec 3.2, section 15.4): the
// conversions behind ctransform and `color "space" (a, b, c)`, composed of IR operations.
#pragma once

#include <string_view>

#include "compiler/value_ops.h"

namespace affray::compiler {

/// One of "rgb", "hsv", "hsl", "xyz" (also "XYZ"), "xyY", "YIQ".
bool IsColorSpace(std::string_view space);
/// The color `in`, given in `space`, in rgb.
Value ColorToRgb(ValueOps& o, std::string_view space, const Value& in);
/// The rgb color `in` in `space`.
Value RgbToColor(ValueOps& o, std::string_view space, const Value& in);

}  // namespace affray::compiler
