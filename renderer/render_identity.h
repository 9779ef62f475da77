// renderer/render_identity.h: what identifies a render's pixels, as text that two processes can
// compare: a checkpoint is resumed only by the render that wrote it (renderer/checkpoint.h),
// and tiles rendered on many machines may be merged only if they come from the same render.
//
// A render is identified by two parts:
//   scene    the hash of everything read that decides the pixels: the RIB file's bytes, the scene
//            as read (ToString(SceneDesc): archives, and the camera after command-line overrides
//            such as --crop and --samples), each primitive's specialised bound and shade programs
//            (SaveBytecode: so the shader sources, -D/-I and included files count through what
//            they compiled to) with its shader's source text, and every texture file a program
//            reads, by size and modification time (not content: maps can be large). File paths
//            count by their file names only, so the identity is the same whichever directory
//            the render starts in, or wherever a farm machine mounts the project. Everything
//            but the scene's head line and camera is digested once per prepared scene
//            (PreparedScene::identityDigest), which the render's and the frame's identity share.
//   options  the render options that change pixels, as canonical "name=value" lines (so a
//            mismatch can be named): resolution, crop, samples, frame, display mode, tolerance,
//            bounds, max depth, region budget and ray groups. Options that do not change pixels
//            (threads, tile order and size, cache and texture budgets) are left out: the image is
//            the same bit for bit whatever they are (tests/tools/determinism_cli_test.cpp).
// Hash(): FNV-1a 128 (Fowler, Noll and Vo) of both parts, 32 lowercase hex digits. It detects
// accidents (another scene, an edited shader), not forgeries.
//
// Adding to it: anything new that changes pixels (a new option, a new kind of input file) goes
// into IdentifyRender, and an old checkpoint is then refused, which is the safe side.
#pragma once

#include <string>
#include <string_view>

#include "renderer/options.h"
#include "renderer/render.h"

namespace affray::renderer {

struct RenderIdentity {
    std::string scene;    ///< 32 hex digits (HashHex of the scene's inputs)
    std::string options;  ///< "name=value" lines, each ending in '\n'
    /// HashHex of scene and options: the one string that identifies the render.
    std::string Hash() const;
};

/// Identifies the render of `scene` (prepared, from the RIB file scene.desc.path) with `options`.
/// Files that cannot be read count as such (a hash of their name), never as an error.
RenderIdentity IdentifyRender(const PreparedScene& scene, const Options& options);

/// The identity of the whole frame that a render of `scene` is a part of: IdentifyRender with the
/// crop window left out (the scene hashed as if it had none, and no "crop=" line in options).
/// Tiles of one frame rendered with different crops share it (affray merge checks it).
RenderIdentity IdentifyFrame(const PreparedScene& scene, const Options& options);

/// FNV-1a 128 of `bytes`, as 32 lowercase hex digits.
std::string HashHex(std::string_view bytes);

/// The names of the options whose lines differ between two RenderIdentity::options texts
/// ("samples, crop"), or "" if none do.
std::string DifferingOptions(const std::string& a, const std::string& b);

}  // namespace affray::renderer
