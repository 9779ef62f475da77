// texture/texture_file.cpp: maps read from files through OpenImageIO: the header and the streaming
// pyramid build when a file is opened, level-0 texels in tiles read on demand, the process-wide
// tile budget with least-recently-used eviction, the per-thread tile cache that keeps most texel
// reads free of locks, and the process-wide cache of maps keyed by path and modification time.
#include <algorithm>
#include <array>
#include <filesystem>
#include <list>
#include <map>
#include <mutex>
#include <system_error>
#include <utility>

#include "image/image_io.h"
#include "texture/texture_impl.h"

namespace affray::texture {

using namespace detail;

namespace detail {

class FileSource;

namespace {

/// A resident tile's place in the process-wide least-recently-used list.
struct LruEntry {
    FileSource* source;
    int index;
    size_t bytes;
};

/// One tile's slot: the tile is guarded by the slot's stripe mutex, the list position by the
/// cache mutex (taken first when both are needed, never the other way round).
struct Slot {
    std::shared_ptr<const Tile> tile;
    std::list<LruEntry>::iterator position;
    bool listed = false;
};

}  // namespace

/// The open image of a file map and its tile slots.
class FileSource {
  public:
    std::mutex inputMutex;  // one read at a time through the reader
    std::unique_ptr<image::io::ImageReader> input;
    MapImpl* map = nullptr;
    int fileTileWidth = 0, fileTileHeight = 0;  // 0: a scanline file
    std::unique_ptr<Slot[]> slots;
    int slotCount = 0;
    int64_t readFailures = 0;  // guarded by inputMutex

    ~FileSource();
    /// Reads rows [y0, y1) and columns [x0, x1) of level 0, all channels as float, into `out`
    /// (row stride (x1 - x0) * channels). False on a read error.
    bool readRegion(int x0, int x1, int y0, int y1, float* out);
    /// Reads the tile `index` and, for a scanline file, which delivers whole rows, the other
    /// tiles of its row; returns (index, tile) pairs.
    std::vector<std::pair<int, std::shared_ptr<Tile>>> readTiles(int index);
};

namespace {

/// The process-wide store of resident tiles. Immortal (never destroyed), so that maps released
/// during static destruction still find it.
class TileCache {
  public:
    static TileCache& Get() {
        static TileCache* cache = new TileCache;
        return *cache;
    }
    std::mutex& stripe(const FileSource* source, int index) {
        const size_t h = reinterpret_cast<uintptr_t>(source) / 64 + static_cast<size_t>(index) * 0x9e3779b1u;
        return m_stripes[h % m_stripes.size()];
    }
    /// Marks a tile just used (if it is still listed).
    void touch(FileSource* source, int index) {
        std::lock_guard<std::mutex> lock(m_mutex);
        Slot& slot = source->slots[index];
        if (slot.listed) m_lru.splice(m_lru.begin(), m_lru, slot.position);
    }
    /// Lists tiles just installed in their slots (the last one most recent), then drops the least
    /// recently used tiles beyond the budget, keeping the most recent.
    void insert(FileSource* source, const std::vector<std::pair<int, size_t>>& tiles) {
        std::lock_guard<std::mutex> lock(m_mutex);
        for (const auto& [index, bytes] : tiles) {
            Slot& slot = source->slots[index];
            m_lru.push_front({source, index, bytes});
            slot.position = m_lru.begin();
            slot.listed = true;
            m_bytes += bytes;
            source->map->m_tileBytes.fetch_add(bytes, std::memory_order_relaxed);
        }
        m_tilesRead.fetch_add(static_cast<int64_t>(tiles.size()), std::memory_order_relaxed);
        evictLocked(1);
    }
    /// Forgets every tile of a source being destroyed.
    void forget(FileSource* source, int count) {
        std::lock_guard<std::mutex> lock(m_mutex);
        for (int i = 0; i < count; ++i) {
            Slot& slot = source->slots[i];
            if (!slot.listed) continue;
            m_bytes -= slot.position->bytes;
            m_lru.erase(slot.position);
            slot.listed = false;
        }
    }
    void setBudget(size_t bytes) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_budget.store(bytes, std::memory_order_relaxed);
        evictLocked(0);
    }
    size_t budget() const { return m_budget.load(std::memory_order_relaxed); }
    CacheStats stats() {
        std::lock_guard<std::mutex> lock(m_mutex);
        return {m_tilesRead.load(), m_tilesDropped.load(), m_bytes};
    }

