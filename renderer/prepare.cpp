// renderer/prepare.cpp: Renderer::Prepare, from a scene as read to one ready to render: the image's
// limits checked, MakeTexture requests run, every displacement instance compiled (once per shader
// and what it reads of the scene: compiler/shader_cache.h) and specialised per surface kind, the
// lights grouped, each primitive's box bounded over a grid of its domain (on the Renderer's
// threads) and the BVH built over the boxes.
#include "renderer/renderer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <unordered_map>

#include "compiler/shader_cache.h"
#include "diag/check.h"
#include "diag/limits.h"
#include "renderer/film.h"
#include "renderer/shade.h"
#include "scene/geometry/camera.h"
#include "scene/refine.h"
#include "texture/texture.h"

namespace affray::renderer {

std::vector<compiler::ConstantGlobal> ConstantGlobals(const BaseSurface& base, const glm::dvec3& eye,
                                                      double shutterOpen, double shutterClose) {
    using vm::Global;
    std::vector<compiler::ConstantGlobal> out = {{Global::E, {eye.x, eye.y, eye.z}},
                                                 {Global::du, {kParametricStep, 0, 0}},
                                                 {Global::dv, {kParametricStep, 0, 0}},
                                                 {Global::time, {shutterOpen, 0, 0}},
                                                 {Global::dtime, {shutterClose - shutterOpen, 0, 0}}};
    if (base.kind() != BaseSurface::Kind::BilinearPatch) return out;
    const BilinearPatch& patch = base.patch();
    // The tangents along the mesh's (u,v), scaled by ds/du and dt/dv as SetPatchGlobals scales them.
    glm::dvec3 a = patch.a() * PatchRate(base.range, 0), b = patch.b() * PatchRate(base.range, 1),
               n = patch.flatNormal();
    if (base.flipNormal) n = -n;
    if (patch.flat() && std::isfinite(glm::dot(n, n))) {
        // The same tangents and normal everywhere, the values SetPatchGlobals would give.
        out.push_back({Global::dPdu, {a.x, a.y, a.z}});
        out.push_back({Global::dPdv, {b.x, b.y, b.z}});
        out.push_back({Global::N, {n.x, n.y, n.z}});
        out.push_back({Global::Ng, {n.x, n.y, n.z}});
    }
    return out;
}

namespace {

/// NAME.sl or, failing that, NAME.afb (compiled), in the first directory that has either. A name
/// given with a compiled shader's extension, as scenes exported for one renderer name them
/// (prman's .slo, BMRT's .slc, 3Delight's .sdl, Aqsis's .slx, Pixie's .sdr) or with .sl, is the
/// shader of its stem.
std::string FindShader(const std::string& name, const std::vector<std::string>& paths) {
    for (const std::string& dir : paths) {
        for (const char* extension : {".sl", ".afb"}) {
            std::filesystem::path candidate = std::filesystem::path(dir) / (name + extension);
            std::error_code ec;
            if (std::filesystem::is_regular_file(candidate, ec)) return candidate.string();
        }
    }
    const std::string extension = std::filesystem::path(name).extension().string();
    for (const char* compiled : {".sl", ".slo", ".slc", ".sdl", ".slx", ".sdr"})
        if (extension == compiled) return FindShader(name.substr(0, name.size() - extension.size()), paths);
    return {};
}

/// A shader request's parameter values as the compiler takes them; "" or what is wrong.
std::string OverridesOf(const ShaderRef& ref, std::vector<compiler::ParamOverride>* out) {
    for (const ParamValue& p : ref.params) {
        if (p.strings.size() > 1)
            return "parameter '" + p.name + "' takes one string, got " + std::to_string(p.strings.size());
        if (p.strings.empty())
            out->emplace_back(p.name, p.numbers);
        else
            out->push_back(compiler::ParamOverride::String(p.name, p.strings[0]));
    }
    return {};
}

/// Why the compilation `result` of a shader the scene names as a `want` shader cannot render
/// it: "" if it can.
std::string UnusableBecause(const compiler::CompileResult& result, lang::ShaderKind want) {
    if (result.ok() && result.shader->kind != want)
        return "it is a " + std::string(lang::ToString(result.shader->kind)) + " shader";
    if (!result.paramErrors.empty()) return result.paramErrors.front();
    if (!result.ok()) return "it does not compile";
    return {};
}

/// The largest magnitude a bound of P may reach for the intersector to measure it: the ray-frame
/// test squares widths, which overflow past about 1e154.
constexpr double kMeasurableLimit = 1e150;

/// The ranges of P's coordinates over the cells of an n x n grid of a primitive's domain.
using CellRanges = std::vector<std::array<vm::Interval, 3>>;

/// The cells bounded with number type N.
template <class N>
CellRanges BoundCells(const Primitive& prim, const glm::dvec3& eye, int n) {
    vm::Interpreter<N> interp(prim.bound());
    const vm::ProgramOutput& output = *prim.bound().findOutput("P");
    CellRanges cells;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Vec3<N> p = EvaluateOnSurface(interp, prim.base(), double(i) / n, double(i + 1) / n, double(j) / n,
                                          double(j + 1) / n, eye, output);
            cells.push_back({RangeOf(vm::ValueOf(p.x)), RangeOf(vm::ValueOf(p.y)), RangeOf(vm::ValueOf(p.z))});
        }
    return cells;
}

/// The cells bounded with B (Affine or Interval), or its dual if the bound program takes
/// derivatives.
template <class B>
CellRanges BoundCellsIn(const Primitive& prim, const glm::dvec3& eye, int n) {
    return prim.bound().usesDerivatives() ? BoundCells<vm::Dual<B>>(prim, eye, n) : BoundCells<B>(prim, eye, n);
}

/// The grid the Renderer::Prepare checks and the BVH boxes use: kGridCells across for a scene of a few
/// primitives, coarser for many (a mesh of thousands of faces), so that the whole scene costs
/// about kGridCells^2 * kGridPrimitives bounds, and never fewer than 2 x 2 cells per primitive up
/// to kOneCellPrimitives primitives, one cell past them (a mesh of a million faces costs a million
/// bounds). The subdivision scene of bench/real (26,560 patches) renders 9 % slower with one cell
/// per patch (its boxes looser), which its 4 x 26,560 box bounds do not pay for.
/// A coarser grid only loosens a primitive's box (its bound's union over fewer cells), never the
/// bounds the intersector tests.
constexpr int kGridCells = 8;
/// Primitives boxed per job of the pool: small enough to balance threads, large enough that
/// taking the next chunk costs nothing beside bounding it.
constexpr size_t kBoxGrain = 16;
constexpr size_t kGridPrimitives = 64;
constexpr size_t kOneCellPrimitives = size_t{1} << 17;
int GridCellsFor(size_t primitives) {
    if (primitives <= kGridPrimitives) return kGridCells;
    if (primitives > kOneCellPrimitives) return 1;
    const double n = kGridCells * std::sqrt(double(kGridPrimitives) / double(primitives));
    return std::max(2, static_cast<int>(n));
}

/// Whether P's bound is measurable (finite, within kMeasurableLimit) over at least one cell.
bool MeasurableSomewhere(const CellRanges& cells) {
    for (const auto& cell : cells) {
        bool measurable = true;
        for (const vm::Interval& r : cell)
            measurable = measurable && !r.isUnbounded() && std::fabs(r.lo()) < kMeasurableLimit &&
                         std::fabs(r.hi()) < kMeasurableLimit;
        if (measurable) return true;
    }
    return false;
}

/// The finest grid UnboundedEverywhere tries (64 x 64: 4096 cells per bounding mode, evaluated only
/// for a surface that no coarser grid could bound).
constexpr int kFinestCheckCells = 64;

/// An error if no cell of the grids of the patch, `cells` across and then twice, four and eight...
/// times finer up to kFinestCheckCells, has a measurable bound in either bounding mode
/// (`intervalCells` are the interval bounds of the first grid, looked at first as they are already
/// paid for): every region would then survive the ray test down to the depth
/// limit, 4^depth regions per ray, a render that never ends. A shader whose bound is unbounded
/// where a region straddles a branch (a square root on the side not taken) is bounded on finer
/// cells, so one grid is not enough. Names the instance's parameters that are large enough to be
/// the cause. Empty if the surface can be bounded somewhere.
std::string UnboundedEverywhere(const Primitive& prim, const ShaderRef& ref, const glm::dvec3& eye, int cells,
                                const CellRanges& intervalCells) {
    if (MeasurableSomewhere(intervalCells)) return {};
    for (int n = cells; n <= kFinestCheckCells; n *= 2) {
        if (MeasurableSomewhere(BoundCellsIn<vm::Affine>(prim, eye, n))) return {};
        if (n != cells && MeasurableSomewhere(BoundCellsIn<vm::Interval>(prim, eye, n))) return {};
    }
    std::string culprits;
    for (const ParamValue& p : ref.params)
        for (double x : p.numbers)
            if (std::fabs(x) >= 1e100) {
                char value[32];
                std::snprintf(value, sizeof value, "%g", x);
                culprits += std::string(culprits.empty() ? "" : ", ") + "'" + p.name + "' = " + value;
                break;
            }
    std::string message = "the displaced surface of shader '" + ref.name +
                          "' cannot be bounded over any part of the patch (NaN, infinity or values past 1e150 in "
                          "every region), so no ray could finish";
    if (!culprits.empty()) message += "; parameter " + culprits + " is too large";
    return message;
}

/// The box of the displaced surface over its whole domain: the union of the bounds of the cells
/// of a grid (tighter than one bound over everything). Infinite if any cell's bound is unbounded:
/// the BVH then offers the primitive to every ray.
Box UnionBox(const CellRanges& cells) {
    Box box;
    for (const auto& cell : cells)
        for (int c = 0; c < 3; ++c) {
            const vm::Interval& r = cell[c];
            if (r.isUnbounded()) {
                box.lo[c] = -INFINITY;
                box.hi[c] = INFINITY;
            } else {
                box.lo[c] = std::min(box.lo[c], r.lo());
                box.hi[c] = std::max(box.hi[c], r.hi());
            }
        }
    return box;
}

/// The box a moving primitive sweeps: `placed` (its box where its path's first time placed it)
/// carried to each time of the path. Between two times every point moves on a straight line
/// (MotionPath), so the boxes at the times hold it throughout; padded for the rounding of the
/// carrying. A box that is not finite reaches everywhere.
Box SweptBox(const Box& placed, const MotionPath& path) {
    Box swept;
    if (!std::isfinite(placed.lo.x + placed.lo.y + placed.lo.z + placed.hi.x + placed.hi.y + placed.hi.z)) {
        swept.lo = glm::dvec3(-INFINITY);
        swept.hi = glm::dvec3(INFINITY);
        return swept;
    }
    const glm::dmat4 fromPlaced = glm::inverse(path.matrices.front());
    for (const glm::dmat4& m : path.matrices) {
        const glm::dmat4 carry = m * fromPlaced;
        for (int c = 0; c < 8; ++c) {
            const glm::dvec3 corner((c & 1) ? placed.hi.x : placed.lo.x, (c & 2) ? placed.hi.y : placed.lo.y,
                                    (c & 4) ? placed.hi.z : placed.lo.z);
            swept.Extend(glm::dvec3(carry * glm::dvec4(corner, 1.0)));
        }
    }
    const glm::dvec3 pad = 1e-12 * (glm::abs(swept.lo) + glm::abs(swept.hi)) + 1e-300;
    swept.lo -= pad;
    swept.hi += pad;
    return swept;
}

compiler::Matrix4 RowMajor(const glm::dmat4& m) {
    compiler::Matrix4 out{};
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) out[4 * row + col] = m[col][row];  // glm is column-major
    return out;
}

