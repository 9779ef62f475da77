// image/atomic_file.cpp: atomic file output (rules in atomic_file.h).
#include "image/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <system_error>

namespace affray::image {
namespace {

std::atomic<int64_t> g_faultAt{-1};  // byte number of the injected failure, or -1
std::atomic<int> g_faultError{0};
std::atomic<int64_t> g_written{0};  // bytes written since the fault was injected

std::string Message(int error) { return std::generic_category().message(error); }

/// Why `path` cannot be a target, before any file is made: "" if it may be.
std::string CheckTarget(const std::string& path) {
    if (path.empty()) return "empty file name";
    std::filesystem::path directory = std::filesystem::path(path).parent_path();
    if (directory.empty()) directory = ".";
    std::error_code ec;
    if (!std::filesystem::is_directory(directory, ec)) return "directory '" + directory.string() + "' does not exist";
    if (std::filesystem::is_directory(path, ec)) return "'" + path + "' is a directory";
    return "";
}

/// Creates the temporary file beside `path`; -1 with *error set on failure.
int CreateTemporary(const std::string& path, std::string* temporary, int* error) {
    *temporary = TemporaryPath(path);
    const int fd = ::open(temporary->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    *error = fd < 0 ? errno : 0;
    return fd;
}

}  // namespace

std::string TemporaryPath(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

void InjectWriteFaultForTesting(int64_t failAtByte, int error) {
    g_written = 0;
    g_faultError = error;
    g_faultAt = failAtByte;
}

int WriteAll(int fd, std::string_view bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
        size_t chunk = bytes.size() - done;
        // The injected fault: write up to the failing byte, then fail as the disk would.
        const int64_t faultAt = g_faultAt.load();
        if (faultAt >= 0) {
            const int64_t before = g_written.fetch_add(static_cast<int64_t>(chunk));
            if (before + static_cast<int64_t>(chunk) > faultAt) {
                chunk = before >= faultAt ? 0 : static_cast<size_t>(faultAt - before);
                if (chunk == 0) return g_faultError.load();
            }
        }
        const ssize_t n = ::write(fd, bytes.data() + done, chunk);
        if (n < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        if (n == 0) return EIO;
        done += static_cast<size_t>(n);
    }
    return 0;
}

bool WriteFileAtomically(const std::string& path, std::string_view bytes, std::string* reason) {
    auto fail = [&](const std::string& why) {
        if (reason) *reason = why;
        return false;
    };
    if (std::string why = CheckTarget(path); !why.empty()) return fail(why);
    std::string temporary;
    int error = 0;
    const int fd = CreateTemporary(path, &temporary, &error);
    if (fd < 0) return fail(Message(error));
    // Every step's error counts: a full disk may show only at fsync() or close() (NFS).
    error = WriteAll(fd, bytes);
    if (error == 0 && ::fsync(fd) != 0 && errno != EINVAL) error = errno;
    if (::close(fd) != 0 && error == 0 && errno != EINTR) error = errno;
    if (error == 0 && std::rename(temporary.c_str(), path.c_str()) != 0) error = errno;
    if (error != 0) {
        ::unlink(temporary.c_str());
        return fail(error == EISDIR ? "'" + path + "' is a directory" : Message(error));
    }
    return true;
}

bool CheckWritable(const std::string& path, std::string* reason) {
    if (std::string why = CheckTarget(path); !why.empty()) {
        if (reason) *reason = why;
        return false;
    }
    std::string temporary;
    int error = 0;
    const int fd = CreateTemporary(path, &temporary, &error);
    if (fd < 0) {
        if (reason) *reason = Message(error);
        return false;
    }
    ::close(fd);
    ::unlink(temporary.c_str());
    return true;
}

}  // namespace affray::image
