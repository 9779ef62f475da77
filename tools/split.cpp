// tools/split.cpp: `affray split SCENE.rib --tiles N`, a render cut into tasks for a farm. Each
// frame the render would write is cut into N tiles (renderer/tiling.h: exact pixel rectangles,
// each rendered with the crop window that maps to it), and each frame x tile is one task:
//   Slurm (default): three files beside the output OUT.exr, with absolute paths and the current
//     directory as the jobs' working directory (so the shader search path is the same):
//       OUT.render.sbatch  a job array, one task per frame x tile (task i picks its arguments by
//                          $SLURM_ARRAY_TASK_ID), each `affray render ... --crop ... --resume`
//       OUT.merge.sbatch   `affray merge` of every frame's tiles, run once they all succeed
//       OUT.submit.sh      sbatch --parsable of the array, then of the merge job with
//                          --dependency=afterok:ARRAY; `OUT.submit.sh 3,5` resubmits tasks 3 and 5
//                          only (and a new merge job; the old one is cancelled by Slurm, its
//                          dependency never being satisfied: --kill-on-invalid-dep)
//   --shell: one plain `affray render` command line per task on stdout (tiles written in the
//     current directory), for any system that runs commands; the merge commands go to stderr.
// With --tiles 1 each frame is one task that writes its image directly, and nothing is merged.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "renderer/tiling.h"
#include "tools/commands.h"

