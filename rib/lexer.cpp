// rib/lexer.cpp: RIB ASCII tokens and requests (see rib/lexer.h for the rules).
#include "rib/lexer.h"

#include "diag/limits.h"

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace affray::rib {
namespace {

bool SpaceP(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
bool AlphaP(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool DigitP(char c) { return c >= '0' && c <= '9'; }

// Characters that may continue a number token; anything else ends it.
bool NumberCharP(char c) { return AlphaP(c) || DigitP(c) || c == '.' || c == '+' || c == '-'; }

bool EqualsNoCaseP(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        char x = a[i], y = b[i];
        if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
        if (x != y) return false;
    }
    return true;
}

bool NonFiniteWordP(std::string_view word) {
    if (!word.empty() && (word[0] == '+' || word[0] == '-')) word.remove_prefix(1);
    return EqualsNoCaseP(word, "nan") || EqualsNoCaseP(word, "inf") || EqualsNoCaseP(word, "infinity");
}

std::string DescribeChar(char c) {
    auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x21 && byte < 0x7f) return std::string("character '") + c + "'";
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "byte 0x%02x", byte);
    return buffer;
}

/// The IEEE single-precision float of the 32 bits `raw` (binary RIB's 0244 and float arrays).
float FloatOfBits(uint64_t raw) {
    const auto bits = static_cast<uint32_t>(raw);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

/// A binary number as a message shows it (the ASCII lexer keeps the numeral as written).
std::string NumberText(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", v);
    return buffer;
}

}  // namespace

RibToken RibLexer::Error(RibPos at, std::string message) {
    RibToken token;
    token.kind = RibToken::Kind::Error;
    token.text = std::move(message);
    token.at = at;
    m_pos = m_text.size();  // an error ends the input: Next() then returns End
    return token;
}

RibToken RibLexer::Next() {
    if (m_inFloats) {
        // A binary float array's values, then its ']'.
        RibToken token;
        token.at = m_floatsAt;
        if (m_nextFloat < m_floats.size()) {
            token.kind = RibToken::Kind::Number;
            token.number = m_floats[m_nextFloat++];
            token.text = NumberText(token.number);
        } else {
            token.kind = RibToken::Kind::ArrayEnd;
            m_inFloats = false;
        }
        return token;
    }
    // A binary definition (of a request or a string) gives no token: the one after it. (A loop,
    // not a recursion: a file may hold any number of definitions in a row.)
    RibToken token;
    while (!NextToken(&token)) {}
    return token;
}

bool RibLexer::NextToken(RibToken* out) {
    // Skip white space and # comments (## structure comments included).
    while (m_pos < m_text.size()) {
        char c = m_text[m_pos];
        if (c == '\n') {
            NewLine();
        } else if (SpaceP(c)) {
            ++m_pos;
        } else if (c == '#') {
            while (m_pos < m_text.size() && m_text[m_pos] != '\n') ++m_pos;
        } else {
            break;
        }
    }
    RibToken token;
    token.at = Here();
    if (m_pos >= m_text.size()) {  // End
        *out = token;
        return true;
    }

    char c = m_text[m_pos];
    if (static_cast<unsigned char>(c) >= 0200) return LexBinary(out);
    if (c == '"') {
        *out = LexString();
        return true;
    }
    if (c == '[' || c == ']') {
        ++m_pos;
        token.kind = c == '[' ? RibToken::Kind::ArrayBegin : RibToken::Kind::ArrayEnd;
        *out = token;
        return true;
    }
    if (DigitP(c) || c == '.' || c == '+' || c == '-')
        *out = LexNumber();
    else if (AlphaP(c))
        *out = LexName();
    else
        *out = Error(Here(), "unexpected " + DescribeChar(c));
    return true;
}

bool RibLexer::Unsigned(int n, uint64_t* out) {
    if (m_text.size() - m_pos < static_cast<size_t>(n)) return false;
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) v = v << 8 | static_cast<unsigned char>(m_text[m_pos++]);
    *out = v;
    return true;
}

bool RibLexer::BinaryString(std::string* out) {
    if (m_pos >= m_text.size()) return false;
    const auto b = static_cast<unsigned char>(m_text[m_pos]);
    if (b == '"') {
        const RibToken t = LexString();
        if (t.kind != RibToken::Kind::String) return false;
        *out = t.text;
        return true;
    }
    uint64_t length = 0;
    if (b >= 0220 && b <= 0237) {
        ++m_pos;
        length = b - 0220;
    } else if (b >= 0240 && b <= 0243) {
        ++m_pos;
        if (!Unsigned(b - 0240 + 1, &length)) return false;
    } else {
        return false;
    }
    if (length > m_text.size() - m_pos) return false;
    out->assign(m_text.substr(m_pos, length));
    m_pos += length;
    return true;
}

