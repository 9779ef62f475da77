// renderer/checkpoint.h: the checkpoint file that keeps a render's finished tiles while it runs,
// so that a render killed part way (a signal, a crash, a power cut of the machine's job) can be
// resumed: `affray render ... -o OUT.exr --resume` renders only the tiles the file lacks.
//
// The file is OUTPUT.checkpoint (CheckpointPath), beside the output. Format, little-endian, each
// integer written byte by byte; `str` is a u32 byte count and the bytes; floats are their IEEE-754
// binary32 bit patterns as u32, so a restored tile is the rendered one bit for bit:
//   header   8  magic "AFRAYCKP"
//            4  u32 version (1)
//            .  str identity: RenderIdentity::Hash() (renderer/render_identity.h)
//            .  str scene hash and str options text (RenderIdentity's parts, to say what differs)
//            12 i32 width, i32 height, i32 tile size (the tiling; a resume cuts the image alike)
//            8  u64 FNV-1a 64 of the header's bytes before it
//   records, one per finished tile, appended in the order tiles finish:
//            4  magic "TILE"
//            16 i32 x0, x1, y0, y1: the tile's pixels [x0, x1) x [y0, y1)
//            4  u32 channels per pixel C: R G B A, then the image's extra channels in order
//            .  (x1 - x0) * (y1 - y0) * C floats, pixel by pixel (rows top down), channel by channel
//            8  u64 FNV-1a 64 of the record's bytes before it
// Each record is one write() on a file opened for appending, so a killed process loses only the
// tiles still being rendered; a power cut may leave the last record cut short, which is dropped
// when the file is read. Any other damage (a bad checksum, a tile outside the image) refuses the
// file as a whole.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "renderer/render_identity.h"
#include "renderer/renderer.h"

namespace affray::renderer {

/// "OUT.exr" -> "OUT.exr.checkpoint".
std::string CheckpointPath(const std::string& outputPath);

/// What a checkpoint file holds.
struct CheckpointContents {
    RenderIdentity identity;
    std::string identityHash;
    int width = 0, height = 0, tileSize = 0;
    /// Each finished tile's floats (the record's layout), by (y0, x0, y1, x1).
    std::map<std::tuple<int, int, int, int>, std::vector<float>> tiles;
    int channels = 0;          ///< floats per pixel of the tiles (0 if there are none)
    size_t validBytes = 0;     ///< the file's length up to the end of its last whole record
    bool droppedTail = false;  ///< a last record cut short was dropped
};

/// Reads the checkpoint at `path`. Returns false with *error set to one phrase ("not an affray
/// checkpoint", "damaged: bad checksum in tile record 7", a system error) on failure.
bool ReadCheckpoint(const std::string& path, CheckpointContents* out, std::string* error);

/// The checkpoint a render writes while it runs: a TileStore that restores the tiles of the file
/// it resumes and appends each finished tile.
class CheckpointFile : public TileStore {
  public:
    /// Starts a new checkpoint at `path` (replacing any file there) for the render `identity` of
    /// a width x height image cut into tiles of `tileSize`. Null with *error set on failure.
    static std::unique_ptr<CheckpointFile> Create(const std::string& path, const RenderIdentity& identity, int width,
                                                  int height, int tileSize, std::string* error);
    /// Continues the checkpoint at `path` whose contents `contents` are (ReadCheckpoint, identity
    /// checked by the caller): its tiles are restored, a record cut short is cut off the file, and
    /// new tiles are appended. Null with *error set on failure.
    static std::unique_ptr<CheckpointFile> Resume(const std::string& path, CheckpointContents contents,
                                                  std::string* error);
    ~CheckpointFile() override;

    bool Restore(const PixelRange& tile, image::ImageBuffer* image) override;
    void Finished(const PixelRange& tile, const image::ImageBuffer& image) override;

    /// The first error writing a tile ("" if none); tiles are no longer written after one.
    std::string error() const;
    /// Tiles the file holds (restored and appended).
    int tiles() const;
    /// Flushes the file to disk (fsync): before the process exits after an interruption.
    void Sync();
    /// Deletes the file: the image it was for has been written, or the file is useless.
    void Remove();

  private:
    CheckpointFile(std::string path, int fd) : m_path(std::move(path)), m_fd(fd) {}
    std::string m_path;
    int m_fd = -1;
    mutable std::mutex m_mutex;
    std::string m_error;
    int m_tiles = 0;
    std::map<std::tuple<int, int, int, int>, std::vector<float>> m_restore;
    int m_channels = 0;
};

}  // namespace affray::renderer
