// The paper's synthetic experiment (Li & Hashimoto 2018, section IV-A) on the virtual cell, with
// binpick, its Drost baselines and the peers' PPF implementations on the same scenes; the paper's
// Figure 5; and how binpick's time scales. Writes results.md, outcomes.csv and PNG plots.
//
//   bench_paper [--scenes 2] [--parts gear,l_bracket,...] [--methods binpick,ppf5,...]
//               [--inputs exact,reconstructed] [--sections paper,selection,scaling]
//               [--objects 20] [--seed 1] [--threads 0] [--scaling-part l_bracket]
//               [--scaling-scenes 2] [--out docs/benchmark]
#include <iostream>

#include "paper/bench_paper_options.hpp"
#include "paper/bench_paper_run.hpp"

int main(int argc, char** argv) {
  try {
    const binpick::bench::PaperBenchOptions options = binpick::bench::parsePaperBenchOptions(argc, argv);
    binpick::bench::runPaperBench(options, argc, argv);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "bench_paper: " << e.what() << "\n";
    return 1;
  }
}