namespace affray::tools {
namespace {

namespace fs = std::filesystem;

/// `text` as one shell word: bare if it holds only safe characters, else in single quotes.
std::string ShellWord(const std::string& text) {
    const bool safe = !text.empty() && text.find_first_not_of(
                                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                           "0123456789_./,:=+-@%") == std::string::npos;
    if (safe) return text;
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

/// Where `path`'s extension starts (as FrameOutputPath sees it), or npos if it has none.
size_t ExtensionDot(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    const bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
    return hasExtension ? dot : std::string::npos;
}

/// `path` with `suffix` inserted before its extension: ("out.0001.exr", ".tile3") -> "out.0001.tile3.exr".
std::string InsertBeforeExtension(const std::string& path, const std::string& suffix) {
    const size_t dot = ExtensionDot(path);
    return dot == std::string::npos ? path + suffix : path.substr(0, dot) + suffix + path.substr(dot);
}

/// `path` without its extension.
std::string Stem(const std::string& path) { return path.substr(0, ExtensionDot(path)); }

/// One task: a frame's tile.
struct Task {
    std::vector<std::string> args;  // after `affray render SCENE`
    std::string tile;               // the file it writes
};

/// One frame's merge: its image and its tiles.
struct FrameMerge {
    std::string output;
    std::vector<std::string> tiles;
};

bool WriteScript(const std::string& path, const std::string& text, FILE* err) {
    {
        std::ofstream file(path, std::ios::binary | std::ios::trunc);
        file << text;
        if (!file.flush()) {
            std::fputs(diag::Format({diag::Severity::Error, {path}, "cannot write file", {}}).c_str(), err);
            return false;
        }
    }
    std::error_code ec;
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add,
                    ec);
    return true;
}

}  // namespace

int RunSplit(const SplitCommand& cmd, FILE* out, FILE* err) {
    std::vector<renderer::SceneDesc> frames;
    int status = diag::kExitSuccess;
    const std::vector<const renderer::SceneDesc*> chosen =
        ReadChosenFrames(cmd.scenePath, cmd.frame, err, &frames, &status);
    if (chosen.empty()) return status;
    // Tasks pick their frame by number: two rendered frames of one number cannot be told apart.
    std::map<int, int> numbers;
    for (const renderer::SceneDesc* frame : chosen)
        if (frame->frame && ++numbers[*frame->frame] > 1) {
            std::fputs(diag::Format({diag::Severity::Error,
                                     {cmd.scenePath},
                                     "two frames numbered " + std::to_string(*frame->frame) +
                                         " render images: split needs each frame's number to pick it",
                                     {}})
                           .c_str(),
                       err);
            return diag::kExitBadInput;
        }

    // Slurm jobs run elsewhere: absolute paths; --shell commands run where the farm puts them.
    std::error_code ec;
    const std::string workDir = fs::current_path(ec).string();
    auto place = [&](const std::string& path) {
        return cmd.shell ? fs::path(path).filename().string() : fs::absolute(path, ec).lexically_normal().string();
    };
    const std::vector<std::string> outputs = FrameOutputs(chosen, cmd.outputPath);
    std::vector<Task> tasks;
    std::vector<FrameMerge> merges;
    for (size_t f = 0; f < chosen.size(); ++f) {
        const renderer::CameraDesc& camera = chosen[f]->camera;
        const std::vector<renderer::PixelRange> tiles = renderer::SplitFrame(camera.xres, camera.yres, cmd.tiles);
        if (tiles.empty()) {
            std::fputs(diag::Format({diag::Severity::Error,
                                     {cmd.scenePath},
                                     "--tiles " + std::to_string(cmd.tiles) + ": a " + std::to_string(camera.xres) +
                                         "x" + std::to_string(camera.yres) + " frame cannot be cut into so many tiles",
                                     {}})
                           .c_str(),
                       err);
            return diag::kExitUsage;
        }
        FrameMerge merge{place(outputs[f]), {}};
        for (size_t t = 0; t < tiles.size(); ++t) {
            Task task;
            task.tile = tiles.size() == 1 ? merge.output
                                          : place(InsertBeforeExtension(outputs[f], ".tile" + std::to_string(t)));
            if (chosen[f]->frame) task.args = {"--frame", std::to_string(*chosen[f]->frame)};
            task.args.insert(task.args.end(),
                             {"--crop", renderer::CropWindowText(tiles[t], camera.xres, camera.yres), "-o", task.tile});
            task.args.insert(task.args.end(), cmd.renderArgs.begin(), cmd.renderArgs.end());
            merge.tiles.push_back(task.tile);
            tasks.push_back(std::move(task));
        }
        if (tiles.size() > 1) merges.push_back(std::move(merge));
    }

    if (cmd.shell) {
        // One command per line on stdout; how to merge on stderr.
        for (const Task& task : tasks) {
            std::string line = "affray render " + ShellWord(cmd.scenePath);
            for (const std::string& a : task.args) line += " " + ShellWord(a);
            std::fprintf(out, "%s --threads %d --quiet --resume\n", line.c_str(), cmd.threads);
        }
        for (const FrameMerge& merge : merges) {
            std::string line = "affray merge " + ShellWord(merge.output);
            for (const std::string& tile : merge.tiles) line += " " + ShellWord(tile);
            std::fputs(diag::Format({diag::Severity::Note, {"affray split"}, "then: " + line, {}}).c_str(), err);
        }
        return diag::kExitSuccess;
    }

    // Slurm: the job array, the merge job and the script that submits both.
    const std::string base =
        fs::absolute(Stem(cmd.outputPath.empty() ? outputs[0] : cmd.outputPath), ec).lexically_normal().string();
    const std::string name = fs::path(base).filename().string();
    std::string program = cmd.program;
    if (program.empty()) program = fs::read_symlink("/proc/self/exe", ec).string();
    const std::string renderPath = base + ".render.sbatch", mergePath = base + ".merge.sbatch",
                      submitPath = base + ".submit.sh";
    std::string render =
        "#!/bin/bash\n"
        "# Written by affray split: renders " +
        std::to_string(tasks.size()) + " tiles of " + cmd.scenePath +
        " as a Slurm job array, one task each.\n"
        "# Submit with " +
        fs::path(submitPath).filename().string() +
        " (it submits the merge job too). A task rerun continues its checkpoint.\n"
        "#SBATCH --job-name=affray-render-" +
        name + "\n#SBATCH --array=0-" + std::to_string(tasks.size() - 1) +
        "\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=" + std::to_string(cmd.threads) +
        "\n#SBATCH --chdir=" + workDir + "\n#SBATCH --output=" + base + ".render-%A_%a.log\n" +
        "set -euo pipefail\n"
        "case \"${SLURM_ARRAY_TASK_ID:?run this script with sbatch}\" in\n";
    for (size_t i = 0; i < tasks.size(); ++i) {
        render += "    " + std::to_string(i) + ") set --";
        for (const std::string& a : tasks[i].args) render += " " + ShellWord(a);
        render += " ;;\n";
    }
    render += "    *) echo \"affray split: no task $SLURM_ARRAY_TASK_ID\" >&2; exit 2 ;;\nesac\n";
    render += "exec " + ShellWord(program) + " render " + ShellWord(fs::absolute(cmd.scenePath, ec).string()) +
              " \"$@\" --threads \"${SLURM_CPUS_PER_TASK:-" + std::to_string(cmd.threads) + "}\" --quiet --resume\n";
    std::string merge =
        "#!/bin/bash\n"
        "# Written by affray split: merges the tiles of " +
        cmd.scenePath +
        " once every render task has succeeded.\n"
        "#SBATCH --job-name=affray-merge-" +
        name + "\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n#SBATCH --kill-on-invalid-dep=yes\n" +
        "#SBATCH --chdir=" + workDir + "\n#SBATCH --output=" + base + ".merge-%j.log\n" + "set -euo pipefail\n";
    for (const FrameMerge& m : merges) {
        merge += ShellWord(program) + " merge " + ShellWord(m.output);
        for (const std::string& tile : m.tiles) merge += " " + ShellWord(tile);
        merge += "\n";
    }
    std::string submit =
        "#!/bin/sh\n"
        "# Written by affray split: submits the render job array (every task, or those listed:\n"
        "# " +
        fs::path(submitPath).filename().string() +
        " 3,5) and the merge job, which runs once they succeed. Prints both job ids.\n"
        "set -eu\n"
        "if [ $# -gt 0 ]; then array=\"--array=$1\"; else array=\"\"; fi\n"
        "render=$(sbatch --parsable $array " +
        ShellWord(renderPath) + ")\nrender=${render%%;*}\n";
    if (merges.empty())
        submit += "echo \"render job $render\"\n";
    else
        submit += "merge=$(sbatch --parsable --dependency=afterok:$render " + ShellWord(mergePath) +
                  ")\nmerge=${merge%%;*}\necho \"render job $render, merge job $merge\"\n";
    if (!WriteScript(renderPath, render, err) || (!merges.empty() && !WriteScript(mergePath, merge, err)) ||
        !WriteScript(submitPath, submit, err))
        return diag::kExitOutput;
    std::fprintf(out, "%s\n%s%s\n", renderPath.c_str(), merges.empty() ? "" : (mergePath + "\n").c_str(),
                 submitPath.c_str());
    std::fputs(diag::Format({diag::Severity::Note,
                             {"affray split"},
                             std::to_string(tasks.size()) + " tasks; submit them with " + ShellWord(submitPath),
                             {}})
                   .c_str(),
               err);
    return diag::kExitSuccess;
}

}  // namespace affray::tools
