// Stand-in for the course's vertexarray.h: a GL vertex array object that does nothing.
#pragma once
#include <glad/gl.h>

#include "utils.h"

class VertexArray {
 public:
  MOVE_ONLY(VertexArray)
  VertexArray();
  ~VertexArray();
  void enable(int index) const;
  void bind() const;
  // stride and offset count floats, as in the course.
  void setAttributePointer(int index, int size, int stride, int offset) const;

 private:
  // The course's handle, which its GL calls use; nothing here reads it (clang: unused field).
  [[maybe_unused]] GLuint handle;
};
