// The one source of a precompiled-header target (cmake/PrecompiledHeaders.cmake): CMake compiles
// the headers beside it; the object itself is empty and linked into nothing.
