// compiler/shader_cache.h: compiled shaders kept by the content of their source, so that a scene
// naming one shader for many primitives compiles it once per distinct parameter set, and an
// edited file is never served stale (the key is a hash of its bytes, not its name or date; the
// bytes are read again whenever stat gives the file another identity, size or modification time).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "compiler/compile.h"

namespace affray::compiler {

class ShaderCache {
  public:
    /// LoadShader(path, overrides, preprocess, spaces, facts), or the result of an earlier call
    /// whose file had the same bytes and whose overrides and options were the same, and whose
    /// spaces and facts agree with these on every name that compilation looked up
    /// (CompiledShader::reads): the one shared shader, not a copy. Failures are not kept.
    CompileResult Load(const std::string& path, const std::vector<ParamOverride>& overrides,
                       const lang::PreprocessOptions& preprocess, const Spaces* spaces = nullptr,
                       const SceneFacts* facts = nullptr);

    int hits() const { return m_hits; }
    int misses() const { return m_misses; }

  private:
    /// A file's identity, size and modification time, as stat gives them (size -1: no file).
    struct FileStamp {
        uint64_t device = 0, inode = 0;
        int64_t size = -1, mtimeNs = 0;
        bool operator==(const FileStamp&) const = default;
    };
    /// A file as read: its stamp, its bytes (empty if unreadable) and their vm::HashSource.
    struct FileBytes {
        FileStamp stamp;
        std::string bytes;
        uint64_t hash = 0;
    };
    /// The file at `path`, read (and hashed) again only when its stamp changed since the last call.
    const FileBytes& Bytes(const std::string& path);

    std::map<std::string, FileBytes> m_files;
    /// The shaders compiled from one file with one set of overrides and options (the key), by
    /// what they read of their scene: per set of names read, the values those names had.
    struct ByReads {
        SceneReads reads;
        std::map<std::string, std::shared_ptr<const CompiledShader>> byValues;
    };
    std::map<std::string, std::vector<ByReads>> m_compiled;
    int m_hits = 0, m_misses = 0;
};

}  // namespace affray::compiler
