// Writes the trace of `spring`, explicit Euler, 50 steps, to stdout through the installed library
// and its one include (clothref/clothref.h): the package test compares it with the installed
// CLI's trace of the same run, byte for byte. Before that it reads the trace back (TraceReader,
// which links zlib through the pkg-config file) and steps a world to the same final state hash.
#include <iostream>
#include <sstream>

#include "clothref/clothref.h"

int main() {
  const clothref::Scene scene = clothref::loadScene("spring");
  clothref::TraceSettings settings;
  settings.dt = scene.dt;
  settings.steps = 50;
  settings.stride = 10;
  std::ostringstream trace;
  const clothref::TraceSummary summary = clothref::writeTrace(scene, settings, trace);

  std::istringstream in(trace.str());
  clothref::TraceReader reader(in, "consumer trace");
  int steps = 0;
  while (reader.next()) ++steps;
  auto world = clothref::makeWorld<float>(scene, clothref::Method::Explicit);
  for (int k = 0; k < settings.steps; ++k) clothref::step(world);
  if (steps != 6 || clothref::stateHash(world) != summary.final_hash) {
    std::cerr << "consumer: " << steps << " step lines read back, hash "
              << clothref::hashToHex(clothref::stateHash(world)) << " stepped, "
              << clothref::hashToHex(summary.final_hash) << " traced\n";
    return 1;
  }
  std::cout << trace.str();
  return std::cout.good() ? 0 : 1;
}
