// Runs the fuzz target without libFuzzer, on a seeded stream of inputs: random bytes, and valid
// messages glued together and mutated (bytes flipped, inserted, dropped, chunks repeated, lines
// cut). Deterministic, so a failure reproduces; arguments: [INPUTS [SEED]].
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

// Valid pieces of both framings; the first byte of an input selects the codec parameters.
const std::vector<std::string>& validPieces() {
  static const std::vector<std::string> pieces = {
      "PING\r\n",
      "STATUS\n",
      "TRIGGER\r\n",
      "TRIGGER,bolt_m8\r\n",
      "NEXT\r\n",
      "FAILED\r\n",
      "FAILED,0042\r\n",
      "MODEL,3\r\n",
      "model , Flange \r\n",
      "\r\n",
      "FOO,1,2\r\n",
      std::string("\0\0\0\1\xff\xff\xff\xff", 8),
      std::string("\0\0\0\3\0\0\0\5", 8),
      std::string("\4\0\0\0\0\0\0\0", 8),
      std::string("\6\0\0\0\x2a\0\0\0", 8),
      "NEXT,0,2,17,1,100.00,-200.00,300.50,1.00000,0.00000,0.00000,0.00000\r\n",
      "NEXT,0,100.00,-200.00,300.50,90.00000,0.00000,0.00000\r\n",
      "PING,0\r\n",
      "STATUS,0,1,2,3\r\n",
      "UNKNOWN,7\r\n",
      "NEXT,10\r\n",
      "POSE,600.00,0.00,400.00,1.00000,0.00000,0.00000,0.00000\r\n",
      "POSE,600,-12.5,400,180,0,-90\r\n",
      "pose , 1e3 , 0 , 0 , 0.5 , 0.5 , 0.5 , 0.5\r\n",
      "POSE,1,2,3\r\n",
      "POSE,nan,0,0,0,0,0\r\n",
      "POSE,0,3,12\r\n",
      "POSE,14,3,12\r\n",
      std::string("\0\0\0\7\0\0\x27\x10\xff\xff\xb1\xe0\0\0\x75\x62\0\0\x27\x10", 20) + std::string(12, '\0'),
      std::string("\7\0\0\0\x60\xea\0\0\0\0\0\0\x40\x9c\0\0\x20\xbf\x02\0", 20) + std::string(12, '\0')};
  return pieces;
}

std::string randomBytes(std::mt19937& random, std::size_t size) {
  std::string bytes(size, '\0');
  for (char& c : bytes) c = static_cast<char>(random());
  return bytes;
}

void mutate(std::string& input, std::mt19937& random) {
  if (input.empty()) return;
  const std::size_t at = random() % input.size();
  switch (random() % 6) {
    case 0: input[at] = static_cast<char>(random()); break;
    case 1: input.insert(at, 1, static_cast<char>(random())); break;
    case 2: input.erase(at, 1 + random() % 8); break;
    case 3: input.insert(at, input.substr(at, 1 + random() % 40)); break;
    case 4: input.insert(at, 1, '\n'); break;
    default: input.insert(at, std::string(random() % 300, static_cast<char>('A' + random() % 26)));
  }
}

std::string nextInput(std::mt19937& random) {
  std::string input(1, static_cast<char>(random()));  // the codec parameters
  if (random() % 4 == 0) return input + randomBytes(random, random() % 200);
  const std::vector<std::string>& pieces = validPieces();
  const std::size_t count = 1 + random() % 6;
  for (std::size_t i = 0; i < count; ++i) input += pieces[random() % pieces.size()];
  const std::size_t mutations = random() % 4;
  for (std::size_t i = 0; i < mutations; ++i) mutate(input, random);
  return input;
}

}  // namespace

int main(int argc, char** argv) {
  const long inputs = argc > 1 ? std::atol(argv[1]) : 50000;
  std::mt19937 random(argc > 2 ? static_cast<unsigned>(std::atol(argv[2])) : 20240611u);
  std::size_t bytes = 0;
  for (long i = 0; i < inputs; ++i) {
    const std::string input = nextInput(random);
    bytes += input.size();
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size());
  }
  std::printf("%ld inputs, %zu bytes: every invariant held\n", inputs, bytes);
  return 0;
}
