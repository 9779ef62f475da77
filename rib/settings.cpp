// rib/settings.cpp: RIB requests that set how to read or render the scene rather than what is in
// it: Option (the search paths; Option and Attribute "Ri" run as the standard requests they stand
// for; other renderers' options warn), Hider, Declare, ShadingRate,
// ShadingInterpolation and ArchiveRecord. Rules shared with rib.cpp are in rib/parser.h. Every
// request that only tunes another renderer is accepted, its arguments checked, with one warning.
#include <algorithm>
#include <cmath>

#include "rib/parser.h"

namespace affray::rib {

// Option "searchpath" "shader", "texture" and "archive" are used; "user" is kept for conditional
// RIB (rib/conditional.cpp); every other option tunes another renderer (bucket sizes, statistics,
// caches...) and is ignored with one warning per name.
bool RibParser::DoOption(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!BeforeWorld(r) || !LeadingString(r, "an option name", &name) || !ParamList(r, 1, &params)) return false;
    // Every value is kept for conditional RIB ($category:name), which is what "user" is for.
    for (const RibParam& p : params) m_options[name + ":" + p.value.name] = p.value;
    if (name == "Ri") return RiOptions(params);
    if (name != "searchpath") {
        if (name != "user") Warn(r.at, "'Option \"" + name + "\"' does not apply to affray; ignored");
        return true;
    }
    for (const RibParam& p : params) {
        if (p.value.name == "shader") {
            if (!SetSearchPath(p, &m_scene.shaderSearchPath)) return false;
        } else if (p.value.name == "archive") {
            if (!SetSearchPath(p, &m_archiveSearchPath)) return false;
        } else if (p.value.name == "texture") {
            if (!SetSearchPath(p, &m_scene.textureSearchPath)) return false;
        } else {
            Warn(p.at, "'Option \"searchpath\" \"" + p.value.name + "\"' does not apply to affray; ignored");
        }
    }
    return true;
}

// RenderMan 21 and later write the standard options and attributes as parameters of Option "Ri"
// and Attribute "Ri" ("int[2] FormatResolution" [640 480] for Format, "int Sides" [1] for Sides,
// ...). Each is run as the request it stands for, so it gets that request's checks, effect and
// messages; a parameter standing for a request affray ignores gets that request's warning, and
// one standing for nothing affray knows, a warning of its own. The values stay readable by
// conditional RIB as "Ri:name", as every option's and attribute's are.
namespace {

RibArg NumbersArg(std::vector<double> numbers, RibPos at) {
    RibArg a;
    a.isArray = true;
    a.numbers = std::move(numbers);
    a.at = at;
    return a;
}

RibArg StringArg(std::string text, RibPos at) {
    RibArg a;
    a.strings = {std::move(text)};
    a.at = at;
    return a;
}

/// The parameters of Option and Attribute "Ri" named as the request they stand for, a request of
/// numbers or of strings (its arguments are the parameter's values).
// clang-format off
constexpr std::string_view kRiOptions[] = {
    "Clipping", "CropWindow", "DepthOfField", "FrameAspectRatio", "PixelSamples", "PixelVariance",
    "RelativeDetail", "ScreenWindow", "Shutter",
};
constexpr std::string_view kRiAttributes[] = {
    "Color", "DetailRange", "Matte", "Opacity", "Orientation", "ShadingInterpolation", "ShadingRate", "Sides",
    "TextureCoordinates",
};
// clang-format on

/// A standing-for parameter run as its request: numbers as one array, a string as a bare string.
std::vector<RibArg> ArgsOf(const RibParam& p) {
    if (!p.value.strings.empty()) {
        std::vector<RibArg> args;
        for (const std::string& s : p.value.strings) args.push_back(StringArg(s, p.at));
        return args;
    }
    return {NumbersArg(p.value.numbers, p.at)};
}

bool RiRequestP(const std::string_view* begin, const std::string_view* end, std::string_view parameter) {
    return std::find(begin, end, parameter) != end;
}

}  // namespace

bool RibParser::Forward(const std::string& name, RibPos at, std::vector<RibArg> args) {
    RibRequest r;
    r.name = name;
    r.at = at;
    r.args = std::move(args);
    return DispatchRequest(r);
}