bool IsAffine(const compiler::Matrix4& m) { return m[12] == 0 && m[13] == 0 && m[14] == 0 && m[15] == 1; }

/// The spaces a shader on `patch` sees. "current" is world space: P is computed there.
compiler::Spaces SpacesOf(const SceneDesc& scene, const glm::dmat4& objectToWorld, const glm::dmat4& shaderToWorld,
                          const std::map<std::string, glm::dmat4>* scoped) {
    const CameraDesc& camera = scene.camera;
    auto space = [](const glm::dmat4& toWorld) {
        return compiler::SpaceTransform{RowMajor(toWorld), RowMajor(glm::inverse(toWorld))};
    };
    compiler::Spaces spaces;
    for (const auto& [name, toWorld] : scene.coordinateSystems) spaces[name] = space(toWorld);
    if (scoped)
        for (const auto& [name, toWorld] : *scoped) spaces[name] = space(toWorld);
    spaces["world"] = compiler::SpaceTransform{};
    spaces["object"] = space(objectToWorld);
    spaces["shader"] = space(shaderToWorld);
    spaces["camera"] = space(glm::inverse(camera.worldToCamera));
    return spaces;
}

/// The spaces of a shader on `patch` (its request `shader`: the displacement's unless given).
compiler::Spaces SpacesOf(const SceneDesc& scene, const PrimitiveAttributes& patch, const ShaderRef* shader = nullptr) {
    if (!shader && patch.displacement) shader = &*patch.displacement;
    return SpacesOf(scene, patch.objectToWorld, shader ? shader->shaderToWorld : patch.objectToWorld,
                    patch.scopedSpaces.get());
}

