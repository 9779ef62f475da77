// renderer/render_identity.cpp: the identity of a render (what it covers: render_identity.h).
#include "renderer/render_identity.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>

#include "vm/bytecode_file.h"

namespace affray::renderer {
namespace {

__extension__ using Uint128 = unsigned __int128;

/// FNV-1a with the 128-bit parameters (offset basis 144066263297769815596495629667062367629,
/// prime 2^88 + 2^8 + 0x3b).
class Fnv128 {
  public:
    /// FNV-1a's step over 8 bytes at a time (a scene's RIB file and meshes run to hundreds of
    /// megabytes), the last few bytes one by one.
    void Add(std::string_view bytes) {
        size_t i = 0;
        for (; i + 8 <= bytes.size(); i += 8) {
            uint64_t word;
            std::memcpy(&word, bytes.data() + i, 8);
            m_h ^= word;
            m_h *= kPrime;
        }
        for (; i < bytes.size(); ++i) {
            m_h ^= static_cast<unsigned char>(bytes[i]);
            m_h *= kPrime;
        }
    }
    /// A named field, framed by its length, so that no two sequences of fields hash alike.
    void Field(std::string_view name, std::string_view bytes) {
        Add(name);
        const std::string length = ":" + std::to_string(bytes.size()) + ":";
        Add(length);
        Add(bytes);
    }
    std::string Hex() const {
        char text[33];
        std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(m_h >> 64),
                      static_cast<unsigned long long>(m_h));
        return text;
    }

  private:
    static constexpr Uint128 kPrime = (Uint128(1) << 88) + (1 << 8) + 0x3b;
    Uint128 m_h = (Uint128(0x6c62272e07bb0142ULL) << 64) | 0x62b821756295c58dULL;
};

std::string ReadFileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "unreadable file " + path;
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A file's name without its directories: the identity must not change with the directory a
/// render is started from, or the one a farm machine mounts the project at.
std::string FileName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

/// A texture file by name, size and modification time (nanoseconds).
std::string FileStamp(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return "missing " + FileName(path);
    return FileName(path) + " size=" + std::to_string(st.st_size) + " mtime=" + std::to_string(st.st_mtim.tv_sec) +
           "." + std::to_string(st.st_mtim.tv_nsec);
}

void AddTextures(const vm::Program& program, Fnv128* h) {
    if (!program.textures) return;
    for (const vm::TextureSlot& slot : *program.textures) h->Field("texture", FileStamp(slot.path));
}

/// `program` with its file paths cut to file names (FileName).
vm::Program WithoutDirectories(const vm::Program& program) {
    vm::Program copy = program;
    copy.sourcePath = FileName(copy.sourcePath);
    if (copy.textures) {
        auto slots = std::make_shared<vm::TextureSlots>(*copy.textures);
        for (vm::TextureSlot& slot : *slots) slot.path = FileName(slot.path);
        copy.textures = slots;
    }
    return copy;
}

std::string Number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

const char* BoundsName(BoundMode mode) {
    switch (mode) {
        case BoundMode::Affine: return "affine";
        case BoundMode::Reduced: return "reduced";
        case BoundMode::Interval: return "interval";
    }
    return "?";
}

/// The same numbers, bit for bit.
bool SameBits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// Whether two programs are the same in everything vm::SaveBytecode writes (texture slots: the
/// same shared slots; slots are never changed once made).
bool SameProgram(const vm::Program& a, const vm::Program& b) {
    if (a.shaderName != b.shaderName || a.sourcePath != b.sourcePath || a.code.size() != b.code.size() ||
        a.lines != b.lines || !SameBits(a.constants, b.constants) || a.registerCount != b.registerCount ||
        a.globalRegisters != b.globalRegisters || a.spaces != b.spaces || a.textures != b.textures ||
        a.outputs.size() != b.outputs.size() || a.params.size() != b.params.size())
        return false;
    for (size_t i = 0; i < a.code.size(); ++i) {
        const vm::Instr &x = a.code[i], &y = b.code[i];
        if (x.op != y.op || x.flags != y.flags || x.a != y.a || x.b != y.b || x.c != y.c) return false;
    }
    for (size_t i = 0; i < a.outputs.size(); ++i) {
        const vm::ProgramOutput &x = a.outputs[i], &y = b.outputs[i];
        if (x.name != y.name || x.size != y.size || x.registers != y.registers) return false;
    }
    for (size_t i = 0; i < a.params.size(); ++i) {
        const vm::ProgramParam &x = a.params[i], &y = b.params[i];
        if (x.name != y.name || x.type != y.type || x.size != y.size || x.firstRegister != y.firstRegister ||
            !SameBits(x.defaults, y.defaults))
            return false;
    }
    return true;
}

/// The bytes of a vector of plain values.
template <class T>
std::string_view BytesOf(const std::vector<T>& v) {
    return {reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T)};
}

