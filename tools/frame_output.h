// tools/frame_output.h: what `affray render` does around one frame's render so that no output is
// lost or left half made (issue 17): the outputs are checked writable before the render starts,
// finished tiles go to a checkpoint beside the output (renderer/checkpoint.h) that --resume
// continues, a SIGINT or SIGTERM (tools/interrupt.h) stops the render without writing an image,
// and the checkpoint is removed once the image is written.
#pragma once

#include <cstdio>
#include <memory>
#include <string>

#include "renderer/checkpoint.h"
#include "renderer/renderer.h"
#include "tools/commands.h"

namespace affray::tools {

class FrameOutput {
  public:
    FrameOutput(std::string outputPath, std::string pngPath)
        : m_output(std::move(outputPath)), m_png(std::move(pngPath)) {}

    /// Before the render: checks that the outputs can be written, then starts the checkpoint (with
    /// `resume`, continues the one there if it is this render's) and sets in *control the tiling,
    /// the tile store and the stop flag for `renderer` to render `scene` with. Returns
    /// kExitSuccess, or the exit code after printing the error to `err`.
    int Begin(bool resume, const renderer::PreparedScene& scene, const renderer::Renderer& renderer,
              renderer::RenderControl* control, FILE* err);

    /// After the render: if a signal stopped it, keeps the checkpoint and returns the exit code
    /// (128 + signal) after saying so on `err`; else kExitSuccess. Warns if the checkpoint could
    /// not be written.
    int AfterRender(const renderer::RenderStats& stats, FILE* err);

    /// After writing the image, or failing to: removes the checkpoint. (A failed write leaves
    /// nothing behind, the checkpoint included.)
    void Finish();

  private:
    std::string m_output, m_png, m_checkpointPath;
    std::unique_ptr<renderer::CheckpointFile> m_checkpoint;
    int m_tiles = 0;  // in the whole render
};

}  // namespace affray::tools
