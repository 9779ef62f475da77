// image/atomic_file.h: the one way affray puts a finished file on disk.
// Every image affray writes (the OpenEXR output with its AOVs, the PNG preview) goes
// through WriteFileAtomically: the bytes go to a new temporary file in the target's directory,
// are written with every error checked (a full disk is a short or failed write(), or a failed
// fsync() or close()), and only then is the file renamed onto the target. On any failure the
// temporary file is removed, so a reader sees either the old file, or nothing, or the whole new
// one; never a part.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace affray::image {

/// Writes `bytes` to `path` atomically (see the file comment). Returns false with *reason (may
/// be null) set to one phrase, without the path ("No space left on device", "'out' is a
/// directory", "directory 'missing' does not exist"), and nothing left behind, on failure.
bool WriteFileAtomically(const std::string& path, std::string_view bytes, std::string* reason);

/// Checks, before a long render, that WriteFileAtomically(path, ...) could create its file: the
/// directory exists and takes a new file, and `path` is not a directory. Creates and removes a
/// temporary file. Returns false with *reason (may be null) set as WriteFileAtomically does.
bool CheckWritable(const std::string& path, std::string* reason);

/// The temporary name WriteFileAtomically uses beside `path`: "PATH.tmp.PID.N", unique within
/// this process and across processes. Tests look for leftovers by its ".tmp." part.
std::string TemporaryPath(const std::string& path);

/// A fault for tests: the write of byte number `failAtByte` (counted over all the bytes
/// WriteAll writes (WriteFileAtomically and the checkpoint use it) after this call) fails with errno `error`, as a full
/// disk would (ENOSPC). Negative: no fault (the default). Process-wide; never used by affray itself.
void InjectWriteFaultForTesting(int64_t failAtByte, int error);

/// write() all of `bytes` to the open descriptor `fd`, retrying after EINTR and short writes.
/// Returns 0, or the errno of the failure. Counts against InjectWriteFaultForTesting.
int WriteAll(int fd, std::string_view bytes);

}  // namespace affray::image
