// fuzz/fuzz_rib.cpp: RIB text -> lexer, request parser and frames -> each frame prepared for
// rendering as `affray render` prepares it (shaders found and compiled, surfaces specialised,
// the BVH built); nothing is rendered.
// The scene is named as a file in this process's temporary directory, so that what a scene writes
// (MakeTexture) lands there; MakeTexture requests naming an absolute path or '..' are dropped.
// Shaders are found in shaders/, tests/golden and tests/corpus of the source tree. A
// gzip-compressed input is decompressed up to the rib-bytes limit, set to 64 MiB here so that a
// small input cannot grow past libFuzzer's memory limit (-rss_limit_mb) before it is refused.
// The compiler's program-ops and loop-iterations limits are lowered (fuzz_util.h).
#include <optional>
#include <string>
#include <vector>

#include "diag/limits.h"
#include "fuzz/fuzz_util.h"
#include "renderer/renderer.h"
#include "rib/rib.h"

namespace {

bool InsideP(const std::string& path) {
    return !path.empty() && path[0] != '/' && path.find("..") == std::string::npos;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace affray;
    static const bool kLimited =
        (diag::SetLimit(diag::Limit::RibBytes, int64_t{1} << 26), fuzz::SetSmallLimits(), true);
    (void)kLimited;
    static const std::string kPath = fuzz::TempDir() + "/input.rib";
    // One thread: libFuzzer runs one input at a time, and a pool would only add threads to start.
    static const renderer::Renderer kRenderer(
        renderer::Options{.threads = 1,
                          .shaderPaths = {fuzz::SourceDir() + "/shaders", fuzz::SourceDir() + "/tests/golden",
                                          fuzz::SourceDir() + "/tests/corpus"}});
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    diag::Report report;
    std::optional<std::vector<renderer::SceneDesc>> frames = rib::ParseRibFrames(text, kPath, &report);
    if (!frames) return 0;
    for (renderer::SceneDesc& frame : *frames) {
        std::erase_if(frame.makeTextures, [](const renderer::SceneDesc::MakeTextureDesc& m) {
            return !InsideP(m.picture) || !InsideP(m.texture);
        });
        renderer::PreparedScene prepared;
        diag::Report frameReport;
        kRenderer.Prepare(frame, &prepared, &frameReport);
    }
    return 0;
}
