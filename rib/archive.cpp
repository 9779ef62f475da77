// rib/archive.cpp: RIB requests that bring in requests from elsewhere: ReadArchive (another RIB
// file or an inline archive, read in place), inline archives (ArchiveBegin, ArchiveEnd) and
// retained objects (ObjectBegin, ObjectEnd, ObjectInstance). Rules shared with rib.cpp are in
// rib/parser.h.
//
// Files: every file read gets a number in m_sources (the scene is 0), which its requests' RibPos
// carry, so a diagnostic names the archive's own file:line:col. An archive is read by pushing a
// reader for it; Run() reads the innermost reader until it ends.
//
// Objects (RI 3.2 section 5.6): the requests between ObjectBegin and ObjectEnd are recorded,
// not run. ObjectInstance runs them inside an attribute block, so the object takes the graphics
// state current at the instance (transform, color, shaders) and its own transforms and attributes
// apply on top of it, as the spec says.
#include <algorithm>
#include <filesystem>
#include <system_error>

#include "rib/file.h"
#include "rib/parser.h"

namespace affray::rib {
namespace {

// Requests an object definition cannot hold: options, frame and world blocks and lights (RI 3.2
// allows only geometry, transforms and attributes in an object).
constexpr std::string_view kNotInObject[] = {
    "Format",           "Projection",
    "Display",          "FrameAspectRatio",
    "ScreenWindow",     "CropWindow",
    "Clipping",         "PixelSamples",
    "PixelFilter",      "Exposure",
    "Option",           "Hider",
    "FrameBegin",       "FrameEnd",
    "WorldBegin",       "WorldEnd",
    "LightSource",      "AreaLightSource",
    "ObjectBegin",      "MotionBegin",
    "CoordinateSystem", "ScopedCoordinateSystem",
};

constexpr int kMaxInstanceDepth = 32;  // objects instancing objects: deeper is a cycle

}  // namespace

std::string RibParser::FindArchive(const std::string& name, int from, std::string* searched) const {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path file(name);
    if (file.is_absolute()) {
        *searched = name;
        return fs::is_regular_file(file, ec) ? name : std::string();
    }
    const fs::path here = fs::path(m_sources[static_cast<size_t>(from)].path).parent_path();
    const fs::path sceneDir = fs::path(m_sources[0].path).parent_path();
    std::vector<fs::path> dirs = {here};
    for (const std::string& dir : m_archiveSearchPath)
        dirs.push_back(fs::path(dir).is_absolute() ? fs::path(dir) : sceneDir / dir);
    searched->clear();
    for (const fs::path& dir : dirs) {
        const fs::path candidate = dir / file;
        *searched += (searched->empty() ? "" : ", ") + (dir.empty() ? std::string(".") : dir.string());
        if (fs::is_regular_file(candidate, ec)) return candidate.string();
    }
    return {};
}

// ReadArchive "name": the requests of the inline archive of that name if one was defined, else of
// the file, read here as if written in place.
bool RibParser::DoReadArchive(const RibRequest& r) {
    std::string name;
    if (!LeadingString(r, "an archive file name", &name)) return false;
    if (r.args.size() > 1) return Fail(r.args[1].at, "'ReadArchive' expects one string (a file name)");
    auto it = m_inlineArchives.find(name);
    if (it == m_inlineArchives.end()) return OpenArchive(r, r.args[0].at, name, false);
    for (const OpenReader& open : m_readers)
        if (open.inlineRequests && open.inlineName == name)
            return Fail(r.args[0].at,
                        "inline archive " + Quote(name) + " reads itself (from " + LineName(open.at, r.at) + ")");
    OpenReader reader{RibRequestReader(std::string_view()), r.at.file, false, r.at, m_blocks.size()};
    reader.inlineRequests = it->second;
    reader.inlineName = name;
    m_readers.push_back(std::move(reader));
    return true;
}

// Inline archives (RIB 3.3, prman and the exporters that target it): ArchiveBegin "name" ...
// ArchiveEnd keeps its requests, unrun, under the name; ReadArchive "name" reads them in place,
// as it would a file. A name defined again names the new archive; parameters are ignored.
bool RibParser::DoArchiveBegin(const RibRequest& r) {
    if (r.name == "ArchiveEnd") return Fail(r.at, "'ArchiveEnd' without matching 'ArchiveBegin'");
    std::string name;
    if (!LeadingString(r, "an archive name", &name)) return false;
    std::vector<RibParam> params;
    if (!ParamList(r, 1, &params)) return false;
    if (name.empty()) return Fail(r.args[0].at, "'ArchiveBegin' name must not be empty");
    m_archiveDef = ArchiveDef{name, r.at, {}, 0};
    return true;
}

bool RibParser::RecordArchive(const RibRequest& r) {
    if (r.name == "ArchiveBegin") ++m_archiveDef->depth;
    if (r.name == "ArchiveEnd" && m_archiveDef->depth-- == 0) {
        if (!NoArgs(r)) return false;
        m_inlineArchives[m_archiveDef->name] =
            std::make_shared<const std::vector<RibRequest>>(std::move(m_archiveDef->requests));
        m_archiveDef.reset();
        return true;
    }
    m_archiveDef->requests.push_back(r);
    return true;
}

bool RibParser::DoProcedural(const RibRequest& r) {
    std::string kind;
    if (!LeadingString(r, "a procedural name", &kind)) return false;
    if (r.name == "Procedural" && kind == "DelayedReadArchive") {
        // Procedural "DelayedReadArchive" ["file"] [xmin xmax ymin ymax zmin zmax]
        if (r.args.size() != 3 || !r.args[1].isArray || r.args[1].strings.size() != 1 || !r.args[1].StringsP() ||
            !r.args[2].NumericP() || r.args[2].numbers.size() != 6)
            return Fail(r.args.size() > 1 ? r.args[1].at : r.at,
                        "'Procedural \"DelayedReadArchive\"' expects [\"file\"] and a bound [xmin xmax ymin ymax "
                        "zmin zmax]");
        return OpenArchive(r, r.args[1].at, r.args[1].strings[0], true);
    }
    if (r.name == "Procedural2" && kind == "DelayedReadArchive2") {
        // Procedural2 "DelayedReadArchive2" "SimpleBound" "string filename" ["file"] "float[6] bound" [...]
        std::vector<RibParam> params;
        if (r.args.size() < 2 || !r.args[1].StringsP() || r.args[1].isArray)
            return Fail(r.args.size() > 1 ? r.args[1].at : r.at,
                        "'Procedural2' expects the procedural's name, its bound function's name, then parameters");
        if (!ParamList(r, 2, &params)) return false;
        for (const RibParam& p : params)
            if (p.value.name == "filename" && p.value.strings.size() == 1)
                return OpenArchive(r, p.at, p.value.strings[0], true);
        return Fail(r.at, "'Procedural2 \"DelayedReadArchive2\"' needs a \"string filename\" parameter");
    }
    // A program's geometry is skipped, as an unsupported primitive is (rib/unsupported.cpp).
    if (kind == "RunProgram" || kind == "DynamicLoad" || kind == "RunProgram2" || kind == "DynamicLoad2") {
        Warn(r.args[0].at, "procedural " + Quote(kind) +
                               " makes geometry by running a program, which affray does not do: skipped (write its "
                               "output to a RIB file and read that with 'ReadArchive')");
        return true;
    }
    return Fail(r.args[0].at, "unknown procedural " + Quote(kind) + " (affray reads " +
                                  (r.name == "Procedural" ? "\"DelayedReadArchive\")" : "\"DelayedReadArchive2\")"));
}

bool RibParser::EndArchive(const OpenReader& reader) {
    if (!reader.procedural) return true;
    const RibPos at = reader.reader.LastPos();
    const std::string what = "the archive read by 'Procedural' on " + LineName(reader.at, RibPos{}) + " ";
    if (m_defining) {
        if (m_definingDepth != 1) return Fail(at, what + "leaves a block open");
        return Record(RibRequest{"AttributeEnd", reader.at, {}});
    }
    if (m_blocks.size() != reader.blocks) return Fail(at, what + "leaves a block open or closes one it did not open");
    return End(RibRequest{"AttributeEnd", reader.at, {}}, Block::Attribute);
}

bool RibParser::OpenArchive(const RibRequest& r, RibPos nameAt, const std::string& name, bool procedural) {
    // A delayed archive of a level of detail not drawn (DetailRange) is not opened: a renderer
    // reads one only when it is needed.
    if (procedural && m_state.detailHidden) return true;
    std::string searched;
    const std::string path = FindArchive(name, r.at.file, &searched);
    if (path.empty()) return Fail(nameAt, "archive " + Quote(name) + " not found (searched " + searched + ")");
    // A file already being read would read itself for ever.
    std::error_code ec;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
    for (const OpenReader& open : m_readers) {
        if (open.inlineRequests) continue;
        const std::string& openPath = m_sources[static_cast<size_t>(open.file)].path;
        if (std::filesystem::weakly_canonical(openPath, ec) == canonical) {
            std::string chain;
            for (const OpenReader& o : m_readers) chain += m_sources[static_cast<size_t>(o.file)].path + " -> ";
            return Fail(nameAt, Quote(r.name) + " cycle: " + chain + path);
        }
    }
    auto text = std::make_unique<std::string>();
    if (const std::string reason = ReadRibFile(path, text.get()); !reason.empty())
        return Fail(nameAt, "cannot read archive " + Quote(path) + ": " + reason);
    // A Procedural's requests go in an attribute block of their own (RI 3.2: a procedural's
    // geometry takes the graphics state of its request and changes nothing after it).
    if (procedural) {
        const RibRequest begin{"AttributeBegin", r.at, {}};
        if (!(m_defining ? Record(begin) : Begin(begin, Block::Attribute))) return false;
    }
    const std::string_view view = *text;
    m_sources.push_back({path, std::move(text), view});
    m_readers.push_back(
        {RibRequestReader(view), static_cast<int>(m_sources.size() - 1), procedural, r.at, m_blocks.size()});
    return true;
}

bool RibParser::ObjectHandle(const RibRequest& r, std::string* out) {
    if (r.args.size() != 1 || r.args[0].isArray)
        return Fail(r.at, Quote(r.name) + " expects one object handle (a number or a string)");
    const RibArg& handle = r.args[0];
    *out = handle.StringsP() ? handle.strings[0] : FormatNumber(handle.numbers[0]);
    return true;
}

bool RibParser::DoObjectBegin(const RibRequest& r) {
    std::string handle;
    if (!ObjectHandle(r, &handle)) return false;
    if (m_worldEnded) return Fail(r.at, "'ObjectBegin' after 'WorldEnd'");
    m_defining.emplace(handle, ObjectDef{r.at, {}});
    m_definingDepth = 0;
    return true;
}

bool RibParser::DoObjectEnd(const RibRequest& r) {
    if (!NoArgs(r)) return false;
    if (!m_defining) return Fail(r.at, "'ObjectEnd' without matching 'ObjectBegin'");
    if (m_definingDepth != 0)
        return Fail(r.at, "'ObjectEnd' inside an 'AttributeBegin' or 'TransformBegin' of the object");
    // A handle defined again names the new definition (RI 3.2).
    m_objects[m_defining->first] = std::move(m_defining->second);
    m_defining.reset();
    return true;
}

bool RibParser::Record(const RibRequest& r) {
    if (r.name == "ObjectEnd") return DoObjectEnd(r);
    if (r.name == "ReadArchive" || r.name == "Declare" || r.name == "Procedural" || r.name == "Procedural2")
        return Dispatch(r);
    if (std::find(std::begin(kNotInObject), std::end(kNotInObject), r.name) != std::end(kNotInObject))
        return Fail(r.at, Quote(r.name) + " cannot be part of an object (started by 'ObjectBegin' on line " +
                              std::to_string(m_defining->second.at.line) + ")");
    if (r.name == "AttributeBegin" || r.name == "TransformBegin" || r.name == "SolidBegin") ++m_definingDepth;
    if (r.name == "AttributeEnd" || r.name == "TransformEnd" || r.name == "SolidEnd") {
        if (m_definingDepth == 0)
            return Fail(r.at, Quote(r.name) + " inside an object closes a block opened outside it");
        --m_definingDepth;
    }
    m_defining->second.requests.push_back(r);
    return true;
}

bool RibParser::DoObjectInstance(const RibRequest& r) {
    std::string handle;
    if (!ObjectHandle(r, &handle) || !InsideWorld(r)) return false;
    auto it = m_objects.find(handle);
    if (it == m_objects.end()) return Fail(r.args[0].at, "no object " + Quote(handle) + " has been defined");
    if (m_instanceDepth >= kMaxInstanceDepth)
        return Fail(r.at, "objects instance each other more than " + std::to_string(kMaxInstanceDepth) +
                              " deep (an object that instances itself?)");
    // The object's requests inside an attribute block: the instance's graphics state, restored after.
    const ObjectDef& object = it->second;
    const State saved = m_state;
    // The note of an error inside the replay, at the outermost instance: for the meshes it makes,
    // whose errors RefineScene reports (AddMesh).
    std::pair<RibPos, std::string> note{r.at, "in the instance of object " + Quote(handle) + " here"};
    if (m_instanceDepth == 0) m_instanceNote = note;
    ++m_instanceDepth;
    for (const RibRequest& request : object.requests) {
        if (!Dispatch(request)) {
            // Each level out replaces the note, so it ends at the outermost instance.
            m_errorNote = std::move(note);
            return false;
        }
    }
    // Record() saw that the object's blocks close inside it, so m_blocks is as it was.
    --m_instanceDepth;
    if (m_instanceDepth == 0) m_instanceNote.reset();
    m_state = saved;
    return true;
}

}  // namespace affray::rib
