// Runs a fuzz target without libFuzzer, on a seeded stream of inputs made from its seed corpus
// (fuzz/corpus/TARGET): corpus files as they are, glued together and mutated (bytes flipped,
// inserted, dropped, chunks repeated or spliced in from another file, lines cut, numbers made
// huge, negative or not numbers, binary words set to extremes, the file cut short), and random
// bytes. Deterministic, so a failure reproduces; the target aborts on a finding, failing the run.
//   usage: DRIVER CORPUS_DIR [INPUTS [SEED]]
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

// The corpus files in name order, so that a seed means the same inputs on every machine.
std::vector<std::string> readCorpus(const std::string& directory) {
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (entry.is_regular_file()) paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<std::string> corpus;
  for (const auto& path : paths) {
    std::ifstream stream(path, std::ios::binary);
    corpus.emplace_back(std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>());
  }
  return corpus;
}

std::string randomBytes(std::mt19937& random, std::size_t size) {
  std::string bytes(size, '\0');
  for (char& c : bytes) c = static_cast<char>(random());
  return bytes;
}

// Values at the edges of what headers and settings hold: counts past 2^31 and 2^32, negative
// ones, and numbers that are no numbers.
const char* interestingNumber(std::mt19937& random) {
  static const char* const kNumbers[] = {"0",          "-1",          "2147483647", "2147483648", "4294967295",
                                         "4294967296", "1099511627776", "1e308",    "-1e-320",    "nan",
                                         "inf",        "99999999999999999999", "65536", "3"};
  return kNumbers[random() % (sizeof(kNumbers) / sizeof(kNumbers[0]))];
}

// Replaces the run of digits around `at` (or inserts at `at`) with an interesting number.
void replaceNumber(std::string& input, std::size_t at, std::mt19937& random) {
  std::size_t begin = at, end = at;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(input[begin - 1]))) --begin;
  while (end < input.size() && std::isdigit(static_cast<unsigned char>(input[end]))) ++end;
  input.replace(begin, end - begin, interestingNumber(random));
}

// Overwrites four bytes with a 32-bit extreme, as binary counts and sizes are stored.
void overwriteWord(std::string& input, std::size_t at, std::mt19937& random) {
  static const uint32_t kWords[] = {0u, 1u, 0x7fffffffu, 0x80000000u, 0xffffffffu, 0x00010000u};
  const uint32_t word = kWords[random() % (sizeof(kWords) / sizeof(kWords[0]))];
  for (std::size_t i = 0; i < 4 && at + i < input.size(); ++i) input[at + i] = static_cast<char>(word >> (8 * i));
}

void mutate(std::string& input, const std::vector<std::string>& corpus, std::mt19937& random) {
  if (input.empty()) return;
  const std::size_t at = random() % input.size();
  switch (random() % 10) {
    case 0: input[at] = static_cast<char>(random()); break;
    case 1: input.insert(at, 1, static_cast<char>(random())); break;
    case 2: input.erase(at, 1 + random() % 8); break;
    case 3: input.insert(at, input.substr(at, 1 + random() % 40)); break;
    case 4: input.insert(at, 1, '\n'); break;
    case 5: input.insert(at, std::string(random() % 300, static_cast<char>('A' + random() % 26))); break;
    case 6: replaceNumber(input, at, random); break;
    case 7: input.resize(at); break;
    case 8: overwriteWord(input, at, random); break;
    default: {
      const std::string& other = corpus[random() % corpus.size()];
      if (other.empty()) break;
      const std::size_t from = random() % other.size();
      input.insert(at, other.substr(from, 1 + random() % 64));
    }
  }
}

std::string nextInput(const std::vector<std::string>& corpus, std::mt19937& random) {
  if (random() % 8 == 0) return randomBytes(random, random() % 200);
  std::string input = corpus[random() % corpus.size()];
  if (random() % 4 == 0) {  // several files glued: streams, and files with something after them
    const std::size_t more = 1 + random() % 4;
    for (std::size_t i = 0; i < more; ++i) input += corpus[random() % corpus.size()];
  }
  const std::size_t mutations = random() % 5;
  for (std::size_t i = 0; i < mutations; ++i) mutate(input, corpus, random);
  return input;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR [INPUTS [SEED]]\n", argv[0]);
    return 2;
  }
  const std::vector<std::string> corpus = readCorpus(argv[1]);
  if (corpus.empty()) {
    std::fprintf(stderr, "%s: no corpus files\n", argv[1]);
    return 2;
  }
  const long inputs = argc > 2 ? std::atol(argv[2]) : 10000;
  std::mt19937 random(argc > 3 ? static_cast<unsigned>(std::atol(argv[3])) : 20240611u);
  std::size_t bytes = 0;
  for (const std::string& file : corpus) {  // every seed as it is first
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(file.data()), file.size());
  }
  for (long i = 0; i < inputs; ++i) {
    const std::string input = nextInput(corpus, random);
    bytes += input.size();
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size());
  }
  std::printf("%zu corpus files and %ld inputs (%zu bytes): every check held\n", corpus.size(), inputs, bytes);
  return 0;
}
