// Which views spoil a fit. One wrong image or pose can spoil the fit of every view (two views
// with swapped images give hundreds of millimetres everywhere), so the residuals alone may not
// show the culprits. When the fit is too poor to use, the fewest views whose removal lets the
// rest fit are searched for: every single view first, then every pair, and so on, within a
// budget of solves (each takes about a millisecond).
#include <sstream>

#include "binpick/io/error.hpp"
#include "hand_eye_internal.hpp"

namespace binpick::calibration::detail {
namespace {

// OpenCV's solvers need 3 views; one more leaves a residual to judge the rest by.
constexpr std::size_t kFewestViews = 4;
constexpr int kMaxSolves = 2000;

struct Fit {
  double rms_mm = 0.0;
  double rms_deg = 0.0;
  bool within(const HandEyeParams& p) const {
    return rms_mm <= p.max_rms_mm && rms_deg <= p.max_rms_deg;
  }
};

bool fitWithout(const std::vector<HandEyeView>& views, const std::vector<std::size_t>& dropped,
                const HandEyeParams& params, Fit& fit) {
  std::vector<HandEyeView> rest;
  for (std::size_t i = 0, d = 0; i < views.size(); ++i) {
    if (d < dropped.size() && dropped[d] == i) ++d;
    else rest.push_back(views[i]);
  }
  try {
    const HandEyeProblem problem = makeProblem(rest, params.setup, false);
    const PoseDifference rms = rmsOf(residualsOf(problem, solveWithOpenCv(problem, params.method)));
    fit = {rms.translation_mm, rms.rotation_deg};
    return true;
  } catch (const Error&) {
    return false;  // OpenCV found no solution for these views
  }
}

// The next combination of `chosen.size()` indices out of n in lexicographic order; false after
// the last.
bool nextCombination(std::vector<std::size_t>& chosen, std::size_t n) {
  for (std::size_t i = chosen.size(); i-- > 0;) {
    if (chosen[i] < n - chosen.size() + i) {
      ++chosen[i];
      for (std::size_t j = i + 1; j < chosen.size(); ++j) chosen[j] = chosen[j - 1] + 1;
      return true;
    }
  }
  return false;
}

std::string sentence(const std::vector<HandEyeView>& views, const std::vector<std::size_t>& dropped,
                     const Fit& fit) {
  std::ostringstream text;
  text.precision(3);
  text << "the other views fit (" << fit.rms_mm << " mm, " << fit.rms_deg << " deg RMS) without";
  for (const std::size_t i : dropped) text << " " << views[i].name;
  text << ": check their images and robot poses";
  return text.str();
}

}  // namespace

std::string blameViews(std::vector<HandEyeView> views, const HandEyeParams& params) {
  int solves = 0;
  for (std::size_t count = 1; count + kFewestViews <= views.size(); ++count) {
    std::vector<std::size_t> dropped(count);
    for (std::size_t i = 0; i < count; ++i) dropped[i] = i;
    bool found = false;
    std::vector<std::size_t> best;
    Fit best_fit;
    do {
      if (++solves > kMaxSolves) return "";
      Fit fit;
      if (fitWithout(views, dropped, params, fit) && fit.within(params) &&
          (!found || fit.rms_mm < best_fit.rms_mm)) {
        found = true;
        best = dropped;
        best_fit = fit;
      }
    } while (nextCombination(dropped, views.size()));
    if (found) return sentence(views, best, best_fit);
  }
  return "";
}

}  // namespace binpick::calibration::detail
