// bench/tessellation_bench.cpp: the tessellation baseline, in process. Reads and prepares a RIB
// scene as `affray render` does, samples every primitive's displaced surface (its bound program,
// in scalar arithmetic) on an (N+1) x (N+1) grid of (u,v), builds one Embree 3 triangle mesh per
// primitive and renders the scene through Options::intersectorFactory: the film, samples,
// shading (the shade program at the (u,v) of the hit) and shadows are affray's; only the
// ray-surface intersection is the mesh's. The figures are what a tessellating renderer pays to
// reach a given image error (bench/error_report.py), measured on the same machine, same samples.
//
// Usage: affray_bench_tessellation SCENE.rib --grid N [-o OUT.exr] [--threads T] [--samples S]
//                                  [--tolerance PIXELS] [--quality medium|high] [--stats] [--quiet]
// See docs/tessellation.md. Built only when CMake finds Embree 3 (bench/CMakeLists.txt).
#include <embree3/rtcore.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "image/exr_writer.h"
#include "renderer/renderer.h"
#include "rib/rib.h"
#include "scene/geometry/camera.h"
#include "scene/geometry/surface.h"

using namespace affray;

namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct Options {
    std::string scenePath;
    std::string outputPath;  // empty: the scene's Display name
    int grid = 0;
    int threads = 0;  // 0: one per core
    int samples = 0;  // 0: the scene's PixelSamples
    // Options::tolerancePixels. The meshes ignore it; Renderer::Render starts shadow rays twice
    // its footprint above a hit (a hit's certified error being 0 here), so it sets that offset.
    double tolerance = 0.5;
    // MEDIUM: on wave (640x480, N=512) and terrain (N=2048) it built the BVH 1.7-2.3 times faster
    // than HIGH for the same image and the same render time, so it is the stronger baseline.
    RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM;
    bool stats = false;
    bool quiet = false;
};

const char kUsage[] =
    "usage: affray_bench_tessellation SCENE.rib --grid N [-o OUT.exr] [--threads T] [--samples S]\n"
    "                                 [--tolerance PIXELS] [--quality medium|high] [--stats] [--quiet]\n";

/// A whole positive number in [lo, hi], or exits 2 naming the flag.
int ParseCount(const char* text, const char* flag, int lo, int hi) {
    char* end = nullptr;
    long value = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || value < lo || value > hi) {
        std::fprintf(stderr, "affray_bench_tessellation: %s takes a whole number in [%d, %d], got '%s'\n", flag, lo, hi,
                     text);
        std::exit(2);
    }
    return static_cast<int>(value);
}

Options ParseArgs(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "affray_bench_tessellation: %s needs a value\n%s", a.c_str(), kUsage);
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--grid")
            o.grid = ParseCount(value(), "--grid", 1, 16384);
        else if (a == "-o")
            o.outputPath = value();
        else if (a == "--threads")
            o.threads = ParseCount(value(), "--threads", 1, 1024);
        else if (a == "--samples")
            o.samples = ParseCount(value(), "--samples", 1, 64);
        else if (a == "--tolerance") {
            const char* text = value();
            char* end = nullptr;
            o.tolerance = std::strtod(text, &end);
            if (end == text || *end != '\0' || !(o.tolerance > 0) || !std::isfinite(o.tolerance)) {
                std::fprintf(stderr, "affray_bench_tessellation: --tolerance takes a positive number, got '%s'\n",
                             text);
                std::exit(2);
            }
        } else if (a == "--quality") {
            const std::string q = value();
            if (q == "high")
                o.quality = RTC_BUILD_QUALITY_HIGH;
            else if (q == "medium")
                o.quality = RTC_BUILD_QUALITY_MEDIUM;
            else {
                std::fprintf(stderr, "affray_bench_tessellation: --quality takes high or medium, got '%s'\n",
                             q.c_str());
                std::exit(2);
            }
        } else if (a == "--stats")
            o.stats = true;
        else if (a == "--quiet")
            o.quiet = true;  // no progress bar any more; kept for the scripts that pass it
        else if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "affray_bench_tessellation: unknown option '%s'\n%s", a.c_str(), kUsage);
            std::exit(2);
        } else if (o.scenePath.empty())
            o.scenePath = a;
        else {
            std::fprintf(stderr, "affray_bench_tessellation: more than one scene given\n%s", kUsage);
            std::exit(2);
        }
    }
    if (o.scenePath.empty() || o.grid == 0) {
        std::fputs(kUsage, stderr);
        std::exit(2);
    }
    return o;
}

