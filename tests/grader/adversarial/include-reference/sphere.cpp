#include "@SOURCE_DIR@/tools/grader/reference/2022/sphere.cpp"
