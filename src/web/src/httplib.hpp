#pragma once
// cpp-httplib without the `_res` macro of <resolv.h> (which it includes): Eigen names parameters
// `_res`, and the macro would turn them into function calls in every header included after it.
#include <httplib.h>
#undef _res