/// Bytes Embree holds (its BVHs and build scratch), tracked through its memory monitor: the
/// current total and the largest it reached.
struct EmbreeMemory {
    std::atomic<int64_t> current{0};
    std::atomic<int64_t> peak{0};

    // Each allocation (bytes > 0) and release (< 0) is reported once, before or after it happens
    // (`post`); nothing is ever cancelled here, so every report counts.
    static bool Monitor(void* self, ssize_t bytes, bool) {
        auto* m = static_cast<EmbreeMemory*>(self);
        const int64_t now = m->current += bytes;
        int64_t seen = m->peak.load();
        while (now > seen && !m->peak.compare_exchange_weak(seen, now)) {}
        return true;
    }
};

void ReportEmbreeError(void*, RTCError code, const char* message) {
    std::fprintf(stderr, "affray_bench_tessellation: embree error %d: %s\n", static_cast<int>(code),
                 message ? message : "");
}

/// One primitive's tessellation: the (N+1)^2 grid points (vertex i*(N+1)+j at u = i/N,
/// v = j/N), two triangles per cell whose corners are all finite, and its Embree scene.
struct Mesh {
    int n = 0;
    std::vector<float> vertices;    // x, y, z per grid point, then one float of padding (Embree
                                    // reads the last vertex with a 16-byte load)
    std::vector<uint32_t> indices;  // three grid points per triangle
    RTCScene scene = nullptr;       // null if no triangle is left

    size_t triangles() const { return indices.size() / 3; }
    size_t bytes() const { return vertices.size() * sizeof(float) + indices.size() * sizeof(uint32_t); }
    /// The (u,v) of grid point k.
    void Parameters(uint32_t k, double* u, double* v) const {
        const uint32_t side = static_cast<uint32_t>(n) + 1;
        const uint32_t row = k / side, column = k % side;
        *u = double(row) / n;
        *v = double(column) / n;
    }
};

/// Evaluates the displaced P at the grid points of rows [row, ...) handed out by `nextRow`, with
/// number type T (double, or Dual<double> when the bound program takes derivatives).
template <class T>
void EvaluateRows(const renderer::Primitive& prim, const glm::dvec3& eye, Mesh* mesh, std::atomic<int>* nextRow) {
    vm::Interpreter<T> interp(prim.bound());
    const vm::ProgramOutput& output = *prim.bound().findOutput("P");
    const int n = mesh->n;
    for (int i = (*nextRow)++; i <= n; i = (*nextRow)++) {
        const double u = double(i) / n;
        for (int j = 0; j <= n; ++j) {
            const double v = double(j) / n;
            const vm::Vec3<T> p = renderer::EvaluateOnSurface(interp, prim.base(), u, u, v, v, eye, output);
            float* out = &mesh->vertices[3 * (static_cast<size_t>(i) * (n + 1) + j)];
            out[0] = static_cast<float>(vm::ValueOf(p.x));
            out[1] = static_cast<float>(vm::ValueOf(p.y));
            out[2] = static_cast<float>(vm::ValueOf(p.z));
        }
    }
}

/// Fills mesh->vertices and mesh->indices for `prim` (threads share the rows).
void Tessellate(const renderer::Primitive& prim, const glm::dvec3& eye, int n, int threads, Mesh* mesh) {
    mesh->n = n;
    const size_t side = static_cast<size_t>(n) + 1;
    mesh->vertices.assign(3 * side * side + 1, 0.0f);
    std::atomic<int> nextRow{0};
    auto work = [&] {
        if (prim.bound().usesDerivatives())
            EvaluateRows<vm::Dual<double>>(prim, eye, mesh, &nextRow);
        else
            EvaluateRows<double>(prim, eye, mesh, &nextRow);
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();

    // A point where the shader is singular (NaN, infinite, or past float range) takes the
    // triangles touching it away.
    auto finite = [&](size_t k) {
        const float* p = &mesh->vertices[3 * k];
        return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
    };
    mesh->indices.clear();
    mesh->indices.reserve(6 * static_cast<size_t>(n) * n);
    auto triangle = [&](size_t a, size_t b, size_t c) {
        if (!finite(a) || !finite(b) || !finite(c)) return;
        mesh->indices.push_back(static_cast<uint32_t>(a));
        mesh->indices.push_back(static_cast<uint32_t>(b));
        mesh->indices.push_back(static_cast<uint32_t>(c));
    };
    for (size_t i = 0; i < static_cast<size_t>(n); ++i)
        for (size_t j = 0; j < static_cast<size_t>(n); ++j) {
            const size_t k00 = i * side + j, k10 = k00 + side, k01 = k00 + 1, k11 = k10 + 1;
            triangle(k00, k10, k11);
            triangle(k00, k11, k01);
        }
    mesh->indices.shrink_to_fit();
}

/// Builds the Embree scene of one mesh (its buffers shared, not copied).
void BuildScene(RTCDevice device, RTCBuildQuality quality, Mesh* mesh) {
    if (mesh->triangles() == 0) return;
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geometry, quality);
    const size_t side = static_cast<size_t>(mesh->n) + 1;
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh->vertices.data(), 0,
                               3 * sizeof(float), side * side);
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh->indices.data(), 0,
                               3 * sizeof(uint32_t), mesh->triangles());
    rtcCommitGeometry(geometry);
    mesh->scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(mesh->scene, quality);
    rtcAttachGeometry(mesh->scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(mesh->scene);
}

