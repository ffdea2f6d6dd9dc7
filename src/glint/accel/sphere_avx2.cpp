// The avx2 sphere-set kernel (8-wide); built with its own -march (src/CMakeLists.txt).
#define GLINT_KERNEL_ISA avx2
#define GLINT_KERNEL_WIDTH 8
#include "glint/accel/sphere_kernels.inl"
