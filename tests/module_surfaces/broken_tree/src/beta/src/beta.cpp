// Module beta uses alpha's one public header.
#include "binpick/alpha/used.hpp"

int beta() { return used(); }
