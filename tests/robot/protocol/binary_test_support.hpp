#pragma once
// Binary-framing codecs and raw byte strings for the protocol tests.
#include <initializer_list>
#include <string>

#include "binpick/robot/protocol.hpp"

namespace binpick::robot {

inline CodecParams binary(ByteOrder order, core::Orientation orientation = core::Orientation::Quaternion) {
  CodecParams params;
  params.framing = Framing::Binary;
  params.byte_order = order;
  params.orientation = orientation;
  return params;
}

inline std::string bytes(std::initializer_list<unsigned char> values) {
  return std::string(values.begin(), values.end());
}

}  // namespace binpick::robot