/// `path` as the scene names it: as written if absolute, else from the RIB file's directory.
std::string FromSceneDir(const SceneDesc& scene, const std::string& path) {
    const std::filesystem::path p(path);
    return p.is_absolute() ? path : (std::filesystem::path(scene.path).parent_path() / p).string();
}

/// The options and attributes a shader on `patch` may query (option(), attribute(), depth()):
/// those of RI Spec 3.2 tables 15.4 and 15.5 that the scene holds.
compiler::SceneFacts FactsOf(const SceneDesc& scene, const PrimitiveAttributes& patch) {
    const CameraDesc& camera = scene.camera;
    const double frameAspect = camera.frameAspectRatio.value_or(camera.xres * camera.pixelAspect / camera.yres);
    compiler::SceneFacts facts;
    auto numbers = [](std::vector<double> values) { return compiler::FactValue{std::move(values), std::nullopt}; };
    facts.options["Format"] = numbers({double(camera.xres), double(camera.yres), camera.pixelAspect});
    facts.options["DeviceResolution"] = facts.options["Format"];
    facts.options["FrameAspectRatio"] = numbers({frameAspect});
    const glm::dvec4& crop = camera.cropWindow;
    facts.options["CropWindow"] = numbers({crop[0], crop[1], crop[2], crop[3]});
    facts.options["Clipping"] = numbers({camera.nearClip, camera.farClip});
    facts.attributes["Sides"] = numbers({patch.twoSided ? 2.0 : 1.0});
    // Option "searchpath" "texture", relative directories taken from the RIB file's, then that
    // directory itself.
    for (const std::string& dir : scene.textureSearchPath) facts.textureSearchPath.push_back(FromSceneDir(scene, dir));
    facts.textureSearchPath.push_back(std::filesystem::path(scene.path).parent_path().string());
    return facts;
}

