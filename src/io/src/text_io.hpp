#pragma once
// Internal: tokenising and number conversion for the text formats (ascii PLY, ascii STL, OBJ).
// Numbers go through std::from_chars/std::to_chars: locale-independent, no per-byte iostream
// overhead, and floats written as the shortest text that reads back to the identical value.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace binpick::io::detail {

// Whitespace-separated tokens of a text, with the line number of the last token for messages.
class TextCursor {
 public:
  explicit TextCursor(std::string_view text, std::size_t firstLine = 1) : text_(text), line_(firstLine) {}

  // The next token, or an empty view at the end of the text.
  std::string_view nextToken();
  // Drops everything up to and including the next newline (e.g. a free-form name).
  void skipRestOfLine();
  bool atEnd();
  // True when only blanks remain before the next newline (or the end of the text).
  bool restOfLineIsBlank() const;
  // 1-based line of the most recent token.
  std::size_t line() const { return line_; }
  std::size_t remainingBytes() const { return text_.size() - position_; }

 private:
  void skipWhitespace();

  std::string_view text_;
  std::size_t position_ = 0;
  std::size_t line_;
};

// Whole-token conversions; false when the token is not entirely a number of that kind. An
// optional leading '+' is accepted. parseFloat returns false for out-of-range values like 1e999.
bool parseFloat(std::string_view token, float& value);
bool parseInteger(std::string_view token, std::int64_t& value);

bool equalsIgnoringCase(std::string_view a, std::string_view b);

// Appends the shortest decimal text that parses back to exactly `value` ("nan", "inf" for those).
void appendNumber(std::string& out, float value);
// "(x, y, z)" for error messages.
std::string describePoint(const Eigen::Vector3f& point);

}  // namespace binpick::io::detail
