// rib/args.cpp: argument shape checks shared by all RIB requests (see rib_args.h).
#include "rib/args.h"

#include <algorithm>
#include <cstdlib>
#include <glm/gtc/type_ptr.hpp>
#include <sstream>
#include <unordered_map>

namespace affray::rib {

// "[class] type[n]": the classes and types of RI 3.2 section 3 (with prman's "int", "bool" and
// the "facevertex" class).
renderer::StorageClass RibDeclaration::Storage() const {
    using renderer::StorageClass;
    if (storage == "constant") return StorageClass::Constant;
    if (storage == "uniform" || storage.empty()) return StorageClass::Uniform;
    if (storage == "varying") return StorageClass::Varying;
    if (storage == "vertex") return StorageClass::Vertex;
    return StorageClass::FaceVarying;  // facevarying, facevertex
}

std::string StandardDeclaration(const std::string& name) {
    if (name == "P") return "vertex point";
    if (name == "Pw") return "vertex hpoint";
    if (name == "N") return "varying normal";
    if (name == "Np") return "uniform normal";
    if (name == "st") return "varying float[2]";
    if (name == "s" || name == "t") return "varying float";
    if (name == "Cs" || name == "Os") return "varying color";
    return "";
}

bool RibDeclaration::Parse(const std::string& text, RibDeclaration* out, std::string* problem) {
    static const char* const kStorage[] = {"constant", "uniform", "varying", "vertex", "facevarying", "facevertex"};
    static const std::pair<const char*, int> kTypes[] = {
        {"float", 1}, {"integer", 1}, {"int", 1},    {"bool", 1},   {"string", 1},  {"color", 3},
        {"point", 3}, {"vector", 3},  {"normal", 3}, {"hpoint", 4}, {"matrix", 16},
    };
    std::istringstream in(text);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    RibDeclaration d;
    size_t i = 0;
    if (i < words.size() && std::find(std::begin(kStorage), std::end(kStorage), words[i]) != std::end(kStorage))
        d.storage = words[i++];
    if (i >= words.size()) {
        *problem = "declaration \"" + text + "\" has no type";
        return false;
    }
    std::string type = words[i++];
    // The array size may be written "float[2]" or "float [2]".
    if (i < words.size() && words[i].front() == '[') type += words[i++];
    if (i < words.size()) {
        *problem = "declaration \"" + text + "\" has words after its type";
        return false;
    }
    if (size_t open = type.find('['); open != std::string::npos) {
        const std::string size = type.substr(open + 1);
        char* end = nullptr;
        long n = std::strtol(size.c_str(), &end, 10);
        if (size.empty() || end != size.c_str() + size.size() - 1 || *end != ']' || n < 1 || n > 65536) {
            *problem = "declaration \"" + text + "\" needs a positive array size, as \"float[2]\"";
            return false;
        }
        d.arraySize = static_cast<int>(n);
        type.resize(open);
    }
    auto it = std::find_if(std::begin(kTypes), std::end(kTypes), [&](const auto& t) { return type == t.first; });
    if (it == std::end(kTypes)) {
        *problem = "declaration \"" + text + "\" has an unknown type '" + type +
                   "' (expected float, integer, string, color, point, vector, normal, hpoint or matrix)";
        return false;
    }
    d.type = type;
    d.components = it->second;
    *out = d;
    return true;
}

bool RibArgChecks::Fail(RibPos at, const std::string& message) {
    m_errorAt = at;
    m_errorMessage = message;
    return false;
}

std::string RibArgChecks::FormatNumber(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

bool RibArgChecks::NoArgs(const RibRequest& r) {
    if (r.args.empty()) return true;
    return Fail(r.args[0].at, Quote(r.name) + " takes no arguments, found " + r.args[0].Describe());
}

// The end of Numbers and LeadingNumbers: `count` values, else an error naming what was found.
bool RibArgChecks::TakeNumbers(const RibRequest& r, const std::vector<double>& values, const RibArg* bad, size_t count,
                               const char* names, double* out) {
    if (bad || values.size() != count) {
        std::string got = bad ? bad->Describe() : std::to_string(values.size());
        return Fail(r.at, Quote(r.name) + " expects " + std::to_string(count) + " numbers (" + names + "), got " + got);
    }
    std::copy(values.begin(), values.end(), out);
    return true;
}

// The leading numbers of a request: bare numbers and numeric arrays in any grouping, flattened
// (the RIB binding gives a request's numbers bare or as one array; exporters also group a point's
// three, as `Hyperboloid [x1 y1 z1] [x2 y2 z2] thetamax`, which prman and Aqsis read alike). They
// end at the first string (a parameter list) or once `count` are taken; an array that would
// carry them past `count` is reported.
static std::vector<double> LeadingValues(const RibRequest& r, size_t count, size_t* next, const RibArg** bad) {
    std::vector<double> values;
    size_t i = 0;
    for (; i < r.args.size() && values.size() < count; ++i) {
        const RibArg& arg = r.args[i];
        if (!arg.NumericP()) break;
        if (values.size() + arg.numbers.size() > count) {
            *bad = &arg;
            break;
        }
        values.insert(values.end(), arg.numbers.begin(), arg.numbers.end());
    }
    *next = i;
    return values;
}

// Exactly `count` numbers and nothing after them.
bool RibArgChecks::Numbers(const RibRequest& r, size_t count, const char* names, double* out) {
    size_t next = 0;
    const RibArg* bad = nullptr;
    const std::vector<double> values = LeadingValues(r, count, &next, &bad);
    if (!bad && next < r.args.size()) bad = &r.args[next];
    return TakeNumbers(r, values, bad, count, names, out);
}

// Like Numbers, but a parameter list may follow: the numbers end at the first non-number.
bool RibArgChecks::LeadingNumbers(const RibRequest& r, size_t count, const char* names, double* out, size_t* next) {
    const RibArg* bad = nullptr;
    const std::vector<double> values = LeadingValues(r, count, next, &bad);
    return TakeNumbers(r, values, bad, count, names, out);
}

bool RibArgChecks::LeadingString(const RibRequest& r, const char* what, std::string* out) {
    if (r.args.empty() || r.args[0].isArray || !r.args[0].StringsP())
        return Fail(r.args.empty() ? r.at : r.args[0].at,
                    Quote(r.name) + " expects " + what + " as its first argument" +
                        (r.args.empty() ? "" : ", found " + r.args[0].Describe()));
    *out = r.args[0].strings[0];
    return true;
}

DeclaredName SplitDeclaredName(const std::string& text, const char* blanks) {
    DeclaredName out;
    const size_t last = text.find_last_not_of(blanks);
    if (last == std::string::npos) return out;
    const size_t space = text.find_last_of(blanks, last);
    const size_t start = space == std::string::npos ? 0 : space + 1;
    out.name = text.substr(start, last + 1 - start);
    if (start > 0) {
        const size_t declBegin = text.find_first_not_of(blanks);
        const size_t declEnd = text.find_last_not_of(blanks, start - 1);
        if (declBegin <= declEnd) out.declaration = text.substr(declBegin, declEnd + 1 - declBegin);
    }
    return out;
}

// Token-value pairs from args[first]. A token may carry an inline declaration ("uniform float
// Km"); its last word is the name. A repeated name replaces the earlier value.
bool RibArgChecks::ParamList(const RibRequest& r, size_t first, std::vector<RibParam>* out, bool checkDeclared) {
    std::unordered_map<std::string, size_t> index;
    for (size_t i = 0; i < out->size(); ++i) index[(*out)[i].value.name] = i;
    for (size_t i = first; i < r.args.size(); i += 2) {
        const RibArg& token = r.args[i];
        if (token.isArray || !token.StringsP())
            return Fail(token.at, Quote(r.name) + " expects a parameter name string, found " + token.Describe());
        DeclaredName split = SplitDeclaredName(token.strings[0]);
        if (split.name.empty()) return Fail(token.at, Quote(r.name) + " has an empty parameter name");
        RibParam p;
        p.value.name = std::move(split.name);
        p.value.declaration = std::move(split.declaration);
        if (p.value.declaration.empty())
            if (auto declared = m_declared.find(p.value.name); declared != m_declared.end())
                p.value.declaration = declared->second;
        if (i + 1 >= r.args.size())
            return Fail(token.at, Quote(r.name) + " parameter " + Quote(p.value.name) + " has no value");
        const RibArg& value = r.args[i + 1];
        p.value.numbers = value.numbers;
        p.value.strings = value.strings;
        p.at = value.at;
        if (checkDeclared && !p.value.declaration.empty() && !CheckDeclared(r, token, p)) return false;
        // An index by name keeps long parameter lists linear.
        auto [slot, isNew] = index.try_emplace(p.value.name, out->size());
        if (isNew)
            out->push_back(std::move(p));
        else
            (*out)[slot->second] = std::move(p);
    }
    return true;
}

// A value against its declaration: strings for a string, numbers otherwise, and for a uniform or
// constant parameter (the class by default) exactly the count the type holds. Varying classes
// hold one value per vertex, face or corner, which only the primitive knows: a whole number of
// values.
bool RibArgChecks::CheckDeclared(const RibRequest& r, const RibArg& token, const RibParam& p) {
    RibDeclaration d;
    std::string problem;
    const std::string what = Quote(r.name) + " parameter " + Quote(p.value.name);
    if (!RibDeclaration::Parse(p.value.declaration, &d, &problem)) return Fail(token.at, what + ": " + problem);
    const bool strings = d.type == "string";
    const bool empty = p.value.numbers.empty() && p.value.strings.empty();
    if (!empty && strings != p.value.numbers.empty())
        return Fail(p.at, what + " is declared \"" + p.value.declaration + "\" and expects " +
                              (strings ? "strings" : "numbers") + ", got " + (strings ? "numbers" : "strings"));
    const size_t count = strings ? p.value.strings.size() : p.value.numbers.size();
    const bool uniform = d.storage == "constant" || ((d.storage.empty() || d.storage == "uniform") && !m_uniformVaries);
    const size_t each = d.UniformCount();  // one value of the declared type
    if (uniform ? count != each : count % each != 0)
        return Fail(p.at, what + " is declared \"" + p.value.declaration + "\" and expects " +
                              (uniform ? "" : "a multiple of ") + std::to_string(each) +
                              (strings ? " string" : " number") + (each == 1 ? "" : "s") + ", got " +
                              std::to_string(count));
    return true;
}

bool RibArgChecks::ParamNumbers(const RibParam& p, const std::string& context, size_t count, double* out) {
    if (!p.value.strings.empty() || p.value.numbers.size() != count) {
        std::string got = !p.value.strings.empty() ? "a string" : std::to_string(p.value.numbers.size());
        return Fail(p.at, context + " parameter " + Quote(p.value.name) + " expects " + std::to_string(count) +
                              (count == 1 ? " number" : " numbers") + ", got " + got);
    }
    std::copy(p.value.numbers.begin(), p.value.numbers.end(), out);
    return true;
}

bool RibArgChecks::ParamVector(const RibParam& p, const std::string& context, glm::dvec3* out) {
    double v[3];
    if (!ParamNumbers(p, context, 3, v)) return false;
    *out = glm::dvec3(v[0], v[1], v[2]);
    return true;
}

// 16 numbers, row-major for row vectors, which is column-major for column vectors (see the file
// head). Only affine matrices: the last column of the RIB matrix must be 0 0 0 w, w != 0.
bool RibArgChecks::Matrix(const RibRequest& r, glm::dmat4* out) {
    double m[16];
    if (!Numbers(r, 16, "a 4x4 matrix", m)) return false;
    if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] == 0)
        return Fail(r.at, Quote(r.name) +
                              " matrix must be affine (last column 0 0 0 1); projective transforms "
                              "are not supported yet");
    *out = glm::make_mat4(m) / m[15];
    return true;
}

}  // namespace affray::rib
