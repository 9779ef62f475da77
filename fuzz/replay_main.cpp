// fuzz/replay_main.cpp: main() for a fuzz target built without libFuzzer (any compiler): runs
// LLVMFuzzerTestOneInput once on every file named, and on every file under every directory named
// (in name order), each in a buffer of exactly its size, so that a sanitizer build catches reads
// past the input's end as libFuzzer would. Programs run in every number type of the VM, where
// libFuzzer runs each in the one its input picks (fuzz_util.h). Prints one line per directory
// and a total; a crash is a crash (the sanitizer reports it), so the exit status is 0 when every
// input ran.
// Usage: REPLAY [--verbose] PATH...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "fuzz/fuzz_util.h"

namespace fs = std::filesystem;

namespace {

bool RunFile(const fs::path& path, bool verbose) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        std::fprintf(stderr, "replay: cannot read %s\n", path.c_str());
        return false;
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // A buffer of exactly the input's size, not a std::string (which ends with a NUL).
    std::unique_ptr<uint8_t[]> data(new uint8_t[std::max<size_t>(bytes.size(), 1)]);
    std::memcpy(data.get(), bytes.data(), bytes.size());
    const auto start = std::chrono::steady_clock::now();
    if (verbose) std::fprintf(stderr, "replay: %s\n", path.c_str());
    LLVMFuzzerTestOneInput(data.get(), bytes.size());
    if (verbose) {
        const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
        std::fprintf(stderr, "replay: %s took %.3f s\n", path.c_str(), took.count());
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    affray::fuzz::SetEveryNumberType(true);
    bool verbose = false, ok = true;
    int total = 0;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--verbose") == 0) {
            verbose = true;
            continue;
        }
        const fs::path arg(argv[i]);
        std::error_code ec;
        if (!fs::is_directory(arg, ec)) {
            ok = RunFile(arg, verbose) && ok;
            ++total;
            continue;
        }
        std::vector<fs::path> files;
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(arg, ec))
            if (e.is_regular_file()) files.push_back(e.path());
        std::sort(files.begin(), files.end());
        for (const fs::path& f : files) ok = RunFile(f, verbose) && ok;
        total += static_cast<int>(files.size());
        std::printf("replay: %zu inputs from %s\n", files.size(), arg.c_str());
    }
    std::printf("replay: %d inputs run\n", total);
    return ok ? 0 : 1;
}
