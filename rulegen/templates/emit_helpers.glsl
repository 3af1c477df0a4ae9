// Helpers of the generated GLSL besides the support functions.
float bl_nan() { return uintBitsToFloat(0x7fc00000u); }
float bl_pi() { return 3.14159265358979; }
float bl_series_reach() { return 0.35; }  // see emit_helpers.hpp
