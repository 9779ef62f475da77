// compiler/shader_cache.cpp: the key is everything the result depends on.
#include "compiler/shader_cache.h"

#include <sys/stat.h>

#include <bit>
#include <fstream>
#include <sstream>

#include "vm/bytecode_file.h"

namespace affray::compiler {

namespace {

/// The file's bytes (empty if unreadable: then the compiler reports the error itself).
std::string ReadAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return in ? text.str() : std::string();
}

std::string Key(const std::string& path, const std::string& bytes, const std::vector<ParamOverride>& overrides,
                const lang::PreprocessOptions& preprocess, const Spaces* spaces, const SceneFacts* facts) {
    // The path is part of the key too: #include "x.h" resolves next to the including file.
    std::string key = path + '\n' + std::to_string(vm::HashSource(bytes)) + '\n' + std::to_string(bytes.size());
    for (const std::string& d : preprocess.includeDirs) key += "\n-I" + d;
    for (const std::string& d : preprocess.defines) key += "\n-D" + d;
    for (const ParamOverride& o : overrides) {
        key += "\n" + o.name + "=";
        for (double x : o.numbers) key += std::to_string(std::bit_cast<uint64_t>(x)) + ",";
        if (o.text) key += "\"" + *o.text + "\"";
    }
    for (const auto& [name, t] : spaces ? *spaces : Spaces{}) {
        key += "\nspace " + name + ":";
        for (double x : t.toCurrent) key += std::to_string(std::bit_cast<uint64_t>(x)) + ",";
    }
    auto addFacts = [&](const char* kind, const std::map<std::string, FactValue>& named) {
        for (const auto& [name, value] : named) {
            key += std::string("\n") + kind + " " + name + "=";
            for (double x : value.numbers) key += std::to_string(std::bit_cast<uint64_t>(x)) + ",";
            if (value.text) key += "\"" + *value.text + "\"";
        }
    };
    if (facts) {
        addFacts("option", facts->options);
        addFacts("attribute", facts->attributes);
        for (const std::string& d : facts->textureSearchPath) key += "\ntexture path " + d;
    }
    return key;
}

}  // namespace

const std::string& ShaderCache::Bytes(const std::string& path) {
    // A file is read again only when its identity, size or modification time (nanoseconds)
    // changed: a mesh's thousands of faces name one shader, and reading it per face was a third
    // of the cost of loading.
    struct stat st {};
    const bool known = ::stat(path.c_str(), &st) == 0;
    FileStamp stamp{known ? static_cast<uint64_t>(st.st_dev) : 0, known ? static_cast<uint64_t>(st.st_ino) : 0,
                    known ? static_cast<int64_t>(st.st_size) : -1,
                    known ? static_cast<int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec : 0};
    auto [it, added] = m_files.try_emplace(path);
    if (added || !known || !(it->second.first == stamp)) it->second = {stamp, ReadAll(path)};
    return it->second.second;
}

CompileResult ShaderCache::Load(const std::string& path, const std::vector<ParamOverride>& overrides,
                                const lang::PreprocessOptions& preprocess, const Spaces* spaces,
                                const SceneFacts* facts) {
    const std::string& bytes = Bytes(path);
    const std::string key = Key(path, bytes, overrides, preprocess, spaces, facts);
    if (!bytes.empty()) {
        auto it = m_compiled.find(key);
        if (it != m_compiled.end()) {
            ++m_hits;
            CompileResult hit;
            hit.shader = it->second;
            hit.undeclared = hit.shader->undeclared;
            return hit;
        }
    }
    ++m_misses;
    CompileResult result = LoadShader(path, overrides, preprocess, spaces, facts);
    if (result.ok() && !bytes.empty()) m_compiled.emplace(key, result.shader);
    return result;
}

}  // namespace affray::compiler
