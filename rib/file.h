// rib/file.h: the bytes of a RIB file or archive, as the reader parses them: read whole, and
// decompressed when gzip-compressed (exporters write .rib.gz archives), both within the
// rib-bytes limit (diag/limits.h).
#pragma once

#include <string>
#include <string_view>

namespace affray::rib {

/// Whether `bytes` start as a gzip stream does (0x1f 0x8b).
bool GzipP(std::string_view bytes);

/// Replaces gzip-compressed `*bytes` by their decompressed text (every member of the stream, as
/// gunzip does). Stops with an error past the rib-bytes limit, and on a damaged or cut stream;
/// returns "" or the reason.
std::string Gunzip(std::string* bytes);

/// The whole of file `path` into *text, decompressed if it is gzip-compressed. A file larger than
/// the rib-bytes limit is refused before it is read. Returns "" or the reason.
std::string ReadRibFile(const std::string& path, std::string* text);

}  // namespace affray::rib
