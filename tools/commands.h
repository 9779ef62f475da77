// tools/commands.h: the subcommands of the `affray` program. Each takes its parsed options and
// returns the process exit code (diag::ExitCode); diagnostics go to `err` in the one format of
// diag/diagnostic.h, results to `out`; nothing calls exit().
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "compiler/specialise.h"
#include "diag/diagnostic.h"
#include "lang/preprocess.h"
#include "renderer/intersect.h"
#include "renderer/options.h"
#include "renderer/render.h"

namespace affray::tools {

/// The version `affray --version` prints and every image's header records (renderer/tiling.h).
inline constexpr const char* kVersion = "0.1.0";

struct CompileCommand {
    std::string shaderPath;
    std::string outputPath;  // empty: none
    bool disasm = false;
    bool stats = false;
    lang::PreprocessOptions preprocess;
};

struct EvalCommand {
    std::string shaderPath;
    std::vector<compiler::ParamOverride> params;
    std::vector<std::array<double, 2>> points;  // --at, in order
    bool hasRegion = false;
    std::array<double, 4> region{};  // u0, u1, v0, v1
    std::string mode = "scalar";     // scalar | affine | interval
    lang::PreprocessOptions preprocess;
};

struct RenderCommand {
    std::string scenePath;
    std::string outputPath;  // empty: the scene's Display name
    int threads = 0;
    double tolerance = 0.5;
    bool toleranceGiven = false;  // --tolerance was given: the scene's level of detail does not apply
    renderer::BoundMode bounds = renderer::BoundMode::Reduced;
    int maxDepth = 24;
    bool stats = false;
    std::string pngPath;  // empty: no preview
    lang::PreprocessOptions preprocess;
    bool quiet = false;                         // no progress bar
    std::optional<std::array<double, 4>> crop;  // --crop: replaces the scene's CropWindow
    int samples = 0;                            // --samples N: N x N per pixel (0: the scene's)
    uint64_t regionBudget = renderer::kDefaultRegionBudget;
    size_t cacheBytes = renderer::kDefaultCacheBytes;
    std::optional<size_t> textureBytes;  // --texture-mb: the texture tiles' budget (else the default)
    int rayGroupPixels = renderer::kDefaultRayGroupPixels;
    bool newton = false;        // certified Newton hits (renderer/newton.h)
    std::optional<int> frame;   // --frame N: only the frames numbered N (FrameBegin N)
    bool resume = false;        // --resume: continue the checkpoint beside the output (tools/frame_output.h)
    bool reverseTiles = false;  // --tile-order reverse (a test option: the image must not change)
    bool medianBvh = false;     // --bvh median (a test option: the image must not change)
};

/// affray split: the tiles of every frame as Slurm job scripts, or as shell commands.
struct SplitCommand {
    std::string scenePath;
    std::string outputPath;  // empty: each frame's Display name
    int tiles = 0;
    bool shell = false;  // --shell: print one render command per task instead of writing job scripts
    int threads = 1;     // threads of each task (Slurm: cpus-per-task)
    std::optional<int> frame;
    std::vector<std::string> renderArgs;  // options given to every task's affray render (already checked)
    std::string program;                  // the affray program the tasks run (absolute, for Slurm)
};

/// affray merge: tiles of one frame pasted into one image.
struct MergeCommand {
    std::string outputPath;
    std::vector<std::string> tiles;
};

struct DiffCommand {
    std::string reference, test;  // two OpenEXR images of the same size
};

int RunCompile(const CompileCommand& cmd, FILE* out, FILE* err);
/// Prints {"pixels":..,"rmse":..,"max":..} over the RGB channels of `test` against `reference`.
int RunDiff(const DiffCommand& cmd, FILE* out, FILE* err);
int RunEval(const EvalCommand& cmd, FILE* out, FILE* err);
/// Renders every frame of the scene that is not skipped (or those --frame picks), each to its
/// Display name or to -o; when several frames would write one file name, each frame's number is
/// inserted before the extension (FrameOutputPath).
int RunRender(const RenderCommand& cmd, FILE* out, FILE* err);

/// Writes the job of `cmd` (tools/split.cpp): OUT.render.sbatch, OUT.merge.sbatch and
/// OUT.submit.sh beside the output, or with --shell prints the commands on `out`.
int RunSplit(const SplitCommand& cmd, FILE* out, FILE* err);
/// Checks that the tiles come from one render and cover its frame exactly once, then writes them
/// as one image (tools/merge.cpp).
int RunMerge(const MergeCommand& cmd, FILE* out, FILE* err);

/// Reads the scene at `scenePath` into *frames (its diagnostics printed on `err`) and returns
/// the frames `affray render` renders: all, or those numbered `frame`, less those that make no
/// image (shadow passes). Empty with *status set if the scene cannot be read (kExitBadInput),
/// if --frame names no frame (kExitUsage, with an error on `err`), or if no frame makes an image
/// (kExitSuccess, with a note).
std::vector<const renderer::SceneDesc*> ReadChosenFrames(const std::string& scenePath, std::optional<int> frame,
                                                         FILE* err, std::vector<renderer::SceneDesc>* frames,
                                                         int* status);
/// The image file of each chosen frame: `outputPath` or its Display name, with the frame's number
/// inserted when several frames would share one name (FrameOutputPath).
std::vector<std::string> FrameOutputs(const std::vector<const renderer::SceneDesc*>& chosen,
                                      const std::string& outputPath);

/// `path` with frame number `frame` inserted before its extension, as 4 digits at least:
/// ("out.exr", 7) -> "out.0007.exr"; ("dir.v2/out", 7) -> "dir.v2/out.0007".
std::string FrameOutputPath(const std::string& path, int frame);

/// Prints `report` to `err` in the one format.
void Print(const diag::Report& report, FILE* err);

}  // namespace affray::tools