bool RibLexer::LexBinary(RibToken* out) {
    // RI Spec 3.2, Appendix C.2. Each branch reads its whole value, so a byte inside one (a
    // newline, a '#') is never taken for ASCII; line numbers count only ASCII newlines.
    const auto give = [&](RibToken token) {
        *out = std::move(token);
        return true;
    };
    const RibPos at = Here();
    const auto b = static_cast<unsigned char>(m_text[m_pos++]);
    const auto truncated = [&] { return give(Error(at, "binary RIB ends inside the value that starts here")); };
    RibToken token;
    token.at = at;
    if (b <= 0217) {
        // 0200 + 4d + w: a number of w + 1 bytes, big-endian, d of them after the point;
        // signed when it has an integer part.
        const int bytes = (b & 3) + 1, fraction = (b >> 2) & 3;
        if (fraction > bytes) return give(Error(at, "invalid binary RIB number code " + DescribeChar(char(b))));
        uint64_t raw = 0;
        if (!Unsigned(bytes, &raw)) return truncated();
        double v = static_cast<double>(raw);
        if (fraction < bytes && raw >> (8 * bytes - 1)) v -= std::ldexp(1.0, 8 * bytes);
        token.kind = RibToken::Kind::Number;
        token.number = std::ldexp(v, -8 * fraction);
        token.text = NumberText(token.number);
        return give(std::move(token));
    }
    if (b <= 0243) {
        --m_pos;
        if (!BinaryString(&token.text)) return truncated();
        token.kind = RibToken::Kind::String;
        return give(std::move(token));
    }
    if (b == 0244 || b == 0245) {
        uint64_t raw = 0;
        if (!Unsigned(b == 0244 ? 4 : 8, &raw)) return truncated();
        double v;
        if (b == 0244)
            v = FloatOfBits(raw);
        else
            std::memcpy(&v, &raw, sizeof v);
        if (!std::isfinite(v)) return give(Error(at, "invalid binary RIB number: NaN and infinity are not allowed"));
        token.kind = RibToken::Kind::Number;
        token.number = v;
        token.text = NumberText(v);
        return give(std::move(token));
    }
    if (b == 0246) {
        uint64_t code = 0;
        if (!Unsigned(1, &code)) return truncated();
        if (code >= m_requests.size() || m_requests[code].empty())
            return give(Error(at, "binary RIB request code " + std::to_string(code) + " was never defined"));
        token.kind = RibToken::Kind::Name;
        token.text = m_requests[code];
        return give(std::move(token));
    }
    if (b >= 0310 && b <= 0313) {
        // A float array: its length in 1 to 4 bytes, then that many 32-bit floats.
        uint64_t length = 0;
        if (!Unsigned(b - 0310 + 1, &length)) return truncated();
        if (length > (m_text.size() - m_pos) / 4) return truncated();
        if (static_cast<int64_t>(length) > diag::LimitValue(diag::Limit::RibArray))
            return give(Error(at, "array longer than " + std::to_string(diag::LimitValue(diag::Limit::RibArray)) +
                                      " values " + diag::LimitNote(diag::Limit::RibArray)));
        m_floats.resize(length);
        m_nextFloat = 0;
        for (uint64_t i = 0; i < length; ++i) {
            uint64_t raw = 0;
            Unsigned(4, &raw);
            m_floats[i] = FloatOfBits(raw);
            if (!std::isfinite(m_floats[i]))
                return give(Error(at, "invalid number in a binary RIB array: NaN and infinity are not allowed"));
        }
        m_inFloats = true;
        m_floatsAt = at;
        token.kind = RibToken::Kind::ArrayBegin;
        return give(std::move(token));
    }
    if (b == 0314) {
        // Defines request `code`: a name to be named by 0246 code later.
        uint64_t code = 0;
        std::string name;
        if (!Unsigned(1, &code) || !BinaryString(&name)) return truncated();
        if (name.empty() || !AlphaP(name[0]))
            return give(Error(at, "binary RIB defines request code " + std::to_string(code) + " as \"" + name +
                                      "\", which is no request name"));
        if (m_requests.size() <= code) m_requests.resize(code + 1);
        m_requests[code] = std::move(name);
    } else if (b == 0315 || b == 0316) {
        // Defines string token `id` (1 or 2 bytes).
        uint64_t id = 0;
        std::string value;
        if (!Unsigned(b - 0315 + 1, &id) || !BinaryString(&value)) return truncated();
        if (m_strings.size() <= id) m_strings.resize(id + 1);
        m_strings[id] = std::move(value);
    } else if (b == 0317 || b == 0320) {
        uint64_t id = 0;
        if (!Unsigned(b - 0317 + 1, &id)) return truncated();
        if (id >= m_strings.size())
            return give(Error(at, "binary RIB string token " + std::to_string(id) + " was never defined"));
        token.kind = RibToken::Kind::String;
        token.text = m_strings[id];
        return give(std::move(token));
    } else {
        return give(Error(at, "unexpected " + DescribeChar(char(b)) + " (reserved in binary RIB)"));
    }
    return false;
}

