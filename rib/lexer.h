// rib/lexer.h: the RIB tokenizer and the grouping of tokens into requests.
// Owns the syntax of RIB (RI Spec 3.2, Appendix C): request names, numbers, "strings" with C
// escapes, [ arrays ] and # comments, and the binary encoding of Appendix C.2 (bytes 0200 to
// 0377: encoded numbers, strings, float arrays, and requests and strings defined once and then
// named by a code), which may be mixed with ASCII anywhere between tokens. It knows nothing
// about what a request means; that is rib/rib.cpp. Rules: every token carries the line it starts on; lexing always advances, so
// no input can make it loop; a bad token is an Error token with a message, never an exception.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace affray::rib {

/// A place in RIB text: line and column (in bytes) from 1, and the file. The lexer leaves
/// file 0; the reader numbers the files ReadArchive opens from 1 (see rib/parser.h).
struct RibPos {
    int line = 1;
    int column = 1;
    int file = 0;
};

/// One RIB token.
struct RibToken {
    enum class Kind { Name, Number, String, ArrayBegin, ArrayEnd, End, Error } kind = Kind::End;
    std::string text;   ///< Name: the name. String: the unescaped contents. Error: the message.
    double number = 0;  ///< Number: the value (always finite).
    RibPos at;          ///< Where the token starts.
};

/// Splits RIB ASCII text into tokens. The text must outlive the lexer.
class RibLexer {
  public:
    explicit RibLexer(std::string_view text) : m_text(text) {}

    /// The next token; End at the end of the text (and for ever after).
    RibToken Next();
    /// Where the lexer has reached.
    RibPos Here() const { return {m_line, static_cast<int>(m_pos - m_lineStart) + 1}; }

  private:
    RibToken LexString();
    RibToken LexNumber();
    RibToken LexName();
    /// The next token into *out; false if it was a binary definition, which gives none.
    bool NextToken(RibToken* out);
    /// One binary token at m_pos (a byte from 0200) into *out: a number, a string, a request or
    /// a float array (its '[', then its values from m_floats one token at a time); false for a
    /// definition (of a request or a string), which gives none.
    bool LexBinary(RibToken* out);
    /// A string at m_pos for a binary definition: binary-encoded or "quoted".
    bool BinaryString(std::string* out);
    /// The next n bytes as an unsigned big-endian integer; false if the text ends first.
    bool Unsigned(int n, uint64_t* out);
    RibToken Error(RibPos at, std::string message);
    /// Steps over a line break at m_pos.
    void NewLine() {
        ++m_line;
        m_lineStart = ++m_pos;
    }

    std::string_view m_text;
    size_t m_pos = 0;
    size_t m_lineStart = 0;  // where line m_line starts
    int m_line = 1;
    // Binary RIB: the requests (by code, 0 to 255) and strings (by token, 0 to 65535) defined so
    // far, and the decoded float array being returned (m_nextFloat its next value, m_floatsAt
    // where it starts).
    std::vector<std::string> m_requests, m_strings;
    std::vector<float> m_floats;  // the binary float array being returned, with its ']' after it
    size_t m_nextFloat = 0;
    bool m_inFloats = false;
    RibPos m_floatsAt;
};

/// One argument of a request: a bare number, a bare string, or an array of either.
struct RibArg {
    bool isArray = false;
    std::vector<double> numbers;       ///< Bare number: one value. Numeric array: its values.
    std::vector<std::string> strings;  ///< Bare string: one value. String array: its values.
    RibPos at;

    /// True for a bare number or an array without strings (an empty array counts as both kinds).
    bool NumericP() const { return strings.empty(); }
    /// True for a bare string or an array without numbers.
    bool StringsP() const { return numbers.empty(); }
    /// "number 3", "string \"fov\"" or "array of 4 numbers", for messages.
    std::string Describe() const;
};

/// A request name and its arguments, up to the next request name.
struct RibRequest {
    std::string name;
    RibPos at;
    std::vector<RibArg> args;
};

/// Reads requests one at a time from RIB text.
class RibRequestReader {
  public:
    explicit RibRequestReader(std::string_view text) : m_lexer(text) { Advance(); }

    enum class Status { Ok, End, Error };
    /// Reads the next request into *request. On Error, *error is "message" and *errorAt its place.
    Status Next(RibRequest* request, std::string* error, RibPos* errorAt);
    /// Where the last token read starts, for errors at the end of the input.
    RibPos LastPos() const { return m_lastPos; }

  private:
    void Advance();
    bool ReadArray(RibArg* arg, std::string* error, RibPos* errorAt);

    RibLexer m_lexer;
    RibToken m_token;  // one token of lookahead
    RibPos m_lastPos;
};

}  // namespace affray::rib