/// The scene's MakeTexture requests, in order (relative paths from the RIB file's directory); a
/// texture newer than its picture is kept, as make would.
void MakeTextures(const SceneDesc& desc, diag::Report* report) {
    namespace fs = std::filesystem;
    for (const SceneDesc::MakeTextureDesc& m : desc.makeTextures) {
        const fs::path picture = FromSceneDir(desc, m.picture), texture = FromSceneDir(desc, m.texture);
        std::error_code ec, ec2;
        const auto made = fs::last_write_time(texture, ec), source = fs::last_write_time(picture, ec2);
        if (!ec && !ec2 && made >= source) continue;
        texture::Wrap swrap = texture::Wrap::Periodic, twrap = texture::Wrap::Periodic;
        texture::ParseWrap(m.swrap, &swrap);
        texture::ParseWrap(m.twrap, &twrap);
        std::string error;
        // As a renderer's texture maker does, a failure is reported and the render goes on: a
        // shader that reads the texture then fails to compile, naming the file.
        if (!texture::MakeTexture(picture.string(), texture.string(), swrap, twrap, &error) && report) {
            const std::string& file = m.file.empty() ? desc.path : m.file;
            report->warning({file, m.line, m.column, diag::ReadLine(file, m.line)}, error);
        }
    }
}

/// The image-pixels, pixel-samples and film-mb limits (diag/limits.h) for `camera`'s image with
/// the channels `displayMode` asks for; "" or the error.
std::string CheckImageLimits(const CameraDesc& camera, const std::string& displayMode) {
    using diag::Limit;
    const int64_t pixels = int64_t{camera.xres} * camera.yres;
    if (pixels > diag::LimitValue(Limit::ImagePixels))
        return "the image of " + std::to_string(camera.xres) + "x" + std::to_string(camera.yres) +
               " pixels is too large " + diag::LimitNote(Limit::ImagePixels);
    if (std::max(camera.xsamples, camera.ysamples) > diag::LimitValue(Limit::PixelSamples))
        return "the image has " + std::to_string(camera.xsamples) + "x" + std::to_string(camera.ysamples) +
               " samples per pixel, more than allowed " + diag::LimitNote(Limit::PixelSamples);
    DisplayChannels channels;
    std::string ignored;  // an unknown mode is reported where the image is made
    ParseDisplayMode(displayMode, &channels, &ignored);
    const int64_t floats = 4 + static_cast<int64_t>(ChannelNames(channels).size());
    const int64_t mb = (pixels * floats * int64_t{sizeof(float)} + (int64_t{1} << 20) - 1) >> 20;
    if (mb > diag::LimitValue(Limit::FilmMb))
        return "the film needs " + std::to_string(mb) + " MiB for " + std::to_string(pixels) + " pixels of " +
               std::to_string(floats) + " channels " + diag::LimitNote(Limit::FilmMb);
    return {};
}

}  // namespace

