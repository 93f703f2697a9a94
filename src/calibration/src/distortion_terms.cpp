// The distortion terms a lens fit may change, to and from "k1,k2,p1,p2[,k3]".
#include "binpick/calibration/distortion_terms.hpp"

#include <set>
#include <sstream>

#include "binpick/core/error.hpp"

namespace binpick::calibration {

std::string DistortionTerms::text() const {
  std::string out;
  const auto add = [&out](bool on, const char* name) {
    if (!on) return;
    if (!out.empty()) out += ",";
    out += name;
  };
  add(k1, "k1");
  add(k2, "k2");
  add(tangential, "p1,p2");
  add(k3, "k3");
  return out.empty() ? "none" : out;
}

bool DistortionTerms::fits(int index) const {
  const std::array<bool, kDistortionTermCount> flags{k1, k2, tangential, k3};
  return flags.at(static_cast<std::size_t>(index));
}

DistortionTerms DistortionTerms::with(int index, bool fitted) const {
  DistortionTerms changed = *this;
  std::array<bool*, kDistortionTermCount> flags{&changed.k1, &changed.k2, &changed.tangential, &changed.k3};
  *flags.at(static_cast<std::size_t>(index)) = fitted;
  return changed;
}

bool DistortionTerms::operator==(const DistortionTerms& other) const {
  return k1 == other.k1 && k2 == other.k2 && tangential == other.tangential && k3 == other.k3;
}

DistortionTerms parseDistortionTerms(const std::string& text, const std::string& what) {
  const std::string expected = " (a comma-separated list of k1, k2, p1, p2, k3, or none)";
  if (text == "none") return {false, false, false, false};
  std::set<std::string> names;
  std::istringstream list(text);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (name != "k1" && name != "k2" && name != "p1" && name != "p2" && name != "k3") {
      throw core::Error(what + ": unknown term '" + name + "' in '" + text + "'" + expected);
    }
    if (!names.insert(name).second) throw core::Error(what + ": '" + name + "' given twice in '" + text + "'");
  }
  if (names.empty()) throw core::Error(what + ": no term in '" + text + "'" + expected);
  if (names.count("p1") != names.count("p2")) {
    throw core::Error(what + ": p1 and p2 (the tangential terms) are fitted together, not one alone: '" + text + "'");
  }
  return {names.count("k1") > 0, names.count("k2") > 0, names.count("p1") > 0, names.count("k3") > 0};
}

}  // namespace binpick::calibration
