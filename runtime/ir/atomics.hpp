// The atomic functions the runtime knows: the generated registry's catalog, in its order.
#pragma once

#include <string>

namespace bl::ir {

int atomic_index(const std::string& name);  // -1 when unknown
const char* atomic_name(int index);
int atomic_count();
// Closed bounds of f's range from the catalog (may be infinite).
void atomic_range(int index, double* lo, double* hi);
// f takes only the values 0 and 1 (step, square, pulse30), so f^2 = f: E[f^2] = E[f] under any
// distribution, and the variance is m (1 - m) without smoothing f^2.
bool atomic_indicator(int index);
double plain_atomic(int index, double x);  // f(x) itself (the catalog definition, generated)
float plain_atomic(int index, float x);
// The float plain function itself, for evaluators that resolve calls once (throws on a bad index).
using PlainFloatFn = float (*)(float);
PlainFloatFn plain_atomic_fn(int index);

}  // namespace bl::ir