RibToken RibLexer::LexString() {
    const RibPos start = Here();
    ++m_pos;  // opening quote
    std::string value;
    while (m_pos < m_text.size()) {
        char c = m_text[m_pos];
        if (c == '\n') {
            value += c;
            NewLine();
            continue;
        }
        ++m_pos;
        if (c == '"') {
            RibToken token;
            token.kind = RibToken::Kind::String;
            token.text = std::move(value);
            token.at = start;
            return token;
        }
        if (c != '\\') {
            value += c;
            continue;
        }
        if (m_pos >= m_text.size()) break;
        char e = m_text[m_pos];
        if (e == '\n') {  // backslash-newline continues the string
            NewLine();
            continue;
        }
        ++m_pos;
        switch (e) {
            case 'n': value += '\n'; break;
            case 'r': value += '\r'; break;
            case 't': value += '\t'; break;
            case 'b': value += '\b'; break;
            case 'f': value += '\f'; break;
            default:
                if (e >= '0' && e <= '7') {
                    // Up to three octal digits, as in C.
                    int code = e - '0';
                    for (int i = 0; i < 2 && m_pos < m_text.size() && m_text[m_pos] >= '0' && m_text[m_pos] <= '7'; ++i)
                        code = code * 8 + (m_text[m_pos++] - '0');
                    value += static_cast<char>(code & 0xff);
                } else {
                    value += e;  // \\, \" and any other escaped character stand for themselves
                }
        }
    }
    return Error(start, "unterminated string");
}

RibToken RibLexer::LexNumber() {
    const RibPos at = Here();
    size_t start = m_pos;
    while (m_pos < m_text.size() && NumberCharP(m_text[m_pos])) ++m_pos;
    std::string_view word = m_text.substr(start, m_pos - start);
    if (NonFiniteWordP(word))
        return Error(at, "invalid number '" + std::string(word) + "': NaN and infinity are not allowed");

    // from_chars accepts no leading '+'. A double is read correctly rounded; only where it is out
    // of double's range is the numeral read again in long double, to tell overflow (an error
    // here, rather than a silent infinity) from underflow (a value below double's range, which
    // rounds to 0). libstdc++ parses a long double with strtold, which reads to a NUL: that
    // parse takes a NUL-terminated copy, since the text (a string_view) need not end with one.
    std::string_view numeral = word;
    if (numeral.size() > 1 && numeral[0] == '+' && numeral[1] != '-' && numeral[1] != '+') numeral.remove_prefix(1);
    double value = 0;
    auto [end, ec] = std::from_chars(numeral.data(), numeral.data() + numeral.size(), value);
    if (ec == std::errc::result_out_of_range) {
        const std::string digits(numeral);
        long double wide = 0;
        auto [wideEnd, wideEc] = std::from_chars(digits.data(), digits.data() + digits.size(), wide);
        if (wideEc == std::errc::result_out_of_range || (wideEc == std::errc() && std::fabs(wide) > DBL_MAX))
            return Error(at, "number '" + std::string(word) + "' is out of range");
        if (wideEc != std::errc() || wideEnd != digits.data() + digits.size())
            return Error(at, "malformed number '" + std::string(word) + "'");
        value = static_cast<double>(wide);  // below double's range: 0 or a subnormal
        ec = std::errc();
        end = numeral.data() + numeral.size();
    }
    if (ec != std::errc() || end != numeral.data() + numeral.size())
        return Error(at, "malformed number '" + std::string(word) + "'");
    if (!std::isfinite(value))
        return Error(at, "invalid number '" + std::string(word) + "': NaN and infinity are not allowed");
    RibToken token;
    token.kind = RibToken::Kind::Number;
    token.number = value;
    token.text = std::string(word);
    token.at = at;
    return token;
}

RibToken RibLexer::LexName() {
    const RibPos at = Here();
    size_t start = m_pos;
    while (m_pos < m_text.size() && (AlphaP(m_text[m_pos]) || DigitP(m_text[m_pos]))) ++m_pos;
    std::string_view word = m_text.substr(start, m_pos - start);
    if (NonFiniteWordP(word))
        return Error(at, "invalid number '" + std::string(word) + "': NaN and infinity are not allowed");
    RibToken token;
    token.kind = RibToken::Kind::Name;
    token.text = std::string(word);
    token.at = at;
    return token;
}

std::string RibArg::Describe() const {
    if (!isArray) {
        if (numbers.empty()) return "string \"" + strings[0] + "\"";
        std::ostringstream text;
        text << "number " << numbers[0];
        return text.str();
    }
    size_t n = numbers.size() + strings.size();
    return "array of " + std::to_string(n) + (strings.empty() ? " number" : " string") + (n == 1 ? "" : "s");
}

