#include "irradiance/gpu/compute_program.h"

#include <GLES3/gl31.h>

#include <fmt/format.h>

namespace vs11::irradiance::gpu {

unsigned LinkComputeProgram(const std::string& source, std::string& error) {
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  char log[2048] = {};
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    error = fmt::format("compute shader does not compile: {}", log);
    glDeleteShader(shader);
    return 0;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return program;
  glGetProgramInfoLog(program, sizeof log, nullptr, log);
  error = fmt::format("compute program does not link: {}", log);
  glDeleteProgram(program);
  return 0;
}

}  // namespace vs11::irradiance::gpu
