// The paper's synthetic experiment (Li & Hashimoto 2018, section IV-A) on the virtual cell, with
// binpick, its Drost baselines and the peers' PPF implementations on the same scenes; the paper's
// Figure 5; and how binpick's time scales. Writes results.md, outcomes.csv and PNG plots.
//
//   bench_paper --help lists the options; scripts/benchmark.sh runs it for docs/BENCHMARK.md.
#include <iostream>

#include "paper/bench_paper_options.hpp"
#include "paper/bench_paper_run.hpp"

int main(int argc, char** argv) {
  try {
    const binpick::bench::PaperBenchOptions options = binpick::bench::parsePaperBenchOptions(argc, argv);
    if (options.help) {
      std::cout << binpick::bench::paperBenchUsage();
      return 0;
    }
    binpick::bench::runPaperBench(options, argc, argv);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_paper: " << e.what() << "\n";
    return 1;
  }
}
