// vm/bytecode_file.cpp: writes and reads .afb files (the layout is documented in
// vm/bytecode_file.h). The reader trusts nothing: every count is checked against the bytes left
// (and against the VM's limits) before anything is allocated, and every program is verified.
// To add a field: write it in WriteProgram/SaveBytecode, read it at the same place in
// ReadProgram/LoadBytecode, document it in the header's table and bump kBytecodeVersion.
#include "vm/bytecode_file.h"

#include "diag/limits.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <system_error>

#include "vm/verify.h"

namespace affray::vm {

namespace {

constexpr char kMagic[8] = {'A', 'F', 'R', 'A', 'Y', 'B', 'C', '\0'};
constexpr size_t kHeaderSize = 28;  // magic, version, length, header check
constexpr size_t kChecksumSize = 8;

bool Fail(std::string* error, const std::string& message) {
    if (error) *error = message;
    return false;
}

std::string ErrnoText(int err) { return std::error_code(err, std::generic_category()).message(); }

uint64_t GetU64At(std::string_view bytes, size_t offset) {
    uint64_t x = 0;
    for (int i = 7; i >= 0; --i) x = (x << 8) | static_cast<uint8_t>(bytes[offset + i]);
    return x;
}

void PutU64At(std::string* bytes, size_t offset, uint64_t x) {
    for (int i = 0; i < 8; ++i) (*bytes)[offset + i] = static_cast<char>((x >> (8 * i)) & 0xff);
}

/// Appends little-endian fields to a byte string.
class Writer {
  public:
    void U8(uint8_t x) { m_bytes.push_back(static_cast<char>(x)); }
    void U16(uint16_t x) { Le(x, 2); }
    void U32(uint32_t x) { Le(x, 4); }
    void U64(uint64_t x) { Le(x, 8); }
    void I32(int32_t x) { U32(static_cast<uint32_t>(x)); }
    void F64(double x) { U64(std::bit_cast<uint64_t>(x)); }
    void Count(size_t n) { U32(static_cast<uint32_t>(n)); }
    void Str(const std::string& s) {
        Count(s.size());
        m_bytes += s;
    }
    void Raw(const char* data, size_t n) { m_bytes.append(data, n); }
    std::string& bytes() { return m_bytes; }

  private:
    void Le(uint64_t x, int n) {
        for (int i = 0; i < n; ++i) U8(static_cast<uint8_t>(x >> (8 * i)));
    }
    std::string m_bytes;
};

/// Reads little-endian fields; past the end it reads zeros and remembers that it failed.
class Reader {
  public:
    explicit Reader(std::string_view bytes) : m_bytes(bytes) {}
    bool failed() const { return m_failed; }
    size_t remaining() const { return m_bytes.size() - m_pos; }

    uint8_t U8() { return static_cast<uint8_t>(Le(1)); }
    uint16_t U16() { return static_cast<uint16_t>(Le(2)); }
    uint32_t U32() { return static_cast<uint32_t>(Le(4)); }
    uint64_t U64() { return Le(8); }
    int32_t I32() { return static_cast<int32_t>(U32()); }
    double F64() { return std::bit_cast<double>(U64()); }
    /// A count of items of at least `itemBytes` bytes each, 0 (and failed) if they cannot fit.
    uint32_t Count(size_t itemBytes) {
        uint32_t n = U32();
        if (!m_failed && n > remaining() / itemBytes) m_failed = true;
        return m_failed ? 0 : n;
    }
    std::string Str() {
        uint32_t n = Count(1);
        std::string s(m_bytes.substr(m_pos, n));
        m_pos += n;
        return s;
    }

