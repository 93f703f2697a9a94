#pragma once
// Internal: the number of threads a params struct asks for (0 = every core).
#include <omp.h>

namespace binpick::sim::detail {

inline int threadCount(int requested) {
  return requested > 0 ? requested : omp_get_max_threads();
}

}  // namespace binpick::sim::detail