template <class T>
std::string_view BytesOf(const T& x) {
    return {reinterpret_cast<const char*>(&x), sizeof x};
}

/// A polygon mesh's arrays (PieceMesh::ForEachArray), as bytes: every value a piece of it can read.
void HashMesh(const PieceMesh& m, Fnv128* h) {
    m.ForEachArray([&](const char* name, const auto& values, const std::string& form) {
        h->Field(name, form);
        h->Field("values", BytesOf(values));
    });
}

/// The scene's primitives: what ToString prints of each, except that what primitives share (a
/// request's attributes, a polygon or subdivision mesh) is hashed once, where it first appears,
/// and a mesh's arrays as bytes: a million faces are not a million lines of text.
void HashPrimitives(const SceneDesc& scene, Fnv128* h) {
    const PrimitiveAttributes* attributes = nullptr;
    const void* mesh = nullptr;
    for (const PrimitiveDesc& p : scene.primitives) {
        if (p.attributes.get() != attributes) {
            attributes = p.attributes.get();
            // The attributes as ToString prints them, with a primitive without shape or colours.
            PrimitiveDesc alone;
            alone.attributes = p.attributes;
            h->Field("attributes", ToString(alone));
            h->Field("object", BytesOf(attributes->objectToWorld));
        }
        const BaseSurface& b = p.base;
        for (uint32_t i = 0; i < p.elements; ++i) {
            if (b.kind() == BaseSurface::Kind::MeshPiece) {
                const MeshPieceRef& ref = b.pieceRef();
                if (ref.mesh.get() != mesh) {
                    mesh = ref.mesh.get();
                    HashMesh(*ref.mesh, h);
                }
                h->Field("piece", BytesOf(ref.index + i));
            } else if (b.kind() == BaseSurface::Kind::SubdivPatch) {
                h->Field("subdivision", ToString(b.Element(i).subdiv()));
            } else {
                PrimitiveDesc shape;
                shape.base = b;
                h->Field("shape", ToString(shape));
            }
            // The colours: a polygon mesh's own are in its arrays, a subdivision patch's fields.
            PrimitiveDesc patch;
            if (b.kind() == BaseSurface::Kind::SubdivPatch) patch = p.Element(i);
            const PrimitiveDesc& e = b.kind() == BaseSurface::Kind::SubdivPatch ? patch : p;
            std::string looks(BytesOf(e.color));
            looks.append(BytesOf(e.opacity));
            if (b.flipNormal) looks += " flip";
            if (b.textureCoordinates) looks.append(BytesOf(*b.textureCoordinates));
            if (e.colorField) looks += " Cs " + ToString(*e.colorField);
            if (e.opacityField) looks += " Os " + ToString(*e.opacityField);
            h->Field("looks", looks);
        }
    }
}

/// The digest of what a render's identity and its frame's share: the RIB file's bytes, the
/// scene as read after its camera, and each primitive's specialised programs, its shader's source
/// and the texture files they read. Computed once per prepared scene (PreparedScene::
/// identityDigest): for a mesh of thousands of faces it is most of the cost of an identity. A
/// primitive whose shader and programs are the previous one's (the faces of a mesh) adds a
/// field saying so instead of its programs, source and texture stamps again.
const std::string& InputsDigest(const PreparedScene& scene) {
    if (!scene.identityDigest.empty()) return scene.identityDigest;
    Fnv128 h;
    h.Field("rib", ReadFileBytes(scene.desc.path));
    h.Field("scene", ToStringSettings(scene.desc));
    HashPrimitives(scene.desc, &h);
    const Primitive* previous = nullptr;
    // The surface shaders, each once, in the order the primitives first use them, then the light
    // shaders: their source and programs (their parameter values and lights are in the scene's
    // text above).
    std::vector<const compiler::CompiledShader*> surfaces;
    for (const PrimitivePrograms& programs : scene.programs)
        if (programs.surface && std::find(surfaces.begin(), surfaces.end(), programs.surface.get()) == surfaces.end())
            surfaces.push_back(programs.surface.get());
    // The light shaders, each once: their source and programs (their parameters are the scene's).
    for (const LightDesc& light : scene.desc.lights)
        if (light.program && std::find(surfaces.begin(), surfaces.end(), light.program.get()) == surfaces.end())
            surfaces.push_back(light.program.get());
    for (const compiler::CompiledShader* surface : surfaces) {
        h.Field("surface source", surface->sourceText);
        vm::BytecodeFile program;
        program.shaderName = surface->name;
        program.sourcePath = FileName(surface->sourcePath);
        program.sourceHash = vm::HashSource(surface->sourceText);
        const vm::Program& shading = surface->kind == lang::ShaderKind::Light ? surface->light : surface->surface;
        program.bound = WithoutDirectories(shading);
        h.Field("surface program", vm::SaveBytecode(program));
        AddTextures(shading, &h);
    }
    for (const Primitive& prim : scene.primitives) {
        if (!prim.shader()) {
            h.Field("primitive", "no shader");
            previous = nullptr;
            continue;
        }
        if (previous && (previous->programs == prim.programs ||
                         (previous->shader() == prim.shader() && SameProgram(previous->bound(), prim.bound()) &&
                          SameProgram(previous->shade(), prim.shade())))) {
            h.Field("primitive", "as the previous one");
            continue;
        }
        previous = &prim;
        vm::BytecodeFile programs;
        programs.shaderName = prim.shader()->name;
        programs.sourcePath = FileName(prim.shader()->sourcePath);
        programs.sourceHash = vm::HashSource(prim.shader()->sourceText);
        programs.bound = WithoutDirectories(prim.bound());
        programs.shade = WithoutDirectories(prim.shade());
        h.Field("primitive", vm::SaveBytecode(programs));
        h.Field("source", prim.shader()->sourceText);
        AddTextures(prim.bound(), &h);
        AddTextures(prim.shade(), &h);
    }
    scene.identityDigest = h.Hex();
    return scene.identityDigest;
}

