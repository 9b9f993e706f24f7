// first draft, does not compile
#include "cloth.h"
void Cloth::computeSpringForce() { oops }
