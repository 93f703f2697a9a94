#include "text_io.hpp"

#include <cctype>
#include <charconv>

namespace binpick::io::detail {

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// from_chars rejects a leading '+', which some writers emit.
std::string_view withoutPlusSign(std::string_view token) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  return token;
}

}  // namespace

void TextCursor::skipWhitespace() {
  while (position_ < text_.size() && isSpace(text_[position_])) {
    if (text_[position_] == '\n') ++line_;
    ++position_;
  }
}

std::string_view TextCursor::nextToken() {
  skipWhitespace();
  const std::size_t start = position_;
  while (position_ < text_.size() && !isSpace(text_[position_])) ++position_;
  return text_.substr(start, position_ - start);
}

void TextCursor::skipRestOfLine() {
  while (position_ < text_.size() && text_[position_] != '\n') ++position_;
}

bool TextCursor::restOfLineIsBlank() const {
  for (std::size_t i = position_; i < text_.size() && text_[i] != '\n'; ++i) {
    if (!isSpace(text_[i])) return false;
  }
  return true;
}

bool TextCursor::atEnd() {
  skipWhitespace();
  return position_ == text_.size();
}

bool parseFloat(std::string_view token, float& value) {
  token = withoutPlusSign(token);
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

bool parseInteger(std::string_view token, std::int64_t& value) {
  token = withoutPlusSign(token);
  const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) {
      return false;
    }
  }
  return true;
}

void appendNumber(std::string& out, float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

std::string describePoint(const Eigen::Vector3f& point) {
  std::string text = "(";
  for (int axis = 0; axis < 3; ++axis) {
    if (axis > 0) text += ", ";
    appendNumber(text, point[axis]);
  }
  return text + ")";
}

}  // namespace binpick::io::detail