void RibRequestReader::Advance() {
    m_token = m_lexer.Next();
    if (m_token.kind != RibToken::Kind::End) m_lastPos = m_token.at;
}

namespace {

/// `message` about a bad number that follows a bare string in a request's arguments, with the
/// parameter that string names ("Km" [1e400]): the number is then reported against the shader or
/// light parameter it was meant for, not only by its line. Other messages are returned as they
/// are (LexNumber's messages are the ones that quote a "number '...'").
std::string InParameter(const RibRequest& request, std::string message) {
    if (request.args.empty() || message.find("number '") == std::string::npos) return message;
    const RibArg& last = request.args.back();
    if (last.isArray || last.strings.size() != 1) return message;
    return message + " (in the value of parameter \"" + last.strings[0] + "\" of " + request.name + ")";
}

}  // namespace

RibRequestReader::Status RibRequestReader::Next(RibRequest* request, std::string* error, RibPos* errorAt) {
    using Kind = RibToken::Kind;
    auto fail = [&](RibPos at, std::string message) {
        *error = std::move(message);
        *errorAt = at;
        return Status::Error;
    };
    request->args.clear();
    switch (m_token.kind) {
        case Kind::End: return Status::End;
        case Kind::Error: return fail(m_token.at, m_token.text);
        case Kind::Name: break;
        case Kind::Number: return fail(m_token.at, "expected a request name, found number " + m_token.text);
        case Kind::String: return fail(m_token.at, "expected a request name, found string \"" + m_token.text + "\"");
        case Kind::ArrayBegin: return fail(m_token.at, "expected a request name, found '['");
        case Kind::ArrayEnd: return fail(m_token.at, "']' without matching '['");
    }
    request->name = m_token.text;
    request->at = m_token.at;
    Advance();

    // Arguments run up to the next request name or the end of the input.
    for (;;) {
        RibArg arg;
        arg.at = m_token.at;
        switch (m_token.kind) {
            case Kind::Name:
            case Kind::End: return Status::Ok;
            case Kind::Error: return fail(m_token.at, InParameter(*request, m_token.text));
            case Kind::ArrayEnd: return fail(m_token.at, "']' without matching '['");
            case Kind::Number:
                arg.numbers.push_back(m_token.number);
                Advance();
                break;
            case Kind::String:
                arg.strings.push_back(std::move(m_token.text));
                Advance();
                break;
            case Kind::ArrayBegin:
                if (!ReadArray(&arg, error, errorAt)) {
                    *error = InParameter(*request, *error);
                    return Status::Error;
                }
                break;
        }
        request->args.push_back(std::move(arg));
    }
}

bool RibRequestReader::ReadArray(RibArg* arg, std::string* error, RibPos* errorAt) {
    using Kind = RibToken::Kind;
    const RibPos open = m_token.at;
    arg->isArray = true;
    arg->at = open;
    auto fail = [&](RibPos at, std::string message) {
        *error = std::move(message);
        *errorAt = at;
        return false;
    };
    Advance();  // '['
    for (;;) {
        switch (m_token.kind) {
            case Kind::ArrayEnd: Advance(); return true;
            case Kind::End: return fail(open, "unterminated array: '[' has no matching ']'");
            case Kind::Error: return fail(m_token.at, m_token.text);
            case Kind::ArrayBegin: return fail(m_token.at, "nested arrays are not allowed");
            case Kind::Name:
                return fail(m_token.at, "expected a number, a string or ']' in the array opened on line " +
                                            std::to_string(open.line) + ", found '" + m_token.text + "'");
            case Kind::Number:
                if (static_cast<int64_t>(arg->numbers.size() + arg->strings.size()) >=
                    diag::LimitValue(diag::Limit::RibArray))
                    return fail(m_token.at, "array longer than " +
                                                std::to_string(diag::LimitValue(diag::Limit::RibArray)) + " values " +
                                                diag::LimitNote(diag::Limit::RibArray));
                if (!arg->strings.empty()) return fail(m_token.at, "array mixes strings and numbers");
                arg->numbers.push_back(m_token.number);
                break;
            case Kind::String:
                if (static_cast<int64_t>(arg->numbers.size() + arg->strings.size()) >=
                    diag::LimitValue(diag::Limit::RibArray))
                    return fail(m_token.at, "array longer than " +
                                                std::to_string(diag::LimitValue(diag::Limit::RibArray)) + " values " +
                                                diag::LimitNote(diag::Limit::RibArray));
                if (!arg->numbers.empty()) return fail(m_token.at, "array mixes numbers and strings");
                arg->strings.push_back(std::move(m_token.text));
                break;
        }
        Advance();
    }
}

}  // namespace affray::rib
