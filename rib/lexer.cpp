// rib/lexer.cpp: RIB ASCII tokens and requests (see rib/lexer.h for the rules).
#include "rib/lexer.h"

#include "diag/limits.h"

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
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
    std::snprintf(buffer, sizeof buffer, "byte 0x%02x%s", byte, byte >= 0x80 ? " (binary RIB is not supported)" : "");
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
    if (m_pos >= m_text.size()) return token;  // End

    char c = m_text[m_pos];
    if (c == '"') return LexString();
    if (c == '[' || c == ']') {
        ++m_pos;
        token.kind = c == '[' ? RibToken::Kind::ArrayBegin : RibToken::Kind::ArrayEnd;
        return token;
    }
    if (DigitP(c) || c == '.' || c == '+' || c == '-') return LexNumber();
    if (AlphaP(c)) return LexName();
    return Error(Here(), "unexpected " + DescribeChar(c));
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

    // from_chars accepts no leading '+'; parse in long double so that overflow past double's
    // range is detected here rather than silently becoming infinity. libstdc++ parses a long
    // double with strtold, which reads to a NUL: parse a NUL-terminated copy, since the text
    // (a string_view) need not end with one.
    std::string_view numeral = word;
    if (numeral.size() > 1 && numeral[0] == '+' && numeral[1] != '-' && numeral[1] != '+') numeral.remove_prefix(1);
    const std::string digits(numeral);
    long double value = 0;
    auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (ec == std::errc::result_out_of_range ||
        (ec == std::errc() && std::isfinite(value) && std::fabs(value) > DBL_MAX))
        return Error(at, "number '" + std::string(word) + "' is out of range");
    if (ec != std::errc() || end != digits.data() + digits.size())
        return Error(at, "malformed number '" + std::string(word) + "'");
    if (!std::isfinite(value))
        return Error(at, "invalid number '" + std::string(word) + "': NaN and infinity are not allowed");
    RibToken token;
    token.kind = RibToken::Kind::Number;
    token.number = static_cast<double>(value);  // values below double's range round to 0
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
