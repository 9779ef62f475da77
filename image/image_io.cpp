// image/image_io.cpp: finding and loading the image-file module (image/image_io.h).
#include "image/image_io.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace affray::image::io {
namespace {

std::atomic<bool> g_loaded{false};

/// Where the module may be, in the order tried.
std::vector<std::string> Candidates() {
    std::vector<std::string> paths;
    if (const char* env = std::getenv("AFFRAY_IMAGE_IO"); env && *env) paths.emplace_back(env);
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) paths.push_back((exe.parent_path() / kModuleFile).string());
#ifdef AFFRAY_IMAGE_IO_PATH
    paths.emplace_back(AFFRAY_IMAGE_IO_PATH);
#endif
    return paths;
}

struct Module {
    const ImageIo* io = nullptr;
    std::string error;
};

Module Load() {
    Module result;
    std::string tried;
    auto refuse = [&](const std::string& path, const std::string& why) {
        tried += (tried.empty() ? "" : ", ") + path + " (" + why + ")";
    };
    for (const std::string& path : Candidates()) {
        std::error_code ec;
        if (!std::filesystem::exists(path, ec)) {
            refuse(path, "missing");
            continue;
        }
        // Never closed: OpenImageIO keeps threads and caches for the life of the process.
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = dlerror();
            refuse(path, why ? why : "cannot load");
            continue;
        }
        auto entry = reinterpret_cast<EntryPoint>(dlsym(handle, kEntryName));
        const ImageIo* io = entry ? entry(kAbi) : nullptr;
        if (!io) {
            refuse(path, "not a module of this affray");
            continue;
        }
        result.io = io;
        g_loaded = true;
        return result;
    }
    result.error = std::string("image files need ") + kModuleFile + ", which is not available (tried " +
                   (tried.empty() ? "nothing" : tried) + "; set AFFRAY_IMAGE_IO to its path)";
    return result;
}

}  // namespace

const ImageIo* Get(std::string* error) {
    static const Module loaded = Load();
    if (!loaded.io && error) *error = loaded.error;
    return loaded.io;
}

bool Loaded() { return g_loaded; }

}  // namespace affray::image::io