bool RibParser::RiOptions(const std::vector<RibParam>& params) {
    // Format, PixelFilter and Exposure are each split over two parameters: what one leaves out
    // is the value in effect.
    const RibParam *resolution = nullptr, *pixelAspect = nullptr, *filterName = nullptr, *filterWidth = nullptr,
                   *gain = nullptr, *gamma = nullptr;
    for (const RibParam& p : params) {
        const std::string& name = p.value.name;
        if (name == "FormatResolution") {
            resolution = &p;
        } else if (name == "FormatPixelAspectRatio") {
            pixelAspect = &p;
        } else if (name == "PixelFilterName") {
            filterName = &p;
        } else if (name == "PixelFilterWidth") {
            filterWidth = &p;
        } else if (name == "ExposureGain") {
            gain = &p;
        } else if (name == "ExposureGamma") {
            gamma = &p;
        } else if (name == "Frame") {
            // The frame number, for the exporter's own bookkeeping (FrameBegin gives affray's).
        } else if (RiRequestP(std::begin(kRiOptions), std::end(kRiOptions), name)) {
            if (!Forward(name, p.at, ArgsOf(p))) return false;
        } else {
            Warn(p.at, "'Option \"Ri\"' parameter " + Quote(name) + " does not apply to affray; ignored");
        }
    }
    const CameraDesc& camera = m_scene.camera;
    // One number each: a parameter with the wrong count is refused by the request's own check.
    auto values = [](const RibParam* p, std::vector<double> fallback) { return p ? p->value.numbers : fallback; };
    if (resolution || pixelAspect) {
        std::vector<double> v = values(resolution, {double(camera.xres), double(camera.yres)});
        const std::vector<double> aspect = values(pixelAspect, {camera.pixelAspect});
        v.insert(v.end(), aspect.begin(), aspect.end());
        const RibPos at = (resolution ? resolution : pixelAspect)->at;
        if (!Forward("Format", at, {NumbersArg(v, at)})) return false;
    }
    if (filterName || filterWidth) {
        const RibParam* at = filterName ? filterName : filterWidth;
        std::string name = camera.filter.kind == FilterDesc::Kind::Box ? "box" : "gaussian";
        if (filterName) {
            if (filterName->value.strings.size() != 1)
                return Fail(filterName->at, "'Option \"Ri\"' parameter 'PixelFilterName' expects 1 string");
            name = filterName->value.strings[0];
        }
        const std::vector<double> widths = values(filterWidth, {camera.filter.xwidth, camera.filter.ywidth});
        if (widths.size() != 2)
            return Fail(filterWidth->at, "'Option \"Ri\"' parameter 'PixelFilterWidth' expects 2 numbers");
        std::vector<RibArg> args = {StringArg(name, at->at)};
        for (double w : widths) {
            RibArg a;
            a.numbers = {w};
            a.at = at->at;
            args.push_back(a);
        }
        if (!Forward("PixelFilter", at->at, std::move(args))) return false;
    }
    if (gain || gamma) {
        std::vector<double> v = values(gain, {camera.exposureGain});
        const std::vector<double> g = values(gamma, {camera.exposureGamma});
        v.insert(v.end(), g.begin(), g.end());
        const RibPos at = (gain ? gain : gamma)->at;
        if (!Forward("Exposure", at, {NumbersArg(v, at)})) return false;
    }
    return true;
}

bool RibParser::RiAttributes(const std::vector<RibParam>& params) {
    for (const RibParam& p : params) {
        if (RiRequestP(std::begin(kRiAttributes), std::end(kRiAttributes), p.value.name)) {
            if (!Forward(p.value.name, p.at, ArgsOf(p))) return false;
        } else {
            Warn(p.at, "'Attribute \"Ri\"' parameter " + Quote(p.value.name) + " does not apply to affray; ignored");
        }
    }
    return true;
}

// Option "searchpath" "shader" "dir1:dir2": '&' is the previous path and '@' the default, which
// is the empty list (the renderer's own default), so '@' adds nothing. Empty entries are
// skipped. Relative directories are kept as written; they are taken relative to the RIB file's
// directory (the renderer does so for shaders, FindArchive for archives).
bool RibParser::SetSearchPath(const RibParam& p, std::vector<std::string>* out) {
    if (p.value.strings.size() != 1 || !p.value.numbers.empty())
        return Fail(p.at, "'Option \"searchpath\"' parameter " + Quote(p.value.name) + " expects 1 string");
    const std::string& text = p.value.strings[0];
    std::vector<std::string> path;
    for (size_t begin = 0;;) {
        size_t end = std::min(text.find(':', begin), text.size());
        std::string dir = text.substr(begin, end - begin);
        if (dir == "&")
            path.insert(path.end(), out->begin(), out->end());
        else if (!dir.empty() && dir != "@")
            path.push_back(dir);
        if (end == text.size()) break;
        begin = end + 1;
    }
    *out = std::move(path);
    return true;
}