/// The smallest float >= x (x itself if it is a float), and the largest float <= x: the ray's
/// [tMin, tMax] narrowed, never widened, by rounding.
float FloatUp(double x) {
    float f = static_cast<float>(x);
    return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}
float FloatDown(double x) {
    float f = static_cast<float>(x);
    return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

/// Intersects rays with one primitive's mesh through Embree. Holds nothing mutable but the
/// statistics it is given, so one per thread and primitive costs nothing.
class MeshIntersector final : public renderer::SurfaceIntersector {
  public:
    explicit MeshIntersector(const Mesh& mesh) : m_mesh(mesh) {}

    bool Intersect(const renderer::Ray& ray, double tMin, double tMax, const renderer::Tolerance&, bool anyHit,
                   renderer::Hit* hit, renderer::IntersectStats& stats, const renderer::RayGroup*) override {
        ++stats.rays;
        if (!m_mesh.scene || !(tMin <= tMax)) return false;
        const float tnear = FloatUp(std::max(tMin, 0.0)), tfar = FloatDown(tMax);
        if (!(tnear <= tfar)) return false;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh;
        RTCRay& r = rh.ray;
        r.org_x = static_cast<float>(ray.origin.x);
        r.org_y = static_cast<float>(ray.origin.y);
        r.org_z = static_cast<float>(ray.origin.z);
        r.dir_x = static_cast<float>(ray.dir.x);
        r.dir_y = static_cast<float>(ray.dir.y);
        r.dir_z = static_cast<float>(ray.dir.z);
        r.tnear = tnear;
        r.tfar = tfar;
        r.time = 0;
        r.mask = 0xffffffffu;
        r.id = 0;
        r.flags = 0;
        if (anyHit) {
            rtcOccluded1(m_mesh.scene, &context, &r);
            if (r.tfar != -std::numeric_limits<float>::infinity()) return false;
            // An occlusion query finds that something is hit, not where: the renderer asks no more.
            *hit = renderer::Hit{};
            hit->t = tMin;
            return true;
        }
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(m_mesh.scene, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
        // The hit's (u,v): the triangle's corners' parameters weighted by its barycentrics.
        const uint32_t* corner = &m_mesh.indices[3 * static_cast<size_t>(rh.hit.primID)];
        const double b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.0 - b1 - b2;
        double u[3], v[3];
        for (int c = 0; c < 3; ++c) m_mesh.Parameters(corner[c], &u[c], &v[c]);
        *hit = renderer::Hit{};
        hit->t = std::clamp(static_cast<double>(r.tfar), tMin, tMax);
        hit->u = std::clamp(b0 * u[0] + b1 * u[1] + b2 * u[2], 0.0, 1.0);
        hit->v = std::clamp(b0 * v[0] + b1 * v[1] + b2 * v[2], 0.0, 1.0);
        hit->error = 0;
        hit->depthLimited = false;
        return true;
    }

  private:
    const Mesh& m_mesh;
};

double PeakRssMegabytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

}  // namespace

int main(int argc, char** argv) {
    const Clock::time_point start = Clock::now();
    const Options opt = ParseArgs(argc, argv);

    // Read and prepare the scene as `affray render` does (tools/commands.cpp, RunRender).
    diag::Report report;
    std::optional<renderer::SceneDesc> scene = rib::ReadRib(opt.scenePath, &report);
    if (!scene) {
        std::fputs(report.format().c_str(), stderr);
        return diag::kExitBadInput;
    }
    std::filesystem::path ribDir = std::filesystem::path(opt.scenePath).parent_path();
    if (ribDir.empty()) ribDir = ".";
    const std::vector<std::string> shaderPaths = {ribDir.string(), (ribDir / ".." / "shaders").string(), "shaders"};
    if (opt.samples > 0) scene->camera.xsamples = scene->camera.ysamples = opt.samples;
    // One Renderer prepares the scene and renders it through the meshes, made in between: the
    // film, sampling, shading and shadows of affray's own render.
    std::vector<Mesh> meshes;
    renderer::Options options;
    options.threads = opt.threads;
    options.shaderPaths = shaderPaths;
    options.tolerancePixels = opt.tolerance;
    options.intersectorFactory = [&meshes](const renderer::Primitive&, int index) {
        return std::unique_ptr<renderer::SurfaceIntersector>(new MeshIntersector(meshes[static_cast<size_t>(index)]));
    };
    const renderer::Renderer affray(std::move(options));
    renderer::PreparedScene prepared;
    const bool preparedOk = affray.Prepare(std::move(*scene), &prepared, &report);
    std::fputs(report.format().c_str(), stderr);
    if (!preparedOk) return diag::kExitBadInput;
    const int threads = affray.threads();
    const glm::dvec3 eye = renderer::Camera(prepared.desc.camera).Position();

    // Tessellate: the bound program's P at every grid point.
    const Clock::time_point tessellateStart = Clock::now();
    meshes.resize(prepared.primitives.size());
    for (size_t i = 0; i < meshes.size(); ++i) Tessellate(prepared.primitives[i], eye, opt.grid, threads, &meshes[i]);
    const double tessellateSeconds = SecondsSince(tessellateStart);

    // One Embree scene per primitive (the intersector is asked per primitive).
    EmbreeMemory embreeMemory;
    const std::string config = "threads=" + std::to_string(threads) + ",set_affinity=0";
    RTCDevice device = rtcNewDevice(config.c_str());
    if (!device) {
        std::fprintf(stderr, "affray_bench_tessellation: cannot create an Embree device (error %d)\n",
                     static_cast<int>(rtcGetDeviceError(nullptr)));
        return 1;
    }
    rtcSetDeviceErrorFunction(device, ReportEmbreeError, nullptr);
    rtcSetDeviceMemoryMonitorFunction(device, &EmbreeMemory::Monitor, &embreeMemory);
    const Clock::time_point bvhStart = Clock::now();
    for (Mesh& mesh : meshes) BuildScene(device, opt.quality, &mesh);
    const double bvhSeconds = SecondsSince(bvhStart);
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE) return 1;

    // Render through the meshes.
    const Clock::time_point renderStart = Clock::now();
    image::ImageBuffer image;
    renderer::RenderStats stats;
    affray.Render(prepared, &image, &stats);
    const double renderSeconds = SecondsSince(renderStart);

    const std::string outputPath = opt.outputPath.empty() ? prepared.desc.displayName : opt.outputPath;
    diag::Report output;
    if (!image::WriteExr(outputPath, image, &output)) {
        std::fputs(output.format().c_str(), stderr);
        return diag::kExitOutput;
    }

    size_t triangles = 0, meshBytes = 0;
    for (Mesh& mesh : meshes) {
        triangles += mesh.triangles();
        meshBytes += mesh.bytes();
        if (mesh.scene) rtcReleaseScene(mesh.scene);
    }
    rtcReleaseDevice(device);
    if (opt.stats)
        std::printf(
            "{\"grid\":%d,\"triangles\":%zu,\"tessellate_seconds\":%.4f,\"bvh_seconds\":%.4f,"
            "\"render_seconds\":%.4f,\"wall_seconds\":%.4f,\"mesh_bytes\":%zu,\"bvh_bytes\":%lld,"
            "\"peak_rss_mb\":%.1f,\"build_quality\":\"%s\",\"threads\":%d,\"camera_rays\":%llu,"
            "\"shadow_rays\":%llu}\n",
            opt.grid, triangles, tessellateSeconds, bvhSeconds, renderSeconds, SecondsSince(start), meshBytes,
            static_cast<long long>(embreeMemory.peak.load()), PeakRssMegabytes(),
            opt.quality == RTC_BUILD_QUALITY_HIGH ? "high" : "medium", threads,
            static_cast<unsigned long long>(stats.cameraRays), static_cast<unsigned long long>(stats.shadow.rays));
    return 0;
}