  private:
    void evictLocked(size_t keep) {
        const size_t budget = m_budget.load(std::memory_order_relaxed);
        while (m_bytes > budget && m_lru.size() > keep) {
            const LruEntry e = m_lru.back();
            m_lru.pop_back();
            m_bytes -= e.bytes;
            e.source->map->m_tileBytes.fetch_sub(e.bytes, std::memory_order_relaxed);
            std::shared_ptr<const Tile> dropped;  // released outside the stripe lock
            {
                std::lock_guard<std::mutex> slotLock(stripe(e.source, e.index));
                Slot& slot = e.source->slots[e.index];
                dropped = std::move(slot.tile);
                slot.listed = false;
            }
            m_tilesDropped.fetch_add(1, std::memory_order_relaxed);
        }
    }

    std::mutex m_mutex;
    std::list<LruEntry> m_lru;
    size_t m_bytes = 0;
    std::atomic<size_t> m_budget{size_t{512} << 20};
    std::atomic<int64_t> m_tilesRead{0}, m_tilesDropped{0};
    std::array<std::mutex, 64> m_stripes;
};

/// The calling thread's most recent tiles, tried before any lock is taken. Keyed by the map's
/// id, never reused, so a destroyed map's tiles cannot be mistaken for a new one's.
struct ThreadTiles {
    static constexpr int kSize = 4;
    struct Entry {
        uint64_t map = 0;
        int index = -1;
        std::shared_ptr<const Tile> tile;
    };
    std::array<Entry, kSize> entries;
    int next = 0;
};
thread_local ThreadTiles t_tiles;

}  // namespace

FileSource::~FileSource() {
    if (slotCount) TileCache::Get().forget(this, slotCount);
}

bool FileSource::readRegion(int x0, int x1, int y0, int y1, float* out) {
    const int channels = map->channels();
    if (fileTileWidth == 0) {
        // Scanlines come whole; keep the columns asked for.
        const size_t row = static_cast<size_t>(map->width()) * channels;
        std::vector<float> band;
        float* dst = out;
        if (x0 != 0 || x1 != map->width()) {
            band.resize(row * (y1 - y0));
            dst = band.data();
        }
        if (!input->readScanlines(y0, y1, dst)) return false;
        if (dst != out) {
            const size_t width = static_cast<size_t>(x1 - x0) * channels;
            for (int y = 0; y < y1 - y0; ++y)
                std::copy_n(band.data() + y * row + static_cast<size_t>(x0) * channels, width, out + y * width);
        }
        return true;
    }
    // Tiles are read whole: widen the region to the file's tiles.
    const int ax0 = x0 / fileTileWidth * fileTileWidth, ay0 = y0 / fileTileHeight * fileTileHeight;
    const int ax1 = std::min((x1 + fileTileWidth - 1) / fileTileWidth * fileTileWidth, map->width());
    const int ay1 = std::min((y1 + fileTileHeight - 1) / fileTileHeight * fileTileHeight, map->height());
    const bool aligned = ax0 == x0 && ax1 == x1 && ay0 == y0 && ay1 == y1;
    std::vector<float> region;
    if (!aligned) region.resize(static_cast<size_t>(ax1 - ax0) * (ay1 - ay0) * channels);
    float* dst = aligned ? out : region.data();
    if (!input->readTiles(ax0, ax1, ay0, ay1, dst)) return false;
    if (!aligned) {
        const size_t row = static_cast<size_t>(ax1 - ax0) * channels, width = static_cast<size_t>(x1 - x0) * channels;
        for (int y = y0; y < y1; ++y)
            std::copy_n(region.data() + (y - ay0) * row + static_cast<size_t>(x0 - ax0) * channels, width,
                        out + (y - y0) * width);
    }
    return true;
}

std::vector<std::pair<int, std::shared_ptr<Tile>>> FileSource::readTiles(int index) {
    const int tilesX = map->tilesX(), channels = map->channels();
    const int ty = index / tilesX, tx = index % tilesX;
    const int y0 = ty * kTileSize, y1 = std::min(y0 + kTileSize, map->height());
    // A scanline file reads whole rows anyway: every tile of the row comes at the cost of one.
    const int first = fileTileWidth == 0 ? 0 : tx, last = fileTileWidth == 0 ? tilesX - 1 : tx;
    const int x0 = first * kTileSize, x1 = std::min((last + 1) * kTileSize, map->width());
    std::vector<float> texels(static_cast<size_t>(x1 - x0) * (y1 - y0) * channels);
    bool ok;
    {
        std::lock_guard<std::mutex> lock(inputMutex);
        ok = readRegion(x0, x1, y0, y1, texels.data());
        if (!ok) {
            // A file changed or damaged since it was opened: its texels read as 0 (the map's
            // pyramid, from the first reading, still bounds them).
            input->error();  // clears the reader's message
            ++readFailures;
        }
    }
    if (!ok) std::fill(texels.begin(), texels.end(), 0.0f);
    ZeroNonFinite(texels.data(), texels.size());
    // Each texel into its block's range in the pyramid: a no-op for the file the pyramid was built
    // from, and what keeps lookups inside the bounds if the file changed under the open map.
    const PyramidLevel& blocks = map->m_levels[0];
    const size_t plane = static_cast<size_t>(blocks.width) * blocks.height * 2;
    for (int y = y0; y < y1; ++y) {
        float* row = texels.data() + static_cast<size_t>(y - y0) * (x1 - x0) * channels;
        const float* blockRow = blocks.minMax.data() + static_cast<size_t>(y >> kBlockBits) * blocks.width * 2;
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < channels; ++c) {
                const float* b = blockRow + c * plane + static_cast<size_t>(x >> kBlockBits) * 2;
                float& v = row[static_cast<size_t>(x - x0) * channels + c];
                v = std::clamp(v, b[0], b[1]);
            }
    }
    std::vector<std::pair<int, std::shared_ptr<Tile>>> tiles;
    const size_t row = static_cast<size_t>(x1 - x0) * channels;
    for (int t = first; t <= last; ++t) {
        auto tile = std::make_shared<Tile>();
        tile->width = std::min(kTileSize, map->width() - t * kTileSize);
        tile->height = y1 - y0;
        tile->texels.resize(static_cast<size_t>(tile->width) * tile->height * channels);
        const size_t width = static_cast<size_t>(tile->width) * channels;
        for (int y = 0; y < tile->height; ++y)
            std::copy_n(texels.data() + y * row + static_cast<size_t>(t * kTileSize - x0) * channels, width,
                        tile->texels.data() + y * width);
        tiles.emplace_back(ty * tilesX + t, std::move(tile));
    }
    return tiles;
}

}  // namespace detail

