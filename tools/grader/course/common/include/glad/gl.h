// Stand-in for the course's <glad/gl.h>: the GL types, constants and the six GL calls a student's
// cloth.cpp and sphere.cpp make, as no-ops. Nothing is drawn; the grader runs headless.
#pragma once
#include <stdint.h>

typedef unsigned int GLenum;
typedef unsigned int GLuint;
typedef int GLint;
typedef int GLsizei;
typedef float GLfloat;
typedef double GLdouble;
typedef unsigned char GLboolean;
typedef unsigned int GLbitfield;
typedef char GLchar;
typedef void GLvoid;
typedef long GLsizeiptr;
typedef long GLintptr;

// Integer constant expressions: the constexpr Buffer::getType() overrides return them.
#define GL_FALSE 0
#define GL_TRUE 1
#define GL_POINTS 0x0000
#define GL_LINES 0x0001
#define GL_TRIANGLES 0x0004
#define GL_UNSIGNED_INT 0x1405
#define GL_FLOAT 0x1406
#define GL_ARRAY_BUFFER 0x8892
#define GL_ELEMENT_ARRAY_BUFFER 0x8893
#define GL_UNIFORM_BUFFER 0x8A11
#define GL_STATIC_DRAW 0x88E4
#define GL_DYNAMIC_DRAW 0x88E8

// No-op GL entry points (defined in framework.cpp).
void glDrawElements(GLenum mode, GLsizei count, GLenum type, const void* indices);
void glDrawArrays(GLenum mode, GLint first, GLsizei count);
void glBindVertexArray(GLuint array);
void glBindBuffer(GLenum target, GLuint buffer);
void glVertexAttribDivisor(GLuint index, GLuint divisor);
void glDrawElementsInstanced(GLenum mode, GLsizei count, GLenum type, const void* indices,
                             GLsizei instancecount);
