// tools/main.cpp: the `affray` command line. Only argument parsing lives here; each subcommand's
// work is in tools/commands.cpp.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "diag/limits.h"
#include "tools/commands.h"
#include "vm/disasm.h"

namespace {

namespace diag = affray::diag;

const char* const kUsage =
    "usage:\n"
    "  affray render SCENE.rib [-o OUT.exr] [--threads N] [--tolerance PIXELS] [-I DIR] [-D NAME[=VALUE]]\n"
    "                [--bounds affine|reduced|interval] [--max-depth N] [--stats] [--png PREVIEW.png] [--quiet]\n"
    "                [--crop XMIN,XMAX,YMIN,YMAX] [--samples N] [--region-budget N] [--cache-mb MB]\n"
    "                [--texture-mb MB] [--ray-groups PIXELS] [--newton] [--frame N] [--resume] [--time-limit S]\n"
    "  affray compile SHADER.sl [-o OUT.afb] [--disasm] [--stats] [-I DIR] [-D NAME[=VALUE]]\n"
    "  affray eval SHADER.sl [--param NAME=VALUE]... (--at U,V ... | --region U0,U1,V0,V1)\n"
    "              [--mode scalar|affine|interval] [-I DIR] [-D NAME[=VALUE]]\n"
    "  affray split SCENE.rib --tiles N [-o OUT.exr] [--shell] [--threads N] [--frame N] [render options]\n"
    "              (Slurm job scripts for a farm, or with --shell one render command per tile)\n"
    "  affray merge OUT.exr TILE.exr...   (the tiles of a split, checked and pasted into one image)\n"
    "  affray diff REFERENCE.exr TEST.exr   (RMSE and largest error of TEST's RGB, as JSON)\n"
    "  affray opcodes   (the VM's instruction set, as a Markdown table)\n"
    "  affray limits    (the resource limits; render, compile and eval take --limit NAME=VALUE)\n"
    "  affray --help | --version\n";

/// `affray render --help`: the usage, then what render does with its files.
const char* const kRenderHelp =
    "\n"
    "affray render writes OUT.exr (or the scene's Display name) and, with --png, an 8-bit preview;\n"
    "each file is written to a temporary name beside it and renamed, so it is whole or absent.\n"
    "\n"
    "Interrupted renders:\n"
    "  While it runs, finished tiles are appended to OUT.exr.checkpoint. SIGINT (Ctrl-C) or SIGTERM\n"
    "  stops the render: no image is written, the checkpoint is kept, and the exit status is 130\n"
    "  (SIGINT) or 143 (SIGTERM). The checkpoint is removed once the image is written.\n"
    "  --resume      continue from OUT.exr.checkpoint: render only the missing tiles, and write the\n"
    "                image an uninterrupted render writes, bit for bit. A checkpoint of another scene\n"
    "                (RIB, shader or texture) or of other options (resolution, crop, samples,\n"
    "                tolerance, bounds...) is refused; --threads, --cache-mb and --texture-mb may differ.\n"
    "  Without --resume, an existing checkpoint is overwritten.\n"
    "  --time-limit S  stop after S seconds of wall-clock time as if interrupted, but with exit\n"
    "                status 4 and an error naming the limit (the same as --limit time-limit=S).\n";

struct UsageError {
    std::string message;
};

/// Parses a comma-separated list of finite numbers, e.g. "0.5,0.25".
std::vector<double> ParseNumbers(const std::string& text, const std::string& option) {
    std::vector<double> values;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        double x = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0') throw UsageError{option + ": '" + item + "' is not a number"};
        if (!std::isfinite(x)) throw UsageError{option + ": '" + item + "' is not finite"};
        values.push_back(x);
    }
    if (!text.empty() && text.back() == ',') throw UsageError{option + ": trailing comma in '" + text + "'"};
    return values;
}

/// Every comma-separated item starts like a number (strtod reads something, nan and inf too).
bool LooksNumeric(const std::string& text) {
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        std::strtod(item.c_str(), &end);
        if (end == item.c_str()) return false;
    }
    return !text.empty();
}

double ParseNumber(const std::string& text, const std::string& option) {
    std::vector<double> v = ParseNumbers(text, option);
    if (v.size() != 1) throw UsageError{option + " takes one number, got '" + text + "'"};
    return v[0];
}

int ParseInt(const std::string& text, const std::string& option, int lo, int hi) {
    double x = ParseNumber(text, option);
    if (x != std::floor(x) || x < lo || x > hi)
        throw UsageError{option + " takes an integer from " + std::to_string(lo) + " to " + std::to_string(hi)};
    return static_cast<int>(x);
}

