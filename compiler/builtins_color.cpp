// compiler/builtins_color.cpp: color space conversions (ctransform, `color "hsv" (...)`), each a
// composition of IR operations, so every number type bounds them with the rules of those
// operations (Min, Max, Select, Div, Floor...). Hue is in [0, 1), as RenderMan has it.
// Sources: Foley, van Dam, Feiner & Hughes, "Computer Graphics: Principles and Practice" (2nd
// ed.), section 13.3 (HSV, HLS, YIQ); CIE XYZ of Rec. 709 primaries with white D65 (ITU-R
// BT.709); the chromaticity xyY of CIE 1931.
#include "compiler/builtins_color.h"

#include <array>

namespace affray::compiler {

namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

constexpr Matrix3 kRgbToXyz = {
    {{0.412453, 0.357580, 0.180423}, {0.212671, 0.715160, 0.072169}, {0.019334, 0.119193, 0.950227}}};
constexpr Matrix3 kRgbToYiq = {{{0.299, 0.587, 0.114}, {0.596, -0.275, -0.321}, {0.212, -0.523, 0.311}}};

Matrix3 Inverse(const Matrix3& m) {
    auto cofactor = [&](int r, int c) {
        const int r0 = (r + 1) % 3, r1 = (r + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
        return m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    };
    const double det = m[0][0] * cofactor(0, 0) + m[0][1] * cofactor(0, 1) + m[0][2] * cofactor(0, 2);
    Matrix3 out{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) out[r][c] = cofactor(c, r) / det;
    return out;
}

Value Apply(ValueOps& o, const Matrix3& m, const Value& c) {
    Value out{Type::Color, {}};
    for (int r = 0; r < 3; ++r) {
        Value sum = o.Mul(o.Constant(m[r][0]), o.Component(c, 0));
        for (int k = 1; k < 3; ++k) sum = o.Add(sum, o.Mul(o.Constant(m[r][k]), o.Component(c, k)));
        out.c[r] = sum.c[0];
    }
    return out;
}

Value Color(const Value& x, const Value& y, const Value& z) { return {Type::Color, {x.c[0], y.c[0], z.c[0]}}; }

Value Less(ValueOps& o, const Value& a, const Value& b) { return o.Binary(IrOp::Lt, a, b); }

/// The hue of HSV and HSL, in [0, 1): by which channel is largest (0 for a grey).
Value Hue(ValueOps& o, const Value& r, const Value& g, const Value& b, const Value& mx, const Value& d) {
    const Value six = o.Constant(6.0);
    const Value byR = o.Div(o.Sub(g, b), d);
    const Value byG = o.Add(o.Constant(2.0), o.Div(o.Sub(b, r), d));
    const Value byB = o.Add(o.Constant(4.0), o.Div(o.Sub(r, g), d));
    Value h = o.SelectValue(o.Binary(IrOp::Eq, r, mx), byR, o.SelectValue(o.Binary(IrOp::Eq, g, mx), byG, byB));
    h = o.Div(h, six);
    h = o.SelectValue(Less(o, h, o.Constant(0.0)), o.Add(h, o.Constant(1.0)), h);
    return o.SelectValue(o.Binary(IrOp::Eq, d, o.Constant(0.0)), o.Constant(0.0), h);
}

Value RgbToHsvOrHsl(ValueOps& o, const Value& c, bool hsl) {
    const Value r = o.Component(c, 0), g = o.Component(c, 1), b = o.Component(c, 2);
    const Value mx = o.Binary(IrOp::Max, o.Binary(IrOp::Max, r, g), b);
    const Value mn = o.Binary(IrOp::Min, o.Binary(IrOp::Min, r, g), b);
    const Value d = o.Sub(mx, mn);
    const Value zero = o.Constant(0.0), grey = o.Binary(IrOp::Eq, d, zero);
    const Value h = Hue(o, r, g, b, mx, d);
    if (!hsl) {
        // v = max, s = (max - min) / max (0 for black)
        const Value s = o.SelectValue(Less(o, zero, mx), o.Div(d, mx), zero);
        return Color(h, s, mx);
    }
    // l = (max + min) / 2, s = d / (max + min) up to l = 1/2, d / (2 - max - min) above
    const Value sum = o.Add(mx, mn);
    const Value l = o.Mul(sum, o.Constant(0.5));
    const Value s = o.SelectValue(
        grey, zero,
        o.SelectValue(o.Binary(IrOp::Le, l, o.Constant(0.5)), o.Div(d, sum), o.Div(d, o.Sub(o.Constant(2.0), sum))));
    return Color(h, s, l);
}

Value HsvToRgb(ValueOps& o, const Value& c) {
    const Value h = o.Component(c, 0), s = o.Component(c, 1), v = o.Component(c, 2);
    const Value h6 = o.Mul(o.Sub(h, o.Map(IrOp::Floor, h)), o.Constant(6.0));
    const Value sector = o.Map(IrOp::Floor, h6);
    const Value f = o.Sub(h6, sector);
    const Value one = o.Constant(1.0);
    const Value p = o.Mul(v, o.Sub(one, s));
    const Value q = o.Mul(v, o.Sub(one, o.Mul(s, f)));
    const Value t = o.Mul(v, o.Sub(one, o.Mul(s, o.Sub(one, f))));
    const Value rows[6] = {Color(v, t, p), Color(q, v, p), Color(p, v, t),
                           Color(p, q, v), Color(t, p, v), Color(v, p, q)};
    Value out = rows[5];
    for (int i = 4; i >= 0; --i) out = o.SelectValue(o.Binary(IrOp::Eq, sector, o.Constant(i)), rows[i], out);
    return out;
}

Value HslToRgb(ValueOps& o, const Value& c) {
    const Value h = o.Component(c, 0), s = o.Component(c, 1), l = o.Component(c, 2);
    const Value one = o.Constant(1.0);
    const Value m2 =
        o.SelectValue(o.Binary(IrOp::Le, l, o.Constant(0.5)), o.Mul(l, o.Add(one, s)), o.Sub(o.Add(l, s), o.Mul(l, s)));
    const Value m1 = o.Sub(o.Mul(o.Constant(2.0), l), m2);
    // One channel from its hue: rising over the first sixth, m2 to 1/2, falling to 2/3, m1 after.
    auto channel = [&](double offset) {
        Value x = o.Add(h, o.Constant(offset));
        x = o.Sub(x, o.Map(IrOp::Floor, x));
        const Value rising = o.Add(m1, o.Mul(o.Mul(o.Sub(m2, m1), x), o.Constant(6.0)));
        const Value falling = o.Add(m1, o.Mul(o.Mul(o.Sub(m2, m1), o.Sub(o.Constant(2.0 / 3), x)), o.Constant(6.0)));
        return o.SelectValue(Less(o, x, o.Constant(1.0 / 6)), rising,
                             o.SelectValue(Less(o, x, o.Constant(0.5)), m2,
                                           o.SelectValue(Less(o, x, o.Constant(2.0 / 3)), falling, m1)));
    };
    return Color(channel(1.0 / 3), channel(0.0), channel(-1.0 / 3));
}

}  // namespace

bool IsColorSpace(std::string_view space) {
    return space == "rgb" || space == "hsv" || space == "hsl" || space == "xyz" || space == "XYZ" || space == "xyY" ||
           space == "YIQ";
}

Value ColorToRgb(ValueOps& o, std::string_view space, const Value& in) {
    const Value c = o.Promote(in, Type::Color);
    if (space == "hsv") return HsvToRgb(o, c);
    if (space == "hsl") return HslToRgb(o, c);
    if (space == "xyz" || space == "XYZ") return Apply(o, Inverse(kRgbToXyz), c);
    if (space == "YIQ") return Apply(o, Inverse(kRgbToYiq), c);
    if (space == "xyY") {
        // X = x Y / y, Z = (1 - x - y) Y / y; black (Y = 0) stays black.
        const Value x = o.Component(c, 0), y = o.Component(c, 1), Y = o.Component(c, 2);
        const Value scale = o.Div(Y, y);
        const Value xyz = Color(o.Mul(x, scale), Y, o.Mul(o.Sub(o.Sub(o.Constant(1.0), x), y), scale));
        const Value black = o.Binary(IrOp::Eq, Y, o.Constant(0.0));
        return o.SelectValue(black, o.Promote(o.Constant(0.0), Type::Color), Apply(o, Inverse(kRgbToXyz), xyz));
    }
    return c;  // rgb
}

Value RgbToColor(ValueOps& o, std::string_view space, const Value& in) {
    const Value c = o.Promote(in, Type::Color);
    if (space == "hsv") return RgbToHsvOrHsl(o, c, false);
    if (space == "hsl") return RgbToHsvOrHsl(o, c, true);
    if (space == "xyz" || space == "XYZ") return Apply(o, kRgbToXyz, c);
    if (space == "YIQ") return Apply(o, kRgbToYiq, c);
    if (space == "xyY") {
        // x = X / (X + Y + Z), y = Y / (X + Y + Z); black is (0, 0, 0).
        const Value xyz = Apply(o, kRgbToXyz, c);
        const Value sum = o.Add(o.Add(o.Component(xyz, 0), o.Component(xyz, 1)), o.Component(xyz, 2));
        const Value xyY = Color(o.Div(o.Component(xyz, 0), sum), o.Div(o.Component(xyz, 1), sum), o.Component(xyz, 1));
        const Value black = o.Binary(IrOp::Eq, sum, o.Constant(0.0));
        return o.SelectValue(black, o.Promote(o.Constant(0.0), Type::Color), xyY);
    }
    return c;  // rgb
}

}  // namespace affray::compiler
