// rib/file.cpp: reading RIB files and archives, gzip-compressed or not (rib/file.h).
#include "rib/file.h"

#include <zlib.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include "diag/limits.h"

namespace affray::rib {
namespace {

std::string TooLarge(const char* what) {
    const int64_t limit = diag::LimitValue(diag::Limit::RibBytes);
    return std::string(what) + " more than " + std::to_string(limit) + " bytes " +
           diag::LimitNote(diag::Limit::RibBytes);
}

}  // namespace

bool GzipP(std::string_view bytes) {
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
           static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string Gunzip(std::string* bytes) {
    const auto limit = static_cast<uint64_t>(diag::LimitValue(diag::Limit::RibBytes));
    z_stream z{};
    if (inflateInit2(&z, 15 + 16) != Z_OK) return "cannot start decompressing it";
    std::string out;
    char buffer[1 << 16];
    size_t at = 0;  // input consumed
    std::string error;
    for (;;) {
        const size_t chunk = std::min<size_t>(bytes->size() - at, 1u << 30);
        z.next_in = reinterpret_cast<Bytef*>(bytes->data() + at);
        z.avail_in = static_cast<uInt>(chunk);
        z.next_out = reinterpret_cast<Bytef*>(buffer);
        z.avail_out = sizeof buffer;
        const int status = inflate(&z, Z_NO_FLUSH);
        at += chunk - z.avail_in;
        out.append(buffer, sizeof buffer - z.avail_out);
        if (out.size() > limit) {
            error = TooLarge("decompressed, it holds");
            break;
        }
        if (status == Z_STREAM_END) {
            // Concatenated members (gzip -c a b > c) follow one another.
            if (at == bytes->size()) break;
            if (inflateReset(&z) != Z_OK) {
                error = "cannot decompress it";
                break;
            }
            continue;
        }
        if (status == Z_BUF_ERROR && z.avail_in == 0 && at == bytes->size()) {
            error = "the gzip stream is cut short";
            break;
        }
        if (status != Z_OK && status != Z_BUF_ERROR) {
            error = std::string("the gzip stream is damaged (") + (z.msg ? z.msg : "zlib error") + ")";
            break;
        }
    }
    inflateEnd(&z);
    if (!error.empty()) return error;
    *bytes = std::move(out);
    return {};
}

std::string ReadRibFile(const std::string& path, std::string* text) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return "it is a directory";
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) return errno ? std::generic_category().message(errno) : "cannot open";
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size > diag::LimitValue(diag::Limit::RibBytes)) return TooLarge("it holds");
    in.seekg(0, std::ios::beg);
    text->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) return "read error";
    if (static_cast<int64_t>(text->size()) > diag::LimitValue(diag::Limit::RibBytes)) return TooLarge("it holds");
    return GzipP(*text) ? Gunzip(text) : std::string();
}

}  // namespace affray::rib