class Args {
  public:
    Args(int argc, char** argv, int first) : m_args(argv + first, argv + argc) {}
    bool Done() const { return m_next >= m_args.size(); }
    std::string Next() { return m_args[m_next++]; }
    size_t Position() const { return m_next; }
    const std::string& At(size_t i) const { return m_args[i]; }
    std::string Value(const std::string& option) {
        if (Done()) throw UsageError{option + " needs a value"};
        return Next();
    }

  private:
    std::vector<std::string> m_args;
    size_t m_next = 0;
};

/// Takes -I DIR, -IDIR, -D NAME[=VALUE] and -DNAME[=VALUE]; false if `a` is none of them.
bool PreprocessorOption(const std::string& a, Args& args, affray::lang::PreprocessOptions* options) {
    if (a.size() < 2 || a[0] != '-' || (a[1] != 'I' && a[1] != 'D')) return false;
    std::string value = a.size() > 2 ? a.substr(2) : args.Value(a);
    if (value.empty()) throw UsageError{a.substr(0, 2) + " needs a value"};
    (a[1] == 'I' ? options->includeDirs : options->defines).push_back(value);
    return true;
}

/// Takes --limit NAME=VALUE and --time-limit S (diag/limits.h); false if `a` is neither.
bool LimitOption(const std::string& a, Args& args) {
    std::string assignment;
    if (a == "--limit")
        assignment = args.Value(a);
    else if (a == "--time-limit")
        assignment = "time-limit=" + args.Value(a);
    else
        return false;
    if (std::optional<std::string> error = diag::ApplyLimit(assignment)) throw UsageError{*error};
    return true;
}

void SetInput(std::string* slot, const std::string& arg) {
    if (!arg.empty() && arg[0] == '-' && arg != "-") throw UsageError{"unknown option '" + arg + "'"};
    if (!slot->empty()) throw UsageError{"unexpected argument '" + arg + "'"};
    *slot = arg;
}

int Compile(Args& args) {
    affray::tools::CompileCommand cmd;
    while (!args.Done()) {
        std::string a = args.Next();
        if (a == "-o")
            cmd.outputPath = args.Value(a);
        else if (a == "--disasm")
            cmd.disasm = true;
        else if (a == "--stats")
            cmd.stats = true;
        else if (LimitOption(a, args) || PreprocessorOption(a, args, &cmd.preprocess))
            continue;
        else
            SetInput(&cmd.shaderPath, a);
    }
    if (cmd.shaderPath.empty()) throw UsageError{"compile: missing SHADER.sl"};
    return affray::tools::RunCompile(cmd, stdout, stderr);
}

int Eval(Args& args) {
    affray::tools::EvalCommand cmd;
    while (!args.Done()) {
        std::string a = args.Next();
        if (a == "--param") {
            std::string p = args.Value(a);
            size_t eq = p.find('=');
            if (eq == std::string::npos || eq == 0) throw UsageError{"--param takes NAME=VALUE, got '" + p + "'"};
            // A value that is not a list of numbers is a string parameter's value.
            const std::string name = p.substr(0, eq), value = p.substr(eq + 1);
            if (LooksNumeric(value))
                cmd.params.emplace_back(name, ParseNumbers(value, "--param " + name));
            else
                cmd.params.push_back(affray::compiler::ParamOverride::String(name, value));
        } else if (a == "--at") {
            std::vector<double> uv = ParseNumbers(args.Value(a), a);
            if (uv.size() != 2) throw UsageError{"--at takes U,V"};
            cmd.points.push_back({uv[0], uv[1]});
        } else if (a == "--region") {
            std::vector<double> r = ParseNumbers(args.Value(a), a);
            if (r.size() != 4) throw UsageError{"--region takes U0,U1,V0,V1"};
            if (r[0] > r[1] || r[2] > r[3]) throw UsageError{"--region needs U0 <= U1 and V0 <= V1"};
            cmd.hasRegion = true;
            cmd.region = {r[0], r[1], r[2], r[3]};
        } else if (a == "--mode") {
            cmd.mode = args.Value(a);
            if (cmd.mode != "scalar" && cmd.mode != "affine" && cmd.mode != "interval")
                throw UsageError{"--mode takes scalar, affine or interval, got '" + cmd.mode + "'"};
        } else if (!LimitOption(a, args) && !PreprocessorOption(a, args, &cmd.preprocess)) {
            SetInput(&cmd.shaderPath, a);
        }
    }
    if (cmd.shaderPath.empty()) throw UsageError{"eval: missing SHADER.sl"};
    if (cmd.points.empty() == !cmd.hasRegion) throw UsageError{"eval: give either --at U,V or --region U0,U1,V0,V1"};
    if (cmd.hasRegion && cmd.mode == "scalar")
        throw UsageError{"eval: --region bounds a region; use --mode affine or --mode interval"};
    return affray::tools::RunEval(cmd, stdout, stderr);
}

