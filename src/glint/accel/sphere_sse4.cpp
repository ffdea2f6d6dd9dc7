// The sse4 sphere-set kernel (4-wide); built with its own -march (src/CMakeLists.txt).
#define GLINT_KERNEL_ISA sse4
#define GLINT_KERNEL_WIDTH 4
#include "glint/accel/sphere_kernels.inl"
