// renderer/checkpoint.cpp: the checkpoint file (format and rules in checkpoint.h).
#include "renderer/checkpoint.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

#include "image/atomic_file.h"
#include "vm/bytecode_file.h"

namespace affray::renderer {
namespace {

constexpr char kMagic[8] = {'A', 'F', 'R', 'A', 'Y', 'C', 'K', 'P'};
constexpr char kTileMagic[4] = {'T', 'I', 'L', 'E'};
constexpr uint32_t kVersion = 1;
constexpr uint32_t kMaxChannels = 64;

void PutU32(std::string& out, uint32_t x) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>(x >> (8 * i)));
}
void PutU64(std::string& out, uint64_t x) {
    for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>(x >> (8 * i)));
}
void PutStr(std::string& out, const std::string& s) {
    PutU32(out, static_cast<uint32_t>(s.size()));
    out += s;
}

/// Reads from a byte string; every Get fails (returns false) past the end.
class Reader {
  public:
    explicit Reader(std::string_view bytes) : m_bytes(bytes) {}
    size_t pos() const { return m_pos; }
    bool AtEnd() const { return m_pos == m_bytes.size(); }
    bool Get(size_t n, std::string_view* out) {
        if (m_bytes.size() - m_pos < n) return false;
        *out = m_bytes.substr(m_pos, n);
        m_pos += n;
        return true;
    }
    bool U32(uint32_t* x) {
        std::string_view b;
        if (!Get(4, &b)) return false;
        *x = 0;
        for (int i = 3; i >= 0; --i) *x = (*x << 8) | static_cast<unsigned char>(b[i]);
        return true;
    }
    bool I32(int* x) {
        uint32_t u;
        if (!U32(&u)) return false;
        *x = static_cast<int>(u);
        return true;
    }
    bool U64(uint64_t* x) {
        std::string_view b;
        if (!Get(8, &b)) return false;
        *x = 0;
        for (int i = 7; i >= 0; --i) *x = (*x << 8) | static_cast<unsigned char>(b[i]);
        return true;
    }
    bool Str(std::string* s) {
        uint32_t n;
        std::string_view b;
        if (!U32(&n) || !Get(n, &b)) return false;
        *s = std::string(b);
        return true;
    }

  private:
    std::string_view m_bytes;
    size_t m_pos = 0;
};

using TileKey = std::tuple<int, int, int, int>;
TileKey Key(const PixelRange& r) { return {r.y0, r.x0, r.y1, r.x1}; }

}  // namespace

std::string CheckpointPath(const std::string& outputPath) { return outputPath + ".checkpoint"; }

bool ReadCheckpoint(const std::string& path, CheckpointContents* out, std::string* error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        *error = std::generic_category().message(errno);
        return false;
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CheckpointContents c;
    Reader r(bytes);
    std::string_view magic;
    uint32_t version = 0;
    if (!r.Get(8, &magic) || magic != std::string_view(kMagic, 8)) {
        *error = "not an affray checkpoint";
        return false;
    }
    uint64_t check = 0;
    if (!r.U32(&version) || !r.Str(&c.identityHash) || !r.Str(&c.identity.scene) || !r.Str(&c.identity.options) ||
        !r.I32(&c.width) || !r.I32(&c.height) || !r.I32(&c.tileSize)) {
        *error = "damaged: its header is cut short";
        return false;
    }
    if (version != kVersion) {
        *error = "unsupported checkpoint version " + std::to_string(version);
        return false;
    }
    const size_t headerEnd = r.pos();
    if (!r.U64(&check) || check != vm::HashSource(std::string_view(bytes).substr(0, headerEnd)) || c.width <= 0 ||
        c.height <= 0 || c.tileSize <= 0) {
        *error = "damaged: bad header";
        return false;
    }
    c.validBytes = r.pos();
    for (int record = 1; !r.AtEnd(); ++record) {
        // A record cut short can only be the last: drop it, and the file ends before it.
        const size_t start = r.pos();
        PixelRange t;
        uint32_t channels = 0;
        if (!r.Get(4, &magic) || !r.I32(&t.x0) || !r.I32(&t.x1) || !r.I32(&t.y0) || !r.I32(&t.y1) ||
            !r.U32(&channels)) {
            c.droppedTail = true;
            break;
        }
        const auto damaged = [&](const std::string& what) {
            *error = "damaged: " + what + " in tile record " + std::to_string(record);
            return false;
        };
        if (magic != std::string_view(kTileMagic, 4)) return damaged("no record mark");
        if (t.empty() || t.x0 < 0 || t.y0 < 0 || t.x1 > c.width || t.y1 > c.height || t.width() > c.tileSize ||
            t.height() > c.tileSize)
            return damaged("a tile " + ToString(t) + " outside the tiling");
        if (channels < 4 || channels > kMaxChannels || (c.channels != 0 && int(channels) != c.channels))
            return damaged("a bad channel count");
        const size_t count = size_t(t.width()) * size_t(t.height()) * channels;
        std::string_view payload;
        if (!r.Get(count * 4, &payload) || !r.U64(&check)) {
            c.droppedTail = true;
            break;
        }
        if (check != vm::HashSource(std::string_view(bytes).substr(start, r.pos() - 8 - start)))
            return damaged("a bad checksum");
        std::vector<float> values(count);
        for (size_t i = 0; i < count; ++i) {
            uint32_t u = 0;
            for (int k = 3; k >= 0; --k) u = (u << 8) | static_cast<unsigned char>(payload[4 * i + size_t(k)]);
            std::memcpy(&values[i], &u, 4);
        }
        c.channels = int(channels);
        c.tiles[Key(t)] = std::move(values);
        c.validBytes = r.pos();
    }
    *out = std::move(c);
    return true;
}

