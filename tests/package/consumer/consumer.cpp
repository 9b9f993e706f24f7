// Writes the trace of `spring`, explicit Euler, 50 steps, to stdout through the installed library:
// the package test compares it with the installed CLI's trace of the same run, byte for byte.
#include <iostream>

#include "clothref/record/record.h"
#include "clothref/scene/scene.h"

int main() {
  const clothref::Scene scene = clothref::loadScene("spring");
  clothref::TraceSettings settings;
  settings.dt = scene.dt;
  settings.steps = 50;
  settings.stride = 10;
  clothref::writeTrace(scene, settings, std::cout);
  return std::cout.good() ? 0 : 1;
}