// Hider: affray has one hider, a ray tracer that takes each sample's nearest hit, which is what
// "hidden" with "depthfilter" "min" computes. "jitter" places the samples; other hiders and
// parameters change sampling or speed only and are ignored with a warning.
bool RibParser::DoHider(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!BeforeWorld(r) || !LeadingString(r, "a hider name", &name) || !ParamList(r, 1, &params)) return false;
    m_hider = name;  // "photon" makes the frame a photon map pass (SkipReason)
    if (name != "hidden" && name != "photon")
        Warn(r.at, "hider " + Quote(name) + " is not supported; rendering with affray's ray tracer (as \"hidden\")");
    const std::string context = "'Hider \"" + name + "\"'";
    for (const RibParam& p : params) {
        if (p.value.name == "jitter") {
            double jitter;
            if (!ParamNumbers(p, context, 1, &jitter)) return false;
            if (jitter != 0 && jitter != 1)
                return Fail(p.at, context + " parameter 'jitter' must be 0 or 1, got " + FormatNumber(jitter));
            m_scene.camera.jitter = jitter == 1;
        } else if (p.value.name == "depthfilter") {
            if (p.value.strings.size() != 1 || !p.value.numbers.empty())
                return Fail(p.at, context + " parameter 'depthfilter' expects 1 string");
            const std::string& filter = p.value.strings[0];
            if (filter != "min")
                Warn(p.at, context + " depthfilter " + Quote(filter) +
                               " is not supported; depth is each sample's nearest hit (\"min\")");
        } else {
            Warn(p.at, context + " parameter " + Quote(p.value.name) + " is not supported; ignored");
        }
    }
    return true;
}

// Declare "name" "declaration": later parameter lists may give `name` without a declaration.
bool RibParser::DoDeclare(const RibRequest& r) {
    if (r.args.size() != 2 || r.args[0].isArray || !r.args[0].StringsP() || r.args[1].isArray || !r.args[1].StringsP())
        return Fail(r.at, "'Declare' expects 2 strings (name declaration)");
    const std::string& name = r.args[0].strings[0];
    const std::string& declaration = r.args[1].strings[0];
    if (name.empty() || name.find_first_of(" \t\n\r") != std::string::npos)
        return Fail(r.args[0].at, "'Declare' name " + Quote(name) + " must be one word");
    RibDeclaration parsed;
    std::string problem;
    if (!RibDeclaration::Parse(declaration, &parsed, &problem)) return Fail(r.args[1].at, "'Declare': " + problem);
    m_declared[name] = declaration;
    return true;
}

// The scene's level of detail (attributes): a Reyes renderer dices into micropolygons of
// ShadingRate pixels' area, about sqrt(ShadingRate) pixels a side, and GeometricApproximation
// "flatness" is the largest distance in pixels it allows between its facets and the surface.
// affray certifies every hit to its tolerance in pixels (0.5 by default); a primitive whose
// scene asks for less accuracy, 0.5 sqrt(ShadingRate) or the flatness, whichever is larger, is
// certified to that instead (PrimitiveAttributes::sceneTolerance; --tolerance overrides). A finer
// request keeps the default: affray shades every ray hit, so a finer shading rate has nothing
// more to shade.
bool RibParser::DoShadingRate(const RibRequest& r) {
    double rate;
    if (!Numbers(r, 1, "size", &rate)) return false;
    if (!(rate > 0)) return Fail(r.at, "'ShadingRate' must be positive, got " + FormatNumber(rate));
    m_state.shadingRate = rate;
    if (rate > 1)
        Note(r.at, "'ShadingRate' " + FormatNumber(rate) + ": the primitives that follow are certified to " +
                       FormatNumber(0.5 * std::sqrt(rate)) + " pixels, not 0.5 (unless --tolerance is given)");
    return true;
}

bool RibParser::DoGeometricApproximation(const RibRequest& r) {
    std::string type;
    if (!LeadingString(r, "an approximation type", &type)) return false;
    RibRequest value = r;
    value.args.erase(value.args.begin());
    double amount;
    if (!Numbers(value, 1, "value", &amount)) return false;
    if (type != "flatness") {
        Warn(r.at, "'GeometricApproximation \"" + type + "\"' does not apply to affray; ignored");
        return true;
    }
    if (!(amount >= 0))
        return Fail(r.at, "'GeometricApproximation \"flatness\"' must not be negative, got " + FormatNumber(amount));
    m_state.flatness = amount;
    if (amount > 0.5)
        Note(r.at, "'GeometricApproximation \"flatness\"' " + FormatNumber(amount) +
                       ": the primitives that follow are certified to " + FormatNumber(amount) +
                       " pixels, not 0.5 (unless --tolerance is given)");
    return true;
}

bool RibParser::DoShadingInterpolation(const RibRequest& r) {
    std::string type;
    if (!LeadingString(r, "an interpolation type", &type)) return false;
    if (r.args.size() > 1) return Fail(r.at, "'ShadingInterpolation' expects one string");
    if (type != "constant" && type != "smooth")
        return Fail(r.args[0].at,
                    "unknown shading interpolation " + Quote(type) + " (expected \"constant\" or \"smooth\")");
    Warn(r.at, "'ShadingInterpolation' does not apply: affray shades every ray hit; ignored");
    return true;
}

// ArchiveRecord "comment"|"structure"|"verbatim" "text": a comment in the file, as # is.
bool RibParser::DoArchiveRecord(const RibRequest& r) {
    std::string type;
    if (!LeadingString(r, "a record type", &type)) return false;
    if (type == "verbatim") return Fail(r.at, "'ArchiveRecord \"verbatim\"' (RIB text in a string) is not supported");
    return true;
}

}  // namespace affray::rib
