// The sse4 mesh traversal kernel (4-wide nodes); built with its own -march (src/CMakeLists.txt).
#define GLINT_KERNEL_ISA sse4
#define GLINT_KERNEL_WIDTH 4
#include "glint/accel/mesh_bvh_kernels.inl"