std::unique_ptr<CheckpointFile> CheckpointFile::Create(const std::string& path, const RenderIdentity& identity,
                                                       int width, int height, int tileSize, std::string* error) {
    std::string header(kMagic, 8);
    PutU32(header, kVersion);
    PutStr(header, identity.Hash());
    PutStr(header, identity.scene);
    PutStr(header, identity.options);
    PutU32(header, static_cast<uint32_t>(width));
    PutU32(header, static_cast<uint32_t>(height));
    PutU32(header, static_cast<uint32_t>(tileSize));
    PutU64(header, vm::HashSource(header));
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0666);
    int err = fd < 0 ? errno : image::WriteAll(fd, header);
    if (err != 0) {
        if (fd >= 0) {
            ::close(fd);
            ::unlink(path.c_str());
        }
        *error = std::generic_category().message(err);
        return nullptr;
    }
    return std::unique_ptr<CheckpointFile>(new CheckpointFile(path, fd));
}

std::unique_ptr<CheckpointFile> CheckpointFile::Resume(const std::string& path, CheckpointContents contents,
                                                       std::string* error) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd < 0 || ::ftruncate(fd, static_cast<off_t>(contents.validBytes)) != 0) {
        *error = std::generic_category().message(errno);
        if (fd >= 0) ::close(fd);
        return nullptr;
    }
    std::unique_ptr<CheckpointFile> file(new CheckpointFile(path, fd));
    file->m_tiles = static_cast<int>(contents.tiles.size());
    file->m_channels = contents.channels;
    file->m_restore = std::move(contents.tiles);
    return file;
}

CheckpointFile::~CheckpointFile() {
    if (m_fd >= 0) ::close(m_fd);
}

bool CheckpointFile::Restore(const PixelRange& tile, image::ImageBuffer* image) {
    auto it = m_restore.find(Key(tile));
    const int channels = 4 + static_cast<int>(image->extraChannels.size());
    if (it == m_restore.end() || channels != m_channels) return false;
    const float* v = it->second.data();
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
            const size_t pixel = size_t(y) * size_t(image->width) + size_t(x);
            for (int c = 0; c < 4; ++c) image->rgba[pixel * 4 + size_t(c)] = *v++;
            for (auto& channel : image->extraChannels) channel.second[pixel] = *v++;
        }
    return true;
}

void CheckpointFile::Finished(const PixelRange& tile, const image::ImageBuffer& image) {
    // The record is built outside the lock; only the write is serialised.
    std::string record(kTileMagic, 4);
    for (int x : {tile.x0, tile.x1, tile.y0, tile.y1}) PutU32(record, static_cast<uint32_t>(x));
    PutU32(record, 4 + static_cast<uint32_t>(image.extraChannels.size()));
    record.reserve(record.size() + size_t(tile.width()) * size_t(tile.height()) * 4 * (4 + image.extraChannels.size()));
    auto put = [&](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        PutU32(record, u);
    };
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
            const size_t pixel = size_t(y) * size_t(image.width) + size_t(x);
            for (int c = 0; c < 4; ++c) put(image.rgba[pixel * 4 + size_t(c)]);
            for (const auto& channel : image.extraChannels) put(channel.second[pixel]);
        }
    PutU64(record, vm::HashSource(record));
    std::lock_guard<std::mutex> lock(m_mutex);
    if (!m_error.empty() || m_fd < 0) return;
    if (const int err = image::WriteAll(m_fd, record); err != 0) {
        m_error = std::generic_category().message(err);
        return;
    }
    ++m_tiles;
}

std::string CheckpointFile::error() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_error;
}

int CheckpointFile::tiles() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_tiles;
}

void CheckpointFile::Sync() {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_fd >= 0) ::fsync(m_fd);
}

void CheckpointFile::Remove() {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_fd >= 0) ::close(m_fd);
    m_fd = -1;
    ::unlink(m_path.c_str());
}

}  // namespace affray::renderer
