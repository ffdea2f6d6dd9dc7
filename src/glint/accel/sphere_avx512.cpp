// The avx512 sphere-set kernel (16-wide); built with its own -march (src/CMakeLists.txt).
#define GLINT_KERNEL_ISA avx512
#define GLINT_KERNEL_WIDTH 16
#include "glint/accel/sphere_kernels.inl"
