// JSON text with comments -> a JSON document, and the words the messages use for JSON values.
//
// nlohmann refuses a literal that overflows a double (1e400) while parsing, with no position;
// parse_json_text() finds it again with a SAX pass and reports its JSON path, line and column.
// A syntax error is reported by "line L, column C" (1-based, columns in bytes).
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace nmm {

/// Parses JSON text with comments allowed; InputError with "line L, column C" on a syntax error.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);

/// What a JSON value is, for "expected X, got Y" messages: "an object", "a number",
/// "a string ("10")" (short strings quoted: the quotes are often the mistake), ...
std::string describe_json_value(const nlohmann::json& v);

/// RFC 6901 escaping of one JSON pointer component: '~' -> "~0", '/' -> "~1".
std::string escape_json_pointer(const std::string& key);

}  // namespace nmm
