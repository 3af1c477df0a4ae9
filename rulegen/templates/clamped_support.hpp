// Runtime support of the clamped-domain rules (generated/bandlimit/rules_clamped.hpp), copied
// verbatim by `rulegen emit`.
#pragma once

#include <cmath>
#include <limits>

#include "emit_helpers.hpp"
#include "support.hpp"