Box DisplacedBox(const Primitive& prim, const glm::dvec3& eye, int cells) {
    return UnionBox(BoundCellsIn<vm::Interval>(prim, eye, cells));
}

bool Renderer::Prepare(SceneDesc input, PreparedScene* out, diag::Report* report) const {
    const std::vector<std::string>& shaderPaths = m_options.shaderPaths;
    const lang::PreprocessOptions& preprocess = m_options.preprocess;
    auto fail = [&](const diag::Location& where, std::string message) {
        if (report) report->error(where, std::move(message));
        return false;
    };
    // Before anything is refined, compiled or allocated.
    if (std::string problem = CheckImageLimits(input.camera, input.displayMode); !problem.empty())
        return fail({input.path}, std::move(problem));
    // The meshes as read split and refined (scene/refine.h), several at once.
    const auto parallelFor = [&](size_t n, const std::function<void(size_t)>& body) {
        m_pool.ForEach(n, [&](size_t i, int) { body(i); });
    };
    if (!RefineScene(&input, report, parallelFor)) return false;
    // Moved, not copied: the meshes' arrays stay where refinement put them.
    out->desc = std::move(input);
    const SceneDesc& desc = out->desc;
    out->primitives.clear();
    out->programs.clear();  // (a PreparedScene prepared again holds only its new programs)
    out->identityDigest.clear();
    MakeTextures(desc, report);
    const glm::dvec3 eye = Camera(desc.camera).Position();
    compiler::ShaderCache cache;
    // The scene's search path first, relative directories taken from the RIB file's.
    std::vector<std::string> searchPath;
    for (const std::string& dir : desc.shaderSearchPath) searchPath.push_back(FromSceneDir(desc, dir));
    searchPath.insert(searchPath.end(), shaderPaths.begin(), shaderPaths.end());
    // The distinct light lists of the primitives (Illuminate), numbered in order of first use
    // after set 0, every light.
    std::map<std::vector<int>, int> lightSetKeys;
    std::vector<int> allLights(desc.lights.size());
    for (size_t i = 0; i < allLights.size(); ++i) allLights[i] = static_cast<int>(i);
    lightSetKeys[allLights] = 0;
    auto lightSetOf = [&](const PrimitiveAttributes& p) {
        if (!p.lights) return 0;
        std::vector<int> key;
        for (int light : *p.lights)
            if (light >= 0 && static_cast<size_t>(light) < desc.lights.size()) key.push_back(light);
        std::sort(key.begin(), key.end());
        key.erase(std::unique(key.begin(), key.end()), key.end());
        return lightSetKeys.emplace(key, static_cast<int>(lightSetKeys.size())).first->second;
    };
    // Where a Displacement or Surface request is in the RIB file (its line is read again only for a message).
    auto requestAt = [&](const ShaderRef& ref) {
        const std::string& file = ref.file.empty() ? desc.path : ref.file;
        return diag::Location(file, ref.line, ref.column, diag::ReadLine(file, ref.line));
    };
    // A shader name's file ("" if not found), looked up once whatever kind of request names it,
    // and the search path as "not found" messages give it.
    std::map<std::string, std::string> shaderFiles;
    auto fileOf = [&](const std::string& name) -> const std::string& {
        auto [known, added] = shaderFiles.try_emplace(name);
        if (added) known->second = FindShader(name, searchPath);
        return known->second;
    };
    std::string searched;
    for (const std::string& p : searchPath) searched += (searched.empty() ? "" : ", ") + p;
    // The lights of light set `index` (the indices of its key; every light for set 0).
    auto lightSetKey = [&](int index) {
        for (const auto& [key, i] : lightSetKeys)
            if (i == index) return key;
        return allLights;
    };
    // Displacement and surface shaders' names warned about in this scene, once each.
    std::set<std::string> displacementWarned, surfaceWarned;
    // A warning once per sentence over the frames this renderer prepares.
    auto warnRun = [&](const diag::Location& at, const std::string& sentence) {
        if (!report) return;
        std::lock_guard<std::mutex> lock(m_warnedMutex);
        if (m_warned.insert(sentence).second) report->warning(at, sentence);
    };
    // A surface or light shader's diagnostics, its errors as warnings (the render goes on
    // without it), each once over the run.
    auto warnDiagnostics = [&](const diag::Report& diagnostics) {
        for (diag::Diagnostic d : diagnostics.all()) {
            d.severity = diag::Severity::Warning;
            std::lock_guard<std::mutex> lock(m_warnedMutex);
            if (report && m_warned.insert(diag::Format(d)).second) report->add(d);
        }
    };
    // The surface shader of `attributes` (its Surface request `ref`) lit by the lights `key`
    // (indices into desc.lights; the scene's default light if it has none), or null where the
    // built-in model renders it: the shader is not found (a warning for names affray has no
    // model of), or does not compile (its errors are warnings, then the model renders it).
    bool defaultLights = false;  // set once the light shaders are compiled (below)
    auto surfaceOf = [&](const PrimitiveAttributes& attrs, const ShaderRef& ref,
                         const std::vector<int>& key) -> std::shared_ptr<const compiler::CompiledShader> {
        const bool builtIn =
            ref.name == "matte" || ref.name == "metal" || ref.name == "constant" || ref.name == "plastic";
        const std::string& path = fileOf(ref.name);
        auto warnOnce = [&](const std::string& message) {
            if (surfaceWarned.insert(ref.name).second) warnRun(requestAt(ref), message);
        };
        if (path.empty()) {
            if (!builtIn)
                warnOnce("surface shader '" + ref.name + "' not found (searched " + searched + "); using \"plastic\"");
            return nullptr;
        }
        std::vector<compiler::ParamOverride> overrides;
        std::string problem = OverridesOf(ref, &overrides);
        compiler::SceneFacts facts = FactsOf(desc, attrs);
        if (defaultLights) facts.lightCategories = {""};  // the default key light (below)
        for (int light : key)
            if (RoleOf(desc.lights[size_t(light)]) == LightRole::Lit)
                facts.lightCategories.push_back(CategoryOf(desc.lights[size_t(light)]));
        const compiler::Spaces spaces = SpacesOf(desc, attrs, &ref);
        compiler::CompileResult result;
        if (problem.empty()) {
            result = cache.Load(path, overrides, preprocess, &spaces, &facts);
            // The shader's warnings as they are, its errors as warnings: the render goes on.
            warnDiagnostics(result.diagnostics);
            problem = UnusableBecause(result, lang::ShaderKind::Surface);
        }
        if (!problem.empty()) {
            warnOnce("surface shader '" + ref.name + "' in " + path + " cannot be used (" + problem + "); using " +
                     (builtIn ? "affray's built-in \"" + ref.name + "\"" : std::string("\"plastic\"")));
            return nullptr;
        }
        for (const std::string& sentence : result.undeclared)  // as tools/commands.cpp's WarnUndeclared
            warnRun(requestAt(ref), sentence + "; ignored");
        return result.shader;
    };
    // Each request's attributes (shared by its primitives: a mesh's faces) are looked at once:
    // the shader instance compiled, its generic programs and the lights.
    struct Instance {
        std::shared_ptr<const compiler::CompiledShader> shader;   // null: no displacement (the identity)
        std::shared_ptr<const compiler::CompiledShader> surface;  // null: the built-in model
        int lightSet = 0;
        /// The programs of the primitives whose surfaces have no constants beyond E, du, dv
        /// (every kind but the bilinear patch), once made.
        const PrimitivePrograms* general = nullptr;
    };
    std::unordered_map<const PrimitiveAttributes*, Instance> instances;
    const vm::Program identity = vm::IdentityProgram();
    // Specialising a program for a surface's constant globals (below) gives the same program for
    // every surface with the same constants (E, du and dv for all but flat bilinear patches): made
    // once per shader instance and constants, shared by the others.
    std::map<std::pair<const void*, std::vector<uint64_t>>, const PrimitivePrograms*> specialised;
    auto specialise = [&](const Instance& instance, const BaseSurface& base) {
        const std::vector<compiler::ConstantGlobal> constants =
            ConstantGlobals(base, eye, desc.camera.shutterOpen, desc.camera.shutterClose);
        // (The values by their bits: the same bits fold to the same program, a NaN included.)
        std::pair<const void*, std::vector<uint64_t>> key{instance.shader.get(), {}};
        key.second.push_back(std::bit_cast<uint64_t>(instance.surface.get()));
        for (const compiler::ConstantGlobal& c : constants) {
            key.second.push_back(static_cast<uint64_t>(c.global));
            for (double x : c.value) key.second.push_back(std::bit_cast<uint64_t>(x));
        }
        auto [found, added] = specialised.try_emplace(std::move(key), nullptr);
        if (added) {
            std::vector<std::string> unused;  // no overrides here: nothing can go wrong
            const vm::Program& bound = instance.shader ? instance.shader->bound : identity;
            const vm::Program& shade = instance.shader ? instance.shader->shade : identity;
            out->programs.push_back({instance.shader, *compiler::Specialise(bound, {}, &unused, constants),
                                     *compiler::Specialise(shade, {}, &unused, constants), instance.surface});
            found->second = &out->programs.back();
        }
        return found->second;
    };
    // Light shaders, before the surfaces whose light loops visit them: a LightSource's .sl,
    // found as surface shaders are, compiled once per light with its parameter values; a point,
    // vector or normal value the scene gives is in the light's shader space, and mapped to world
    // space as RenderMan maps it (so compiled again when there is one). Not found, or not
    // compiling: the standard light of its name renders it, or for another name no light (one
    // warning per name over the run).
    std::set<std::string> lightWarned;
    for (LightDesc& light : out->desc.lights) {
        if (!light.shader) continue;
        const ShaderRef& ref = *light.shader;
        const std::string& path = fileOf(ref.name);
        auto warnOnce = [&](const std::string& message) {
            if (lightWarned.insert(ref.name).second) warnRun(requestAt(ref), message);
        };
        const std::string fallback = light.builtIn ? "using affray's built-in \"" + ref.name + "\"" : "ignored";
        if (path.empty()) {
            if (!light.builtIn)
                warnOnce("light source '" + ref.name + "' not found (searched " + searched + "); ignored");
            continue;
        }
        std::vector<compiler::ParamOverride> overrides;
        std::string problem = OverridesOf(ref, &overrides);
        const compiler::SceneFacts facts = FactsOf(desc, PrimitiveAttributes{});
        const compiler::Spaces spaces = SpacesOf(desc, ref.shaderToWorld, ref.shaderToWorld, nullptr);
        compiler::CompileResult result;
        auto compile = [&] {
            result = cache.Load(path, overrides, preprocess, &spaces, &facts);
            warnDiagnostics(result.diagnostics);
        };
        if (problem.empty()) compile();
        if (problem.empty() && result.ok() && result.shader->kind == lang::ShaderKind::Light) {
            bool mapped = false;
            for (compiler::ParamOverride& o : overrides) {
                if (o.text || o.numbers.size() != 3) continue;
                for (const compiler::ParamInfo& info : result.shader->params) {
                    if (info.name != o.name || !compiler::IsSpatial(info.type) || info.arraySize >= 0) continue;
                    const glm::dvec3 x(o.numbers[0], o.numbers[1], o.numbers[2]);
                    const glm::dmat4& m = ref.shaderToWorld;
                    const glm::dvec3 y = info.type == compiler::Type::Point ? glm::dvec3(m * glm::dvec4(x, 1.0))
                                         : info.type == compiler::Type::Vector
                                             ? glm::dvec3(m * glm::dvec4(x, 0.0))
                                             : glm::transpose(glm::inverse(glm::dmat3(m))) * x;
                    o.numbers = {y.x, y.y, y.z};
                    mapped = true;
                }
            }
            if (mapped) compile();
        }
        if (problem.empty()) problem = UnusableBecause(result, lang::ShaderKind::Light);
        if (!problem.empty()) {
            warnOnce("light source '" + ref.name + "' in " + path + " cannot be used (" + problem + "); " + fallback);
            continue;
        }
        for (const std::string& sentence : result.undeclared) warnRun(requestAt(ref), sentence + "; ignored");
        light.program = result.shader;
    }

    // A scene with no light that gives light (none, or only light shaders that were not found)
    // gets affray's default lights (below), as a scene without lights always has.
    defaultLights = std::none_of(desc.lights.begin(), desc.lights.end(),
                                 [](const LightDesc& l) { return RoleOf(l) != LightRole::None; });

    size_t elements = 0;
    for (const PrimitiveDesc& p : desc.primitives) elements += p.elements;
    out->primitives.reserve(elements);
    for (const PrimitiveDesc& patch : desc.primitives) {
        AFFRAY_CHECK(!patch.unrefined);  // RefineScene refined every mesh as read
        const PrimitiveAttributes& attributes = *patch.attributes;
        auto [entry, newAttributes] = instances.try_emplace(&attributes);
        Instance& instance = entry->second;
        if (newAttributes) {
            instance.lightSet = lightSetOf(attributes);
            // The shader's file, looked up once per name; a shader that is not found leaves the
            // surface undisplaced, as prman does, with one warning per name (a scene exported with
            // shaders its renderer had but this machine has not).
            std::string path;
            if (attributes.displacement) {
                const ShaderRef& ref = *attributes.displacement;
                path = fileOf(ref.name);
                if (path.empty() && report && displacementWarned.insert(ref.name).second)
                    report->warning(requestAt(ref), "shader '" + ref.name + "' not found (searched " + searched +
                                                        "); its surfaces render undisplaced");
            }
            if (!path.empty()) {
                const ShaderRef& ref = *attributes.displacement;
                auto where = [&] { return requestAt(ref); };
                std::vector<compiler::ParamOverride> overrides;
                if (std::string problem = OverridesOf(ref, &overrides); !problem.empty()) return fail(where(), problem);
                const compiler::Spaces spaces = SpacesOf(desc, attributes);
                const compiler::SceneFacts facts = FactsOf(desc, attributes);
                compiler::CompileResult result = cache.Load(path, overrides, preprocess, &spaces, &facts);
                // The shader's own diagnostics (its warnings too), then what the scene asked of it.
                if (report) report->add(result.diagnostics);
                if (!result.ok()) {
                    for (const std::string& e : result.paramErrors) fail(where(), e);
                    if (result.paramErrors.empty()) fail(where(), "cannot compile shader '" + ref.name + "'");
                    return false;
                }
                instance.shader = result.shader;
                for (const std::string& name : instance.shader->genericBound.spaces) {
                    if (spaces.count(name) && !IsAffine(spaces.at(name).toCurrent))
                        return fail(where(), "shader '" + ref.name + "' uses coordinate space '" + name +
                                                 "', which the scene makes projective (not supported)");
                }
            }
            if (attributes.surface.shader)
                instance.surface = surfaceOf(attributes, *attributes.surface.shader, lightSetKey(instance.lightSet));
        }
        Primitive prim;
        prim.desc = &patch;
        prim.lightSet = instance.lightSet;
        if (patch.base.kind() == BaseSurface::Kind::BilinearPatch) {
            prim.programs = specialise(instance, patch.base);
        } else {
            if (!instance.general) instance.general = specialise(instance, patch.base);
            prim.programs = instance.general;
        }
        // A mesh's pieces or patches: one primitive each, the same but for the element.
        for (uint32_t e = 0; e < patch.elements; ++e) {
            prim.element = e;
            out->primitives.push_back(prim);
        }
    }

    // Each primitive's box, and the check that its displaced surface can be bounded somewhere:
    // a shader run over a grid of cells per primitive, the costly part of preparing a scene of
    // many primitives, spread over the pool's threads in chunks of kBoxGrain primitives.
    const int cells = GridCellsFor(out->primitives.size());
    std::vector<std::string> problems(out->primitives.size());
    std::vector<Box> boxes(out->primitives.size());
    m_pool.ForEach(
        out->primitives.size(),
        [&](size_t i, int) {
            Primitive& prim = out->primitives[i];
            const CellRanges intervalCells = BoundCellsIn<vm::Interval>(prim, eye, cells);
            if (prim.shader())  // a displacement whose shader was found
                problems[i] = UnboundedEverywhere(prim, *prim.attributes().displacement, eye, cells, intervalCells);
            boxes[i] = UnionBox(intervalCells);
            if (const MotionPath* path = prim.attributes().motion.get()) boxes[i] = SweptBox(boxes[i], *path);
        },
        kBoxGrain);
    for (size_t i = 0; i < problems.size(); ++i) {
        if (problems[i].empty()) continue;
        return fail(requestAt(*out->primitives[i].attributes().displacement), problems[i]);
    }
    out->bvh = std::make_unique<Bvh>(boxes, &m_pool, m_options.bvhSplit);
    out->shadersCompiled = cache.misses();
    out->shadersReused = cache.hits();
    out->lights = desc.lights;
    out->lightSets.resize(lightSetKeys.size());
    for (const auto& [key, index] : lightSetKeys)
        for (int light : key) out->lightSets[static_cast<size_t>(index)].push_back(desc.lights[size_t(light)]);
    if (defaultLights) {
        // No lights (none that gives light): a key light from behind the camera, and a little
        // ambient, so that something shows.
        glm::dmat4 cameraToWorld = glm::inverse(desc.camera.worldToCamera);
        glm::dvec3 eye = glm::dvec3(cameraToWorld * glm::dvec4(0, 0, 0, 1));
        glm::dvec3 forward = glm::dvec3(cameraToWorld * glm::dvec4(0, 0, 1, 0));
        LightDesc key;
        key.kind = LightDesc::Kind::Distant;
        key.castShadows = true;  // affray's own light, not a RenderMan one: it keeps the shadows it always had
        key.from = eye;
        key.to = eye + forward;
        out->lights.push_back(key);
        LightDesc ambient;
        ambient.kind = LightDesc::Kind::Ambient;
        ambient.intensity = 0.05;
        out->lights.push_back(ambient);
        out->lightSets = {out->lights};  // for every primitive, whatever its Illuminate said
    }
    return true;
}

}  // namespace affray::renderer
