// The stream side: splitting bytes into messages, and the framing-independent entry points.
#include "binpick/io/error.hpp"
#include "robot_codec.hpp"

namespace binpick::robot {

namespace {

// The bytes of [data, data + size) up to the next '\n', or nothing if none is there.
std::optional<std::size_t> newlineOffset(const char* data, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') return i;
  }
  return std::nullopt;
}

}  // namespace

RequestDecoder::RequestDecoder(const CodecParams& params) : params_(params) { params_.validate(); }

void RequestDecoder::feed(const char* data, std::size_t size) {
  if (params_.framing == Framing::Binary) {
    feedBinary(data, size);
  } else {
    feedAscii(data, size);
  }
}

void RequestDecoder::feedBinary(const char* data, std::size_t size) {
  buffer_.append(data, size);
  std::size_t start = 0;
  // The command id tells how long its request is; until it has arrived, nothing is decided.
  constexpr std::size_t kIdSize = 4;
  while (buffer_.size() - start >= kIdSize) {
    const std::size_t length =
        detail::binaryRequestSize(detail::readInt32(buffer_.data() + start, params_.byte_order));
    if (buffer_.size() - start < length) break;
    ready_.push_back(detail::decodeBinaryRequest(buffer_.data() + start, params_));
    start += length;
  }
  buffer_.erase(0, start);
}

void RequestDecoder::feedAscii(const char* data, std::size_t size) {
  // A line of n bytes before its '\n' is n + 1 long: too long once n >= max_line_length,
  // which is decided the same way whether its '\n' is in sight yet or not.
  const std::size_t limit = params_.max_line_length;
  while (size > 0) {
    const std::optional<std::size_t> newline = newlineOffset(data, size);
    if (discarding_) {
      if (!newline) return;
      discarding_ = false;
    } else if (newline && buffer_.size() + *newline < limit) {
      buffer_.append(data, *newline);
      if (auto decoded = detail::decodeAsciiRequestLine(buffer_, params_)) {
        ready_.push_back(std::move(*decoded));
      }
      buffer_.clear();
    } else if (buffer_.size() + (newline ? *newline : size) >= limit) {
      buffer_.append(data, std::min(size, limit - buffer_.size()));
      ready_.push_back(detail::oversizedAsciiRequest(buffer_.substr(0, limit)));
      buffer_.clear();
      discarding_ = !newline;
      if (!newline) return;
    } else {
      buffer_.append(data, size);  // an incomplete line, shorter than the limit so far
      return;
    }
    data += *newline + 1;
    size -= *newline + 1;
  }
}

std::optional<Decoded> RequestDecoder::next() {
  if (next_ == ready_.size()) return std::nullopt;
  Decoded decoded = std::move(ready_[next_++]);
  if (next_ == ready_.size()) {  // all handed out: reuse the storage
    ready_.clear();
    next_ = 0;
  }
  return decoded;
}

std::size_t RequestDecoder::buffered() const { return buffer_.size(); }

std::string encodeReply(const Reply& reply, const CodecParams& params) {
  params.validate();
  detail::checkReply(reply);
  return params.framing == Framing::Ascii ? detail::encodeAsciiReply(reply, params)
                                          : detail::encodeBinaryReply(reply, params);
}

std::string encodeRequest(const Request& request, const CodecParams& params) {
  params.validate();
  detail::checkRequest(request);
  if (params.framing == Framing::Binary) return detail::encodeBinaryRequest(request, params);
  std::string line = detail::encodeAsciiRequest(request, params);
  if (line.size() > params.max_line_length) {
    throw Error("Request: '" + line.substr(0, line.size() - 2) + "' is longer than " +
                std::to_string(params.max_line_length) + " characters (max_line_length)");
  }
  return line;
}

ReplyDecoder::ReplyDecoder(const CodecParams& params) : params_(params) { params_.validate(); }

void ReplyDecoder::feed(const char* data, std::size_t size) { buffer_.append(data, size); }

std::optional<Reply> ReplyDecoder::next() {
  if (params_.framing == Framing::Binary) {
    if (buffer_.size() < kBinaryReplySize) return std::nullopt;
    const std::string message = buffer_.substr(0, kBinaryReplySize);
    buffer_.erase(0, kBinaryReplySize);  // consumed before a throw: next() goes on after it
    return detail::decodeBinaryReply(message.data(), params_);
  }
  while (true) {
    const std::size_t newline = buffer_.find('\n');
    if (discarding_) {
      if (newline == std::string::npos) {
        buffer_.clear();
        return std::nullopt;
      }
      buffer_.erase(0, newline + 1);
      discarding_ = false;
      continue;
    }
    const std::size_t length = newline == std::string::npos ? buffer_.size() : newline;
    if (length >= params_.max_line_length) {
      discarding_ = newline == std::string::npos;
      buffer_.erase(0, newline == std::string::npos ? buffer_.size() : newline + 1);
      throw Error("malformed reply: a line longer than " + std::to_string(params_.max_line_length) +
                  " characters (max_line_length)");
    }
    if (newline == std::string::npos) return std::nullopt;
    const std::string line = buffer_.substr(0, newline);
    buffer_.erase(0, newline + 1);
    if (line.empty() || line == "\r") continue;
    return detail::decodeAsciiReplyLine(line, params_);
  }
}

}  // namespace binpick::robot
