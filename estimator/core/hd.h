#pragma once
// CRIT_HD marks the pure per-element functions of core/: __host__ __device__ under nvcc, plain
// inline otherwise, so that the CPU build needs no CUDA (DESIGN.md "One algorithm description").
#if defined(__CUDACC__)
#define CRIT_HD __host__ __device__ inline
#else
#define CRIT_HD inline
#endif