namespace {
std::atomic<uint64_t> g_nextMapId{1};
}  // namespace

// Here rather than beside the rest of the map: the source is complete only in this file.
MapImpl::MapImpl(int width, int height, int channels, std::string name, Wrap swrap, Wrap twrap)
    : m_id(g_nextMapId.fetch_add(1, std::memory_order_relaxed)),
      m_tilesX((width + kTileSize - 1) >> kTileBits),
      m_tilesY((height + kTileSize - 1) >> kTileBits) {
    m_width = width;
    m_height = height;
    m_channels = channels;
    m_name = std::move(name);
    m_swrap = swrap;
    m_twrap = twrap;
}

// The source goes first, while the rest of the map it refers to is still whole.
MapImpl::~MapImpl() { m_source.reset(); }

const Tile* MapImpl::threadTile(int index) const {
    ThreadTiles& cache = t_tiles;
    for (const ThreadTiles::Entry& e : cache.entries)
        if (e.index == index && e.map == m_id) return e.tile.get();

    // Not in the thread's cache: the tile's slot, else the file.
    FileSource* source = m_source.get();
    TileCache& tiles = TileCache::Get();
    std::shared_ptr<const Tile> tile;
    {
        std::lock_guard<std::mutex> lock(tiles.stripe(source, index));
        tile = source->slots[index].tile;
    }
    if (tile) {
        tiles.touch(source, index);
    } else {
        std::vector<std::pair<int, size_t>> installed;
        auto fresh = source->readTiles(index);
        // The requested tile last, so that it is the most recent in the list.
        std::stable_partition(fresh.begin(), fresh.end(), [&](const auto& p) { return p.first != index; });
        for (auto& [i, t] : fresh) {
            std::lock_guard<std::mutex> lock(tiles.stripe(source, i));
            Slot& slot = source->slots[i];
            if (!slot.tile) {
                // Another thread may have read the same tile meanwhile: the first one stays.
                slot.tile = std::move(t);
                installed.emplace_back(i, slot.tile->texels.size() * sizeof(float) + sizeof(Tile));
            }
            if (i == index) tile = slot.tile;
        }
        if (!installed.empty()) tiles.insert(source, installed);
    }
    ThreadTiles::Entry& e = cache.entries[cache.next];
    cache.next = (cache.next + 1) % ThreadTiles::kSize;
    e.map = m_id;
    e.index = index;
    e.tile = std::move(tile);
    return e.tile.get();
}

