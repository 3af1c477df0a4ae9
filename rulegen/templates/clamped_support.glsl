// Runtime support of the clamped-domain rules (float); needs bandlimit.glsl before it.