int Diff(Args& args) {
    affray::tools::DiffCommand cmd;
    std::vector<std::string> files;
    while (!args.Done()) files.push_back(args.Next());
    if (files.size() != 2) throw UsageError{"diff takes two images: REFERENCE.exr TEST.exr"};
    cmd.reference = files[0];
    cmd.test = files[1];
    return affray::tools::RunDiff(cmd, stdout, stderr);
}

/// Takes one option of `affray render` (all but --help) into *cmd; false if `a` is none.
bool RenderOption(const std::string& a, Args& args, affray::tools::RenderCommand* cmdOut) {
    affray::tools::RenderCommand& cmd = *cmdOut;
    if (a == "-o")
        cmd.outputPath = args.Value(a);
    else if (a == "--threads")
        cmd.threads = ParseInt(args.Value(a), a, 1, 1024);
    else if (a == "--tolerance") {
        cmd.tolerance = ParseNumber(args.Value(a), a);
        cmd.toleranceGiven = true;
        if (!(cmd.tolerance > 0)) throw UsageError{"--tolerance must be positive"};
    } else if (a == "--max-depth")
        cmd.maxDepth = ParseInt(args.Value(a), a, 1, 40);
    else if (a == "--bounds") {
        std::string b = args.Value(a);
        if (b == "affine")
            cmd.bounds = affray::renderer::BoundMode::Affine;
        else if (b == "reduced")
            cmd.bounds = affray::renderer::BoundMode::Reduced;
        else if (b == "interval")
            cmd.bounds = affray::renderer::BoundMode::Interval;
        else
            throw UsageError{"--bounds takes affine, reduced or interval, got '" + b + "'"};
    } else if (a == "--stats")
        cmd.stats = true;
    else if (a == "--png")
        cmd.pngPath = args.Value(a);
    else if (a == "--quiet" || a == "-q")
        cmd.quiet = true;
    else if (a == "--samples")
        cmd.samples = ParseInt(args.Value(a), a, 1, 256);  // past pixel-samples, Renderer::Prepare says so
    else if (a == "--region-budget")
        cmd.regionBudget = ParseInt(args.Value(a), a, 1, 1 << 30);
    else if (a == "--frame")
        cmd.frame = ParseInt(args.Value(a), a, -1000000000, 1000000000);
    else if (a == "--resume")
        cmd.resume = true;
    else if (a == "--tile-order") {
        // For tests of determinism; not in the usage text.
        const std::string order = args.Value(a);
        if (order != "forward" && order != "reverse")
            throw UsageError{"--tile-order takes forward or reverse, got '" + order + "'"};
        cmd.reverseTiles = order == "reverse";
    } else if (a == "--bvh") {
        // For tests of determinism; not in the usage text.
        const std::string split = args.Value(a);
        if (split != "sah" && split != "median") throw UsageError{"--bvh takes sah or median, got '" + split + "'"};
        cmd.medianBvh = split == "median";
    } else if (a == "--ray-groups")
        cmd.rayGroupPixels = ParseInt(args.Value(a), a, 0, 256);
    else if (a == "--newton")
        cmd.newton = true;
    else if (a == "--cache-mb") {
        const double mb = ParseNumber(args.Value(a), a);
        if (!(mb >= 0 && mb <= 1 << 20)) throw UsageError{"--cache-mb takes a size in MiB from 0 to 1048576"};
        cmd.cacheBytes = static_cast<size_t>(mb * (1 << 20));
    } else if (a == "--texture-mb") {
        const double mb = ParseNumber(args.Value(a), a);
        if (!(mb >= 0 && mb <= 1 << 20)) throw UsageError{"--texture-mb takes a size in MiB from 0 to 1048576"};
        cmd.textureBytes = static_cast<size_t>(mb * (1 << 20));
    } else if (a == "--crop") {
        std::vector<double> c = ParseNumbers(args.Value(a), a);
        if (c.size() != 4 || !(0 <= c[0] && c[0] < c[1] && c[1] <= 1 && 0 <= c[2] && c[2] < c[3] && c[3] <= 1))
            throw UsageError{"--crop takes XMIN,XMAX,YMIN,YMAX with 0 <= min < max <= 1"};
        cmd.crop = std::array<double, 4>{c[0], c[1], c[2], c[3]};
    } else if (!LimitOption(a, args) && !PreprocessorOption(a, args, &cmd.preprocess))
        return false;
    return true;
}

/// -o writes OpenEXR whatever the name: another image format's name would hide that.
void CheckExrName(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* other : {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".tga", ".hdr"})
        if (extension == other)
            throw UsageError{"-o writes OpenEXR: name the file .exr, not '" + path +
                             "' (--png writes an 8-bit preview)"};
}

