#pragma once
// Which of OpenCV's k1 k2 p1 p2 k3 lens distortion terms a calibration fits; the others are held
// at 0. The default, k1,k2,p1,p2, suits lenses whose board views do not reach the image corners:
// there k3 cannot be told from k1 and k2 and a free k3 bends the model where there are no
// corners. A lens with a strong sixth-order term (a projector lens with k3 = -0.012 left 0.48 px
// at the image corners with k3 held) needs k3, and views reaching the corners to pin it.
#include <array>
#include <string>

namespace binpick::calibration {

// The terms one by one, in OpenCV's order; the tangential pair counts as one.
constexpr int kDistortionTermCount = 4;
constexpr std::array<const char*, kDistortionTermCount> kDistortionTermNames{"k1", "k2", "p1,p2", "k3"};

struct DistortionTerms {
  bool k1 = true;
  bool k2 = true;
  bool tangential = true;  // p1 and p2, together
  bool k3 = false;
  std::string text() const;  // "k1,k2,p1,p2", "none" when every term is held
  // Term `index` of kDistortionTermNames.
  bool fits(int index) const;
  DistortionTerms with(int index, bool fitted) const;
  bool operator==(const DistortionTerms& other) const;
};

// "k1,k2,p1,p2", "k1,k2,p1,p2,k3", "k1", "k1,k2", "k1,k2,k3", "none", ... in any order.
// Throws core::Error naming `what` and the bad term: unknown names, repeats, p1 without p2.
DistortionTerms parseDistortionTerms(const std::string& text, const std::string& what = "distortion terms");

}  // namespace binpick::calibration
