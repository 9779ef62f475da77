// compiler/shader_cache.cpp: the key is everything the result depends on.
#include "compiler/shader_cache.h"

#include <sys/stat.h>

#include <algorithm>
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

/// The number's bits, as eight raw bytes.
void AppendBits(std::string* key, double x) {
    const uint64_t bits = std::bit_cast<uint64_t>(x);
    key->append(reinterpret_cast<const char*>(&bits), sizeof bits);
}

/// The numbers, counted, each as its bits: a key is built per primitive of a mesh, so no text.
void AppendNumbers(std::string* key, const double* x, size_t n) {
    *key += std::to_string(n) + ':';
    for (size_t i = 0; i < n; ++i) AppendBits(key, x[i]);
}

std::string Key(const std::string& path, uint64_t sourceHash, size_t sourceSize,
                const std::vector<ParamOverride>& overrides, const lang::PreprocessOptions& preprocess) {
    // The path is part of the key too: #include "x.h" resolves next to the including file.
    std::string key = path + '\n' + std::to_string(sourceHash) + '\n' + std::to_string(sourceSize);
    for (const std::string& d : preprocess.includeDirs) key += "\n-I" + d;
    for (const std::string& d : preprocess.defines) key += "\n-D" + d;
    for (const ParamOverride& o : overrides) {
        key += "\n" + o.name + "=";
        AppendNumbers(&key, o.numbers.data(), o.numbers.size());
        if (o.text) key += "\"" + *o.text + "\"";
    }
    return key;
}

/// The values `spaces` and `facts` give the names in `reads` (a missing one said so).
std::string ValuesKey(const SceneReads& reads, const Spaces* spaces, const SceneFacts* facts) {
    std::string key;
    for (const std::string& name : reads.spaces) {
        key += "\nspace " + name;
        if (!spaces || !spaces->count(name)) continue;
        const SpaceTransform& t = spaces->at(name);
        key += ":";
        AppendNumbers(&key, t.toCurrent.data(), t.toCurrent.size());
    }
    auto addFacts = [&](const char* kind, const std::set<std::string>& names,
                        const std::map<std::string, FactValue>* known) {
        for (const std::string& name : names) {
            key += std::string("\n") + kind + " " + name;
            const auto it = known ? known->find(name) : std::map<std::string, FactValue>::const_iterator();
            if (!known || it == known->end()) continue;
            key += "=";
            AppendNumbers(&key, it->second.numbers.data(), it->second.numbers.size());
            if (it->second.text) key += "\"" + *it->second.text + "\"";
        }
    };
    addFacts("option", reads.options, facts ? &facts->options : nullptr);
    addFacts("attribute", reads.attributes, facts ? &facts->attributes : nullptr);
    if (reads.textureSearchPath && facts)
        for (const std::string& d : facts->textureSearchPath) key += "\ntexture path " + d;
    if (reads.lights && facts)
        for (const std::string& c : facts->lightCategories) key += "\nlight " + c;
    return key;
}

}  // namespace

const ShaderCache::FileBytes& ShaderCache::Bytes(const std::string& path) {
    // A file is read again only when its identity, size or modification time (nanoseconds)
    // changed: a mesh's thousands of faces name one shader, and reading it per face was a third
    // of the cost of loading.
    struct stat st {};
    const bool known = ::stat(path.c_str(), &st) == 0;
    FileStamp stamp{known ? static_cast<uint64_t>(st.st_dev) : 0, known ? static_cast<uint64_t>(st.st_ino) : 0,
                    known ? static_cast<int64_t>(st.st_size) : -1,
                    known ? static_cast<int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec : 0};
    auto [it, added] = m_files.try_emplace(path);
    if (added || !known || !(it->second.stamp == stamp)) {
        std::string bytes = ReadAll(path);
        const uint64_t hash = vm::HashSource(bytes);
        it->second = {stamp, std::move(bytes), hash};
    }
    return it->second;
}

CompileResult ShaderCache::Load(const std::string& path, const std::vector<ParamOverride>& overrides,
                                const lang::PreprocessOptions& preprocess, const Spaces* spaces,
                                const SceneFacts* facts) {
    const FileBytes& file = Bytes(path);
    const bool readable = !file.bytes.empty();
    const std::string key = Key(path, file.hash, file.bytes.size(), overrides, preprocess);
    if (readable) {
        // A shader compiled before with the same file and overrides, whose scene gave every name
        // it read the value this one gives.
        for (const ByReads& group : m_compiled[key]) {
            auto it = group.byValues.find(ValuesKey(group.reads, spaces, facts));
            if (it == group.byValues.end()) continue;
            ++m_hits;
            CompileResult hit;
            hit.shader = it->second;
            hit.undeclared = hit.shader->undeclared;
            return hit;
        }
    }
    ++m_misses;
    CompileResult result = LoadShader(path, overrides, preprocess, spaces, facts);
    if (result.ok() && readable) {
        const SceneReads& reads = result.shader->reads;
        std::vector<ByReads>& groups = m_compiled[key];
        auto same = std::find_if(groups.begin(), groups.end(), [&](const ByReads& g) { return g.reads == reads; });
        if (same == groups.end()) same = groups.insert(groups.end(), ByReads{reads, {}});
        same->byValues.emplace(ValuesKey(reads, spaces, facts), result.shader);
    }
    return result;
}

}  // namespace affray::compiler
