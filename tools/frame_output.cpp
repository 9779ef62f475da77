// tools/frame_output.cpp: outputs, checkpoint and interruption of one frame's render (frame_output.h).
#include "tools/frame_output.h"

#include "diag/limits.h"

#include <filesystem>

#include "image/atomic_file.h"
#include "renderer/render_identity.h"
#include "tools/interrupt.h"

namespace affray::tools {
namespace {

void Error(const std::string& where, const std::string& message, FILE* err) {
    std::fputs(diag::Format({diag::Severity::Error, {where}, message, {}}).c_str(), err);
}

}  // namespace

int FrameOutput::Begin(bool resume, const renderer::PreparedScene& scene, const renderer::Renderer& renderer,
                       renderer::RenderControl* control, FILE* err) {
    // A render that could not write its image would be lost: check before it starts.
    for (const std::string& path : {m_output, m_png}) {
        std::string reason;
        if (!path.empty() && !image::CheckWritable(path, &reason)) {
            Error(path, "cannot write file: " + reason, err);
            return diag::kExitOutput;
        }
    }
    const renderer::CameraDesc& camera = scene.desc.camera;
    const renderer::Film film(camera);
    const renderer::RenderIdentity identity = renderer::IdentifyRender(scene, renderer.options());
    m_checkpointPath = renderer::CheckpointPath(m_output);
    std::error_code ec;
    const bool resumed = resume && std::filesystem::exists(m_checkpointPath, ec);
    if (resumed) {
        renderer::CheckpointContents contents;
        std::string error;
        if (!renderer::ReadCheckpoint(m_checkpointPath, &contents, &error)) {
            Error(m_checkpointPath, "--resume: cannot use the checkpoint: " + error, err);
            return diag::kExitBadInput;
        }
        // Options first: those that override the scene's (crop, samples) change its hash too.
        std::string mismatch;
        if (const std::string names = renderer::DifferingOptions(contents.identity.options, identity.options);
            !names.empty())
            mismatch = "other options (" + names + ")";
        else if (contents.identity.scene != identity.scene)
            mismatch = "another scene (the RIB file, a shader or a texture differs)";
        else if (contents.identityHash != identity.Hash() || contents.width != camera.xres ||
                 contents.height != camera.yres)
            mismatch = "another render";
        if (!mismatch.empty()) {
            Error(m_checkpointPath,
                  "--resume: the checkpoint was written by a render of " + mismatch +
                      "; render without --resume to start again",
                  err);
            return diag::kExitBadInput;
        }
        control->tileSize = contents.tileSize;
        const bool dropped = contents.droppedTail;
        m_checkpoint = renderer::CheckpointFile::Resume(m_checkpointPath, std::move(contents), &error);
        if (!m_checkpoint) {
            Error(m_checkpointPath, "--resume: cannot open the checkpoint: " + error, err);
            return diag::kExitOutput;
        }
        if (dropped)
            std::fputs(diag::Format({diag::Severity::Note,
                                     {m_checkpointPath},
                                     "its last tile was cut short (the render was killed while writing it): "
                                     "that tile is rendered again",
                                     {}})
                           .c_str(),
                       err);
    } else {
        // Without --resume an old checkpoint is replaced.
        control->tileSize = renderer.TileSize(camera);
        std::string error;
        m_checkpoint = renderer::CheckpointFile::Create(m_checkpointPath, identity, camera.xres, camera.yres,
                                                        control->tileSize, &error);
        if (!m_checkpoint) {
            Error(m_checkpointPath, "cannot write file: " + error, err);
            return diag::kExitOutput;
        }
    }
    m_tiles = static_cast<int>(film.Tiles(control->tileSize).size());
    if (resume)
        std::fputs(diag::Format({diag::Severity::Note,
                                 {m_checkpointPath},
                                 resumed ? "resuming: " + std::to_string(m_checkpoint->tiles()) + " of " +
                                               std::to_string(m_tiles) + " tiles are taken from the checkpoint"
                                         : std::string("--resume: there is no checkpoint; every tile is rendered"),
                                 {}})
                       .c_str(),
                   err);
    control->tileStore = m_checkpoint.get();
    control->stop = &Interrupts::Flag();
    return diag::kExitSuccess;
}

int FrameOutput::AfterRender(const renderer::RenderStats& stats, FILE* err) {
    const std::string checkpointError = m_checkpoint->error();
    if (!checkpointError.empty())
        std::fputs(diag::Format({diag::Severity::Warning,
                                 {m_checkpointPath},
                                 "cannot write the checkpoint: " + checkpointError +
                                     " (the render went on without it; an interruption would lose it)",
                                 {}})
                       .c_str(),
                   err);
    if (!stats.stopped) return diag::kExitSuccess;
    const int signal = Interrupts::Signal();
    const bool timedOut = Interrupts::TimedOut();
    m_checkpoint->Sync();
    const int kept = m_checkpoint->tiles();
    std::string message = timedOut ? "stopped after " + std::to_string(diag::LimitValue(diag::Limit::TimeLimit)) +
                                         " s of wall-clock time " + diag::LimitNote(diag::Limit::TimeLimit) +
                                         ": no image written"
                                   : "interrupted by " + Interrupts::SignalName(signal) + ": no image written";
    if (checkpointError.empty())
        message += "; " + std::to_string(kept) + " of " + std::to_string(m_tiles) + " tiles kept in " +
                   m_checkpointPath + " (the same command with --resume renders the rest)";
    else
        m_checkpoint->Remove();
    Error(m_output, message, err);
    return timedOut ? diag::kExitResources : Interrupts::ExitCode(signal);
}

void FrameOutput::Finish() { m_checkpoint->Remove(); }

}  // namespace affray::tools