int Render(Args& args) {
    affray::tools::RenderCommand cmd;
    while (!args.Done()) {
        std::string a = args.Next();
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            std::fputs(kRenderHelp, stdout);
            return affray::diag::kExitSuccess;
        }
        if (!RenderOption(a, args, &cmd)) SetInput(&cmd.scenePath, a);
    }
    if (cmd.scenePath.empty()) throw UsageError{"render: missing SCENE.rib"};
    CheckExrName(cmd.outputPath);
    return affray::tools::RunRender(cmd, stdout, stderr);
}

int Split(Args& args) {
    affray::tools::SplitCommand cmd;
    affray::tools::RenderCommand render;  // checks the options given to every task
    while (!args.Done()) {
        const size_t start = args.Position();
        std::string a = args.Next();
        if (a == "--tiles")
            cmd.tiles = ParseInt(args.Value(a), a, 1, 1 << 20);
        else if (a == "--shell")
            cmd.shell = true;
        else if (a == "-o")
            cmd.outputPath = args.Value(a);
        else if (a == "--threads")
            cmd.threads = ParseInt(args.Value(a), a, 1, 1024);
        else if (a == "--frame")
            cmd.frame = ParseInt(args.Value(a), a, -1000000000, 1000000000);
        else if (a == "--crop" || a == "--resume" || a == "--png" || a == "--stats" || a == "--tile-order" ||
                 a == "--quiet" || a == "-q")
            throw UsageError{"split: " + a + " is not an option of split (each task renders its own --crop, " +
                             "quietly, with --resume)"};
        else if (RenderOption(a, args, &render))
            for (size_t i = start; i < args.Position(); ++i) cmd.renderArgs.push_back(args.At(i));
        else
            SetInput(&cmd.scenePath, a);
    }
    if (cmd.scenePath.empty()) throw UsageError{"split: missing SCENE.rib"};
    if (cmd.tiles == 0) throw UsageError{"split: missing --tiles N"};
    CheckExrName(cmd.outputPath);
    return affray::tools::RunSplit(cmd, stdout, stderr);
}

int Merge(Args& args) {
    affray::tools::MergeCommand cmd;
    while (!args.Done()) {
        std::string a = args.Next();
        if (!a.empty() && a[0] == '-') throw UsageError{"unknown option '" + a + "'"};
        if (cmd.outputPath.empty())
            cmd.outputPath = a;
        else
            cmd.tiles.push_back(a);
    }
    if (cmd.tiles.empty()) throw UsageError{"merge takes OUT.exr and at least one TILE.exr"};
    CheckExrName(cmd.outputPath);
    return affray::tools::RunMerge(cmd, stdout, stderr);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fputs(kUsage, stderr);
        return diag::kExitUsage;
    }
    std::string command = argv[1];
    if (command == "--help" || command == "-h" || command == "help") {
        std::fputs(kUsage, stdout);
        return diag::kExitSuccess;
    }
    if (command == "--version") {
        std::printf("affray %s\n", affray::tools::kVersion);
        return diag::kExitSuccess;
    }
    Args args(argc, argv, 2);
    try {
        if (command == "compile") return Compile(args);
        if (command == "eval") return Eval(args);
        if (command == "render") return Render(args);
        if (command == "diff") return Diff(args);
        if (command == "split") return Split(args);
        if (command == "merge") return Merge(args);
        if (command == "opcodes") {
            if (!args.Done()) throw UsageError{"opcodes takes no arguments"};
            std::fputs(affray::vm::OpcodeTable().c_str(), stdout);
            return diag::kExitSuccess;
        }
        if (command == "limits") {
            while (!args.Done()) {
                const std::string a = args.Next();
                if (!LimitOption(a, args)) throw UsageError{"limits takes only --limit NAME=VALUE, got '" + a + "'"};
            }
            std::fputs(diag::LimitsTable().c_str(), stdout);
            return diag::kExitSuccess;
        }
        throw UsageError{"unknown command '" + command + "'"};
    } catch (const UsageError& e) {
        std::fprintf(stderr, "%s%s", diag::Format({diag::Severity::Error, {"affray"}, e.message, {}}).c_str(), kUsage);
        return diag::kExitUsage;
    } catch (const std::bad_alloc&) {
        const std::string message = "out of memory (is the image or the scene too large?)";
        std::fputs(diag::Format({diag::Severity::Error, {"affray"}, message, {}}).c_str(), stderr);
        return diag::kExitResources;
    } catch (const std::exception& e) {
        // Only a bug gets here: every library reports bad input as diagnostics.
        const std::string message = std::string("internal error: ") + e.what() + " (please report this)";
        std::fputs(diag::Format({diag::Severity::Error, {"affray"}, message, {}}).c_str(), stderr);
        return diag::kExitInternal;
    }
}
