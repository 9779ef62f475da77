// rib/unsupported.cpp: the RIB requests affray reads without rendering what they ask, and what it
// does with each. Real exporters (Houdini, Maya's MTOR and RenderMan Artist Tools, Blender's
// RenderMan exporters, BMRT-era tools) write requests for other renderers' features; as prman
// does with what it lacks, affray accepts them with one warning (or note) per name, so that the
// scene still renders. A request is refused only where its name is no RenderMan request at all
// (a projective Perspective is refused by its handler). Unsupported primitives are skipped with a
// warning: the image lacks them, the rest renders.
//
// To support a request: give it a handler in rib.cpp's table and take it out of these lists.
#include <algorithm>
#include <iterator>

#include "rib/parser.h"

namespace affray::rib {
namespace {

// clang-format off
// RI 3.2 requests that tune what affray has no counterpart for (dicing, bounds,
// quantizing an image affray writes as floats), and
// later RenderMan requests that name things for other renderers' pipelines (prman's Camera,
// PixelSampleImager, System): accepted with one warning per name.
constexpr std::string_view kNoEffect[] = {
    "Begin", "Bound", "Camera", "End", "ErrorHandler",
    "PixelSampleImager", "PixelVariance", "Quantize",
    "System", "TransformPoints",
};

// Requests whose absence changes only appearance (shading, lighting, the lens): RI 3.2's, and
// the shading requests of later RenderMan versions (co-shaders; RIS's Bxdf, Pattern, Light,
// Integrator and filters). Skipped with one warning per name.
constexpr std::string_view kIgnored[] = {
    "AreaLightSource", "Bxdf", "ClippingPlane", "ColorSamples",
    "DisplayFilter", "Exterior", "Integrator", "Interior", "Light", "LightFilter", "Matte",
    "Pattern", "SampleFilter", "Shader",
};

// Primitives affray cannot render yet (RI 3.2's and prman's): skipped with one warning per name,
// so the image lacks them (prman too skips a primitive it cannot make, with a warning).
constexpr std::string_view kSkippedPrimitives[] = {
    "Blobby", "Geometry", "Volume",
};
// clang-format on

bool ListedP(const std::string_view* begin, const std::string_view* end, std::string_view name) {
    return std::find(begin, end, name) != end;
}

}  // namespace

bool RibParser::DoUnhandled(const RibRequest& r) {
    if (r.name == "Deformation") {
        Warn(r.at,
             "'Deformation' is not supported (deformation shaders are an optional RI 3.2 capability); ignored: "
             "the geometry is not deformed");
        return true;
    }
    if (ListedP(std::begin(kNoEffect), std::end(kNoEffect), r.name)) {
        Warn(r.at, Quote(r.name) + " does not apply to affray; ignored");
        return true;
    }
    if (ListedP(std::begin(kIgnored), std::end(kIgnored), r.name)) {
        Warn(r.at, "request " + Quote(r.name) + " is not supported yet; ignored");
        return true;
    }
    if (ListedP(std::begin(kSkippedPrimitives), std::end(kSkippedPrimitives), r.name)) {
        if (!InsideWorld(r)) return false;
        Warn(r.at, Quote(r.name) + " is not supported yet: skipped, so the image lacks these primitives");
        return true;
    }
    return Fail(r.at, "unknown RIB request " + Quote(r.name));
}

// SolidBegin "primitive" is one closed surface, and "union" the surfaces of its parts: for opaque
// closed parts, the nearest surface a ray meets is the union's, so rendering every part shows the
// union exactly. "intersection" and "difference" hide parts of surfaces, which affray cannot do
// yet: the solid is skipped, whatever it holds (only its blocks are followed, to find its end).
bool RibParser::DoSolidBegin(const RibRequest& r) {
    std::string operation;
    if (!LeadingString(r, "a solid operation", &operation) || !InsideWorld(r)) return false;
    if (r.args.size() > 1) return Fail(r.args[1].at, "'SolidBegin' expects one string (the operation)");
    const bool hides = operation == "intersection" || operation == "difference";
    if (!hides && operation != "primitive" && operation != "union")
        return Fail(r.args[0].at, "unknown solid operation " + Quote(operation) +
                                      " (expected \"primitive\", \"union\", \"intersection\" or \"difference\")");
    if (m_skipping == 0 && operation == "union")
        Note(r.at,
             "'SolidBegin \"union\"': the surfaces of the parts are rendered, which shows the union of closed, opaque "
             "parts");
    if (m_skipping == 0 && hides)
        Warn(r.at, "'SolidBegin \"" + operation +
                       "\"' (constructive solid geometry) is not supported yet: the solid is skipped");
    m_blocks.push_back({Block::Solid, r.at, m_state, hides});
    if (hides) ++m_skipping;
    return true;
}

bool RibParser::DoSolidEnd(const RibRequest& r) { return NoArgs(r) && End(r, Block::Solid); }

}  // namespace affray::rib
