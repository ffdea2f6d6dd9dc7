// The avx512 mesh traversal kernel (8-wide nodes); built with its own -march (src/CMakeLists.txt).
#define GLINT_KERNEL_ISA avx512
#define GLINT_KERNEL_WIDTH 8
#include "glint/accel/mesh_bvh_kernels.inl"
