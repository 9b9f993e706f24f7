"""clothref's Python side: read traces into numpy, and the plots behind `clothref plot`.

Modules:
  trace      streaming reader: a header dict and (steps, particles, 3) arrays per body
  energy     masses, springs and energies of a trace (kinetic, spring, gravitational)
  plot       `python3 -m clothref.plot {trace,sweep,stability}`: the charts (matplotlib)
"""
