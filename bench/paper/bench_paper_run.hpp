#pragma once
// bench_paper's whole run: the experiment, Figure 5 and scaling, written to options.out.
#include "bench_paper_options.hpp"

namespace binpick::bench {

void runPaperBench(const PaperBenchOptions& options, int argc, char** argv);

}  // namespace binpick::bench
