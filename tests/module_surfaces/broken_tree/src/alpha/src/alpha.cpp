// Module alpha includes its own headers: that does not make them public.
#include "binpick/alpha/unused.hpp"
#include "binpick/alpha/used.hpp"

int used() { return unused(); }