/// IdentifyRender and IdentifyFrame: with `withCrop` false the crop window counts as the whole
/// frame in the scene's hash and has no line in the options.
RenderIdentity Identify(const PreparedScene& scene, const Options& options, bool withCrop) {
    Fnv128 h;
    h.Field("affray render identity", "4");
    h.Field("inputs", InputsDigest(scene));
    CameraDesc camera = scene.desc.camera;
    if (!withCrop) camera.cropWindow = glm::dvec4(0.0, 1.0, 0.0, 1.0);
    h.Field("head", SceneHeadLine(scene.desc, FileName(scene.desc.path)));
    h.Field("camera", ToString(camera));

    const CameraDesc& cam = scene.desc.camera;
    std::ostringstream text;
    text << "resolution=" << cam.xres << "x" << cam.yres << "\n";
    if (withCrop)
        text << "crop=" << Number(cam.cropWindow.x) << "," << Number(cam.cropWindow.y) << ","
             << Number(cam.cropWindow.z) << "," << Number(cam.cropWindow.w) << "\n";
    text << "samples=" << cam.xsamples << "x" << cam.ysamples << "\n"
         << "frame=" << (scene.desc.frame ? std::to_string(*scene.desc.frame) : "none") << "\n"
         << "display=" << scene.desc.displayMode << "\n"
         << "tolerance=" << Number(options.tolerancePixels) << (options.sceneTolerance ? "" : " (given)") << "\n"
         << "bounds=" << BoundsName(options.bounds) << "\n"
         << "max-depth=" << options.maxDepth << "\n"
         << "region-budget=" << options.regionBudget << "\n"
         << "ray-groups=" << options.rayGroupPixels << "\n";
    // Only when on, so that the identity of a render without it is what it was before the option.
    if (options.newton) text << "newton=on\n";
    return {h.Hex(), text.str()};
}

}  // namespace

std::string HashHex(std::string_view bytes) {
    Fnv128 h;
    h.Add(bytes);
    return h.Hex();
}

std::string RenderIdentity::Hash() const {
    Fnv128 h;
    h.Field("scene", scene);
    h.Field("options", options);
    return h.Hex();
}

RenderIdentity IdentifyRender(const PreparedScene& scene, const Options& options) {
    return Identify(scene, options, true);
}

RenderIdentity IdentifyFrame(const PreparedScene& scene, const Options& options) {
    return Identify(scene, options, false);
}

std::string DifferingOptions(const std::string& a, const std::string& b) {
    auto lines = [](const std::string& text) {
        std::map<std::string, std::string> values;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            const size_t eq = line.find('=');
            values[line.substr(0, eq)] = eq == std::string::npos ? "" : line.substr(eq + 1);
        }
        return values;
    };
    const auto va = lines(a), vb = lines(b);
    std::string names;
    auto add = [&](const std::string& name) { names += (names.empty() ? "" : ", ") + name; };
    for (const auto& [name, value] : va)
        if (!vb.count(name) || vb.at(name) != value) add(name);
    for (const auto& [name, value] : vb)
        if (!va.count(name)) add(name);
    return names;
}

}  // namespace affray::renderer