  private:
    uint64_t Le(int n) {
        if (m_failed || remaining() < static_cast<size_t>(n)) {
            m_failed = true;
            return 0;
        }
        uint64_t x = 0;
        for (int i = n - 1; i >= 0; --i) x = (x << 8) | static_cast<uint8_t>(m_bytes[m_pos + i]);
        m_pos += n;
        return x;
    }
    std::string_view m_bytes;
    size_t m_pos = 0;
    bool m_failed = false;
};

void WriteProgram(Writer& w, const char* tag, const Program& p) {
    w.Str(tag);
    w.Str(p.shaderName);
    w.Str(p.sourcePath);
    w.I32(p.registerCount);
    w.Count(p.globalRegisters.size());
    for (uint16_t r : p.globalRegisters) w.U16(r);
    w.Count(p.constants.size());
    for (double k : p.constants) w.F64(k);
    w.Count(p.code.size());
    for (const Instr& in : p.code) {
        w.U8(static_cast<uint8_t>(in.op));
        w.U8(in.flags);
        w.U16(in.a);
        w.U16(in.b);
        w.U16(in.c);
    }
    w.Count(p.lines.size());
    for (int line : p.lines) w.I32(line);
    w.Count(p.outputs.size());
    for (const ProgramOutput& o : p.outputs) {
        w.Str(o.name);
        w.I32(o.size);
        for (uint16_t r : o.registers) w.U16(r);
    }
    w.Count(p.params.size());
    for (const ProgramParam& param : p.params) {
        w.Str(param.name);
        w.Str(param.type);
        w.I32(param.size);
        w.U16(param.firstRegister);
        w.Count(param.defaults.size());
        for (double d : param.defaults) w.F64(d);
    }
    w.Count(p.spaces.size());
    for (const std::string& space : p.spaces) w.Str(space);
    w.Count(p.textures ? p.textures->size() : 0);
    if (p.textures)
        for (const TextureSlot& slot : *p.textures) {
            const texture::LookupOptions& o = slot.options;
            w.Str(slot.path);
            w.I32(o.channel);
            w.U8(static_cast<uint8_t>(o.swrap));
            w.U8(static_cast<uint8_t>(o.twrap));
            w.U8(static_cast<uint8_t>(o.filter));
            w.U8(slot.fillIfMissing ? 1 : 0);
            w.F64(o.sblur);
            w.F64(o.tblur);
            w.F64(o.fill);
            w.Count(slot.dependsOn.size());
            for (const std::string& name : slot.dependsOn) w.Str(name);
        }
}

const char* kRunsPastEnd = "corrupt file (a field runs past the end of the data)";

/// Reads one program section into *p and verifies it; errors name the section.
bool ReadProgram(Reader& r, const std::string& tag, Program* p, std::string* error) {
    const std::string where = "program '" + tag + "': ";
    if (r.Str() != tag) return Fail(error, r.failed() ? kRunsPastEnd : "expected program section '" + tag + "'");
    p->shaderName = r.Str();
    p->sourcePath = r.Str();
    p->registerCount = r.I32();
    if (p->registerCount < 0 || p->registerCount > kMaxRegisters)
        return Fail(error, where + "register count " + std::to_string(p->registerCount) + " out of range");

    uint32_t nGlobals = r.U32();
    if (!r.failed() && nGlobals != static_cast<uint32_t>(kGlobalCount))
        return Fail(error, where + std::to_string(nGlobals) + " globals (this affray has " +
                               std::to_string(kGlobalCount) + ")");
    for (uint16_t& reg : p->globalRegisters) reg = r.U16();

    // Limits first, then the bytes left, then allocate.
    uint32_t nConstants = r.U32();
    if (nConstants > static_cast<uint32_t>(kMaxConstants))
        return Fail(error, where + "too many constants (" + std::to_string(nConstants) + ")");
    if (r.failed() || nConstants > r.remaining() / 8) return Fail(error, kRunsPastEnd);
    p->constants.resize(nConstants);
    for (double& k : p->constants) k = r.F64();

    const uint32_t nCode = r.Count(8);
    p->code.resize(nCode);
    for (Instr& in : p->code) {
        in.op = static_cast<Op>(r.U8());  // unknown numbers are Verify's to reject
        in.flags = r.U8();
        in.a = r.U16();
        in.b = r.U16();
        in.c = r.U16();
    }
    const uint32_t nLines = r.Count(4);
    if (!r.failed() && nLines != 0 && nLines != nCode)
        return Fail(error, where + "line table has " + std::to_string(nLines) + " entries for " +
                               std::to_string(nCode) + " instructions");
    p->lines.resize(nLines);
    for (int& line : p->lines) line = r.I32();

    // Smallest output: empty name (4), size (4), three registers (6).
    p->outputs.resize(r.Count(14));
    for (ProgramOutput& o : p->outputs) {
        o.name = r.Str();
        o.size = r.I32();
        for (uint16_t& reg : o.registers) reg = r.U16();
    }
    // Smallest parameter: two empty strings (8), size (4), register (2), no defaults (4).
    p->params.resize(r.Count(18));
    for (ProgramParam& param : p->params) {
        param.name = r.Str();
        param.type = r.Str();
        param.size = r.I32();
        param.firstRegister = r.U16();
        param.defaults.resize(r.Count(8));
        for (double& d : param.defaults) d = r.F64();
        if (r.failed()) break;
    }
    p->spaces.resize(r.Count(4));  // smallest: an empty name
    for (std::string& space : p->spaces) space = r.Str();
    // Smallest texture slot: an empty path (4), channel (4), four bytes, three doubles (24), no
    // parameter names (4).
    const uint32_t nTextures = r.Count(40);
    if (nTextures > static_cast<uint32_t>(kMaxTextureSlots))
        return Fail(error, where + "too many texture slots (" + std::to_string(nTextures) + ")");
    if (nTextures > 0) {
        auto slots = std::make_shared<TextureSlots>(nTextures);
        for (TextureSlot& slot : *slots) {
            texture::LookupOptions& o = slot.options;
            slot.path = r.Str();
            o.channel = r.I32();
            const uint8_t swrap = r.U8(), twrap = r.U8(), filter = r.U8(), fill = r.U8();
            o.sblur = r.F64();
            o.tblur = r.F64();
            o.fill = r.F64();
            slot.dependsOn.resize(r.Count(4));
            for (std::string& name : slot.dependsOn) name = r.Str();
            if (r.failed()) break;
            if (o.channel < 0 || swrap > 2 || twrap > 2 || filter > 3 || fill > 1 || !std::isfinite(o.sblur) ||
                !std::isfinite(o.tblur) || !(o.sblur >= 0) || !(o.tblur >= 0))
                return Fail(error, where + "texture slot of '" + slot.path + "' has bad options");
            o.swrap = static_cast<texture::Wrap>(swrap);
            o.twrap = static_cast<texture::Wrap>(twrap);
            o.filter = static_cast<texture::Filter>(filter);
            slot.fillIfMissing = fill != 0;
        }
        if (!r.failed()) {
            // The maps are read now, as when the shader was compiled: a file that cannot be read is
            // an error unless its lookup gave a fill.
            for (TextureSlot& slot : *slots) {
                std::string why;
                slot.map = texture::Open(slot.path, &why);
                if (!slot.map && !slot.fillIfMissing) return Fail(error, where + why);
            }
            p->textures = std::move(slots);
        }
    }
    if (r.failed()) return Fail(error, kRunsPastEnd);

    std::string problem;
    if (!Verify(*p, &problem)) return Fail(error, where + problem);
    return true;
}

}  // namespace

uint64_t HashSource(std::string_view text) {
    uint64_t h = 14695981039346656037ull;
    for (char c : text) {
        h ^= static_cast<uint8_t>(c);
        h *= 1099511628211ull;
    }
    return h;
}

std::string SaveBytecode(const BytecodeFile& file) {
    Writer w;
    w.Raw(kMagic, sizeof kMagic);
    w.U32(kBytecodeVersion);
    w.U64(0);  // file length, patched below
    w.U64(0);  // header check, patched below
    w.Str(file.shaderName);
    w.Str(file.sourcePath);
    w.U64(file.sourceHash);
    WriteProgram(w, "bound", file.bound);
    WriteProgram(w, "shade", file.shade);

    std::string& bytes = w.bytes();
    PutU64At(&bytes, 12, bytes.size() + kChecksumSize);
    PutU64At(&bytes, 20, HashSource(std::string_view(bytes).substr(0, 20)));
    w.U64(HashSource(bytes));
    return std::move(bytes);
}

bool LoadBytecode(std::string_view bytes, BytecodeFile* out, std::string* error) {
    const std::string_view magic(kMagic, sizeof kMagic);
    // Header: a strict prefix of a valid file must say "truncated file", whatever its length.
    if (bytes.size() < magic.size())
        return Fail(error, magic.starts_with(bytes) ? "truncated file" : "not an affray bytecode file");
    if (!bytes.starts_with(magic)) return Fail(error, "not an affray bytecode file");
    Reader header(bytes.substr(magic.size()));
    const uint32_t version = header.U32();
    if (header.failed()) return Fail(error, "truncated file");
    if (version != kBytecodeVersion)
        return Fail(error, "unsupported bytecode version " + std::to_string(version) + " (this affray reads " +
                               std::to_string(kBytecodeVersion) + ")");
    if (bytes.size() < kHeaderSize) return Fail(error, "truncated file");
    if (GetU64At(bytes, 20) != HashSource(bytes.substr(0, 20))) return Fail(error, "corrupt file (checksum mismatch)");
    const uint64_t length = GetU64At(bytes, 12);
    if (length < kHeaderSize + kChecksumSize)
        return Fail(error, "corrupt file (impossible length " + std::to_string(length) + ")");
    if (bytes.size() < length) return Fail(error, "truncated file");
    if (bytes.size() > length)
        return Fail(error,
                    "trailing bytes after the end of the file (" + std::to_string(bytes.size() - length) + " extra)");

    // Checksum before interpreting anything else, so damage is reported as damage.
    const std::string_view body = bytes.substr(0, length - kChecksumSize);
    if (GetU64At(bytes, body.size()) != HashSource(body)) return Fail(error, "corrupt file (checksum mismatch)");

    Reader r(body.substr(kHeaderSize));
    BytecodeFile file;
    file.shaderName = r.Str();
    file.sourcePath = r.Str();
    file.sourceHash = r.U64();
    if (r.failed()) return Fail(error, kRunsPastEnd);
    if (!ReadProgram(r, "bound", &file.bound, error) || !ReadProgram(r, "shade", &file.shade, error)) return false;
    if (r.remaining() != 0)
        return Fail(error, "corrupt file (" + std::to_string(r.remaining()) + " unused bytes after the programs)");
    if (out) *out = std::move(file);
    return true;
}

bool WriteBytecodeFile(const std::string& path, const BytecodeFile& file, diag::Report* report) {
    auto fail = [&](int err) {
        if (report) report->error({path}, "cannot write file: " + ErrnoText(err));
        return false;
    };
    const std::string bytes = SaveBytecode(file);
    // A name no other writer (thread or process) uses, in the same directory so rename is atomic.
    static std::atomic<unsigned> counter{0};
    const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) return fail(errno);

    size_t done = 0;
    int err = 0;
    while (done < bytes.size()) {
        ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            err = n < 0 ? errno : EIO;
            break;
        }
        done += static_cast<size_t>(n);
    }
    if (err == 0 && ::fsync(fd) != 0) err = errno;
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err == 0 && std::rename(tmp.c_str(), path.c_str()) != 0) err = errno;
    if (err != 0) {
        ::unlink(tmp.c_str());
        return fail(err);
    }
    return true;
}

bool ReadBytecodeFile(const std::string& path, BytecodeFile* out, diag::Report* report) {
    auto fail = [&](std::string message) {
        if (report) report->error({path}, std::move(message));
        return false;
    };
    std::string bytes;
    if (std::string problem = diag::ReadSourceFile(path, &bytes); !problem.empty()) return fail(std::move(problem));
    std::string problem;
    if (!LoadBytecode(bytes, out, &problem)) return fail(problem);
    return true;
}

}  // namespace affray::vm
