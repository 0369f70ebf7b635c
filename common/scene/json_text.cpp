// JSON text -> document, with the position of a syntax error: see json_text.h.
//
// A document built in memory (a merge patch) can still hold inf or NaN; the scene's readers
// check every number for being finite when they read it (common/scene/json_reader.h).
#include "common/scene/json_text.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/error.h"

namespace nmm {

using nlohmann::json;

std::string describe_json_value(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::object:
      return "an object";
    case json::value_t::array:
      return "an array";
    case json::value_t::string: {
      const std::string& s = v.get_ref<const std::string&>();
      // Quote short strings: `got a string ("10")` shows at once that the quotes are the mistake.
      return s.size() <= 40 ? "a string (\"" + s + "\")" : "a string";
    }
    case json::value_t::boolean:
      return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number";
    default:
      return "an unsupported value";
  }
}

std::string escape_json_pointer(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

namespace {

/// "line L, column C" (both 1-based, columns in bytes) of byte index `at` of `text`.
std::string line_column(const std::string& text, std::size_t at) {
  at = std::min(at, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < at; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(at - line_start + 1);
}

/// SAX handler that builds nothing and records the first error: its byte position, the token
/// read last, nlohmann's message and the JSON path of the value being read.
class ErrorLocator : public nlohmann::json_sax<json> {
 public:
  bool failed = false;
  int id = 0;                ///< nlohmann's error id (101: syntax, 406: number overflow, ...)
  std::size_t position = 0;  ///< bytes read when the error was found
  std::string token, message, path;

  bool null() override { return begin_value(); }
  bool boolean(bool) override { return begin_value(); }
  bool number_integer(number_integer_t) override { return begin_value(); }
  bool number_unsigned(number_unsigned_t) override { return begin_value(); }
  bool number_float(number_float_t, const string_t&) override { return begin_value(); }
  bool string(string_t&) override { return begin_value(); }
  bool binary(binary_t&) override { return begin_value(); }
  bool start_object(std::size_t) override {
    begin_value();
    frames_.push_back(Frame{false, 0, ""});
    return true;
  }
  bool key(string_t& k) override {
    frames_.back().key = k;
    return true;
  }
  bool end_object() override { return end_container(); }
  bool start_array(std::size_t) override {
    begin_value();
    frames_.push_back(Frame{true, 0, ""});
    return true;
  }
  bool end_array() override { return end_container(); }

  bool parse_error(std::size_t pos, const std::string& last_token,
                   const json::exception& ex) override {
    failed = true;
    id = ex.id;
    position = pos;
    token = last_token;
    message = ex.what();
    // Drop "[json.exception.parse_error.101] " and "parse error at line 1, column 2: ": the
    // position is reported on its own.
    const std::size_t bracket = message.find("] ");
    if (bracket != std::string::npos) message.erase(0, bracket + 2);
    const std::size_t colon = message.find(": ");
    if (message.rfind("parse error", 0) == 0 && colon != std::string::npos)
      message.erase(0, colon + 2);
    // The failing value is the next element of the innermost array (not yet counted) or the
    // value of the innermost object's last key; outer arrays are on their last element.
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      const bool innermost = i + 1 == frames_.size();
      path += "/" +
              (f.array ? std::to_string(innermost ? f.count : f.count - 1) : escape_json_pointer(f.key));
    }
    return false;
  }

 private:
  struct Frame {
    bool array;         ///< array or object
    std::size_t count;  ///< array: elements begun so far
    std::string key;    ///< object: the last key read
  };
  std::vector<Frame> frames_;

  bool begin_value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().count;
    return true;
  }
  bool end_container() {
    frames_.pop_back();
    return true;
  }
};

}  // namespace

json parse_json_text(const std::string& text, const std::string& file) {
  try {
    return json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::exception&) {
    // Parse again only to find where: a number overflow (406) carries no position at all.
    ErrorLocator locator;
    json::sax_parse(text, &locator, json::input_format_t::json, /*strict=*/true,
                    /*ignore_comments=*/true);
    if (!locator.failed) throw;  // cannot happen: both passes run the same parser
    if (locator.id == 406) {
      // The position is just past the number; point at its first character instead.
      const std::size_t start = locator.position - std::min(locator.position, locator.token.size());
      throw InputError(file, locator.path,
                       "number " + locator.token + " is too large for a double (at " +
                           line_column(text, start) + ")");
    }
    // The position counts the bytes read, so the offending byte is the one before it (at the end
    // of the input it is one past the text).
    const std::size_t at = locator.position == 0 ? 0 : locator.position - 1;
    throw InputError(file, line_column(text, at), "invalid JSON: " + locator.message);
  }
}

}  // namespace nmm
