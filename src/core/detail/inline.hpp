// Forced inlining for the few small functions of the query hot paths that GCC's heuristics
// leave out of line (measured: a call per support point or simplex case).
#pragma once

#if defined(__GNUC__)
#define HULLCHECK_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define HULLCHECK_ALWAYS_INLINE inline
#endif