namespace {

/// The largest side, and the largest number of tiles, of a map (2^30).
constexpr int64_t kMaxSide = int64_t{1} << 30;
/// The largest side of a file's own tiles (2^20): the bands read are a few of them high.
constexpr int kMaxFileTile = 1 << 20;

/// Reads a file's header and builds its pyramid, streaming the image in bands of rows.
std::shared_ptr<const TextureMap> ReadMap(const std::string& path, std::string* error) {
    auto fail = [&](const std::string& message) -> std::shared_ptr<const TextureMap> {
        if (error) *error = "cannot read texture '" + path + "': " + message;
        return nullptr;
    };
    std::string why;
    const image::io::ImageIo* images = image::io::Get(&why);
    if (!images) return fail(why);
    std::unique_ptr<image::io::ImageReader> input = images->Open(path, &why);
    if (!input) return fail(why);
    const image::io::ImageHeader spec = input->header();
    if (spec.width <= 0 || spec.height <= 0 || spec.channels <= 0) return fail("the image has no pixels");
    // Sides and tile counts are ints (the tile index too): refuse what would overflow them,
    // counted in 64 bits, before anything is sized from the header.
    const int64_t tileCount =
        ((int64_t{spec.width} + kTileSize - 1) >> kTileBits) * ((int64_t{spec.height} + kTileSize - 1) >> kTileBits);
    if (spec.width > kMaxSide || spec.height > kMaxSide || tileCount > kMaxSide)
        return fail("the image is too large (" + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                    " texels; sides and tile counts are limited to 2^30)");
    if (spec.tileWidth < 0 || spec.tileHeight < 0 || spec.tileWidth > kMaxFileTile || spec.tileHeight > kMaxFileTile)
        return fail("the file's tiles are too large (" + std::to_string(spec.tileWidth) + " x " +
                    std::to_string(spec.tileHeight) + " texels; at most 2^20 a side)");

    Wrap swrap = Wrap::Periodic, twrap = Wrap::Periodic;
    const std::string& modes = spec.wrapmodes;
    if (!modes.empty()) {
        const size_t comma = modes.find(',');
        const std::string s = modes.substr(0, comma), t = comma == std::string::npos ? s : modes.substr(comma + 1);
        if (!ParseWrap(s, &swrap)) swrap = Wrap::Periodic;
        if (!ParseWrap(t, &twrap)) twrap = Wrap::Periodic;
    }

    auto map = std::make_shared<MapImpl>(spec.width, spec.height, spec.channels, path, swrap, twrap);
    auto source = std::make_unique<FileSource>();
    source->map = map.get();
    source->fileTileWidth = spec.tileWidth;
    source->fileTileHeight = spec.tileHeight;
    source->input = std::move(input);

    // Bands: whole rows of file tiles, a multiple of the pyramid's blocks, about 64 rows high.
    int band = source->fileTileHeight ? source->fileTileHeight : kTileSize;
    if (source->fileTileHeight)
        while (band % kBlockSize != 0 || band < kTileSize) band += source->fileTileHeight;
    PyramidBuilder builder(spec.width, spec.height, spec.channels);
    std::vector<float> texels;
    int64_t nonFinite = 0;
    for (int y0 = 0; y0 < spec.height; y0 += band) {
        const int y1 = std::min(y0 + band, spec.height);
        texels.resize(static_cast<size_t>(spec.width) * (y1 - y0) * spec.channels);
        if (!source->readRegion(0, spec.width, y0, y1, texels.data())) return fail(source->input->error());
        nonFinite += ZeroNonFinite(texels.data(), texels.size());
        builder.AddRows(y0, y1 - y0, texels.data());
    }
    map->m_levels = builder.Finish();
    map->setNonFinite(nonFinite);
    source->slotCount = map->tilesX() * map->tilesY();
    source->slots = std::make_unique<Slot[]>(static_cast<size_t>(source->slotCount));
    map->m_source = std::move(source);
    return map;
}

/// One file's place in the map cache; its mutex makes threads opening the same file wait for
/// one reading.
struct CachedFile {
    std::mutex mutex;
    std::filesystem::file_time_type mtime;
    std::shared_ptr<const TextureMap> map;
};

struct MapCache {
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<CachedFile>> files;
    static MapCache& Get() {
        static MapCache* cache = new MapCache;  // immortal, like the tile cache
        return *cache;
    }
};

}  // namespace

std::shared_ptr<const TextureMap> Open(const std::string& path, std::string* error) {
    std::error_code ec;
    const auto mtime = std::filesystem::last_write_time(path, ec);
    if (ec) {
        // Let the reader say why (OIIO names a missing file as such); the map is not cached.
        return ReadMap(path, error);
    }
    MapCache& cache = MapCache::Get();
    std::shared_ptr<CachedFile> file;
    {
        std::lock_guard<std::mutex> lock(cache.mutex);
        auto& slot = cache.files[path];
        if (!slot) slot = std::make_shared<CachedFile>();
        file = slot;
    }
    std::lock_guard<std::mutex> lock(file->mutex);
    if (file->map && file->mtime == mtime) return file->map;
    std::shared_ptr<const TextureMap> map = ReadMap(path, error);
    if (map) {
        file->map = map;
        file->mtime = mtime;
    }
    return map;
}

void SetTileMemoryBudget(size_t bytes) { TileCache::Get().setBudget(bytes); }
size_t TileMemoryBudget() { return TileCache::Get().budget(); }
CacheStats Stats() { return TileCache::Get().stats(); }

}  // namespace affray::texture
